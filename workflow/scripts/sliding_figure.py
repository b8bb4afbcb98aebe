"""figures/sliding.png: Figs. 9.4 and 9.5 of the report, from sliding.nc only."""

from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log
from asperity.plots.sliding import sliding_figure

with job_log(snakemake.log[0], "sliding figure"):
    units = snakemake.params.units
    save_figure(sliding_figure(read_dataset(snakemake.input.sliding), units["length"]),
                snakemake.output[0])
