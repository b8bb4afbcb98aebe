"""figures/interface.png from interface.nc (and verification.nc, compared scenes)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "interface figure"):
    i, p = snakemake.input, snakemake.params
    ver = read_dataset(i.verification) if "verification" in i.keys() else None
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    fig = figures.interface_figure(read_dataset(i.interface), p.units, ver, others)
    save_figure(fig, snakemake.output[0], version=p.version)
