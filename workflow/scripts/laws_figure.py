"""figures/laws.png: the fitted laws beside the interface (report Fig. 10.1)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import friction

with job_log(snakemake.log[0], "laws figure"):
    save_figure(friction.laws_figure(read_dataset(snakemake.input.laws), snakemake.params.units),
                snakemake.output[0], version=snakemake.params.version)
