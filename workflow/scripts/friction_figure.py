"""figures/friction.png: mu against pressure (report Figs. 9.1-9.3)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import friction

with job_log(snakemake.log[0], "friction figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    save_figure(friction.friction_figure(read_dataset(i.friction), p.units, others),
                snakemake.output[0], version=p.version)
