"""figures/reference.png from reference.nc and comparison.nc."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import reference as stage

with job_log(snakemake.log[0], "reference figure"):
    i, p = snakemake.input, snakemake.params
    fig = stage.reference_figure(read_dataset(i.reference), read_dataset(i.comparison), p.units)
    save_figure(fig, snakemake.output[0], version=p.version)
