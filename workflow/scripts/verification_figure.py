"""figures/verification.png: one FE asperity against Hertz (report 6.1, Figs. 6.5, 6.6)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "verification figure"):
    save_figure(figures.verification_figure(read_dataset(snakemake.input.verification)),
                snakemake.output[0], version=snakemake.params.version)
