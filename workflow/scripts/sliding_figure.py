"""figures/sliding.png: Figs. 9.4 and 9.5 of the report, from sliding.nc only."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import sliding

with job_log(snakemake.log[0], "sliding figure"):
    save_figure(sliding.sliding_figure(read_dataset(snakemake.input.sliding), snakemake.params.units),
                snakemake.output[0], version=snakemake.params.version)
