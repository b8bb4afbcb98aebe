"""figures/asperities.png: single-asperity responses (and those of compared scenes)."""

from asperity import plots
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "asperities figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    fig = plots.asperities_figure(read_dataset(i.asperities), others, length_unit=p.units["length"])
    save_figure(fig, snakemake.output[0])
