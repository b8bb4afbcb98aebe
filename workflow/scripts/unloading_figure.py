"""figures/unloading.png from unloading.nc (Figs. 8.26, 8.27)."""

from asperity import plots
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "unloading figure"):
    fig = plots.unloading_figure(read_dataset(snakemake.input.unloading),
                                 length_unit=snakemake.params.units["length"])
    save_figure(fig, snakemake.output[0])
