"""figures/expectation.png: the peak density over the integration rectangle, and E(X)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "expectation figure"):
    i, p = snakemake.input, snakemake.params
    fig = figures.expectation_figure(read_dataset(i.surface), read_dataset(i.expectation), p.population,
                                     p.units)
    save_figure(fig, snakemake.output[0], version=p.version)
