"""convergence.nc: sampled statistics of a synthetic series versus spacing."""

from asperity.stages import surface
from asperity.io.netcdf import write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "convergence"):
    gen, units = snakemake.params.generate, snakemake.params.units
    ds = surface.series_convergence(gen, units)
    write_dataset(ds, snakemake.output[0], scene=snakemake.params.scene,
                  title="profile statistics versus sampling interval",
                  config={"generate": gen, "units": units}, version=snakemake.params.version)
