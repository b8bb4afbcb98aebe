"""verification.nc: a result beside its closed form (Hertz, Greenwood-Williamson)."""

from asperity.stages import homogenize
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "verification") as log:
    p, i = snakemake.params, snakemake.input
    if p.single_asperity:
        ds = homogenize.hertz_verification_dataset(p.single_asperity, p.material, p.units)
    else:
        ds = homogenize.verification_dataset(read_dataset(i.surface), read_dataset(i.interface),
                                         p.verification, p.material, p.units)
    log.info("largest relative errors: %s", {k: v for k, v in ds.attrs.items() if k.startswith("max_")})
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=f"verification: {p.verification}",
                  config={"verification": p.verification, "single_asperity": p.single_asperity,
                          "material": p.material, "units": p.units}, version=p.version)
