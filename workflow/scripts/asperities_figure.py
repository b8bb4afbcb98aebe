"""figures/asperities.png from asperities.nc (and compared scenes' asperities)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "asperities figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    save_figure(figures.asperities_figure(read_dataset(i.asperities), p.units, others),
                snakemake.output[0], version=p.version)
