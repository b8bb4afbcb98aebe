"""verification.nc: the homogenized interface beside its closed form."""

from asperity import stages
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.joblog import job_log

with job_log(snakemake.log[0], "verification") as log:
    p = snakemake.params
    ds = stages.verification_dataset(read_dataset(snakemake.input.surface),
                                     read_dataset(snakemake.input.interface), p.verification,
                                     p.material, p.units)
    log.info("largest relative errors: %s",
             {k: v for k, v in ds.attrs.items() if k.startswith("max_")})
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=f"verification: {p.verification}",
                  config={"verification": p.verification, "material": p.material, "units": p.units})
