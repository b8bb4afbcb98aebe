"""figures/adhesion.png: with and without adhesion (report 7.3, Figs. 7.6-7.9)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "adhesion figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    fig = figures.adhesion_figure(read_dataset(i.interface), read_dataset(i.asperities), p.units,
                                  others)
    save_figure(fig, snakemake.output[0], version=p.version)
