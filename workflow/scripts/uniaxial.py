"""results/<scene>/uniaxial.nc: the scene's uniaxial material-point tests."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import uniaxial

p = snakemake.params
with job_log(snakemake.log[0], f"uniaxial tests of {p.scene}") as log:
    ds = uniaxial.uniaxial_dataset(p.uniaxial, p.units)
    for name, steps, wall in zip(ds["test"].values, ds["steps"].values, ds["wall_time"].values):
        log.info("%s: %d steps, %.2f s", name, steps, wall)
    ds.attrs["report"] = p.report
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=p.title,
                  config={"units": p.units, "uniaxial": p.uniaxial}, version=p.version)
