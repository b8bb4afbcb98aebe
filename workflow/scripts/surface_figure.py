"""figures/surface.png from surface.nc (and convergence.nc)."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "surface figure"):
    i, p = snakemake.input, snakemake.params
    conv = read_dataset(i.convergence) if "convergence" in i.keys() else None
    save_figure(figures.surface_figure(p.kind, read_dataset(i.surface), p.units, conv), snakemake.output[0],
                version=p.version)
