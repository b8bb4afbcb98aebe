"""unloading.nc: the blended family of unloading paths (report 8.3)."""

from asperity.stages import homogenize
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "unloading"):
    ds = homogenize.unloading_dataset(read_dataset(snakemake.input.asperities))
    write_dataset(ds, snakemake.output[0], scene=snakemake.params.scene,
                  title="blended unloading paths", config={}, version=snakemake.params.version)
