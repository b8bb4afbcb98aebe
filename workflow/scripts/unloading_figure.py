"""figures/unloading.png: the blended unloading family (report Figs. 8.26, 8.27)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "unloading figure"):
    save_figure(figures.unloading_figure(read_dataset(snakemake.input.unloading),
                                         snakemake.params.units), snakemake.output[0],
                version=snakemake.params.version)
