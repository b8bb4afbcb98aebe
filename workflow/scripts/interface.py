"""interface.nc: the homogenized interface versus separation."""

from asperity.stages import homogenize
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "interface"):
    p, i = snakemake.params, snakemake.input
    ds = homogenize.interface_dataset(read_dataset(i.asperities), read_dataset(i.surface),
                                  read_dataset(i.plan), p.population, p.homogenization, p.units,
                                  read_dataset(i.unloading) if "unloading" in i.keys() else None,
                                  material_cfg=p.material, effects=p.effects,
                                  validity_cfg=p.validity)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="homogenized interface",
                  config={"population": p.population, "homogenization": p.homogenization,
                          "units": p.units, "material": p.material, "effects": p.effects,
                          "validity": p.validity}, version=p.version)
