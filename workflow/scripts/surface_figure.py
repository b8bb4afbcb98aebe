"""figures/surface.png from surface.nc (and the profile, convergence.nc)."""

import numpy as np

from asperity import plots
from asperity.io import inputs
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.joblog import job_log

with job_log(snakemake.log[0], "surface figure"):
    i, p = snakemake.input, snakemake.params
    profile = None
    if p.kind == "profile":
        z, dx = inputs.read_profile(i.data, spacing=None, length_unit=p.units["length"])
        profile = (dx * np.arange(z.size), z)
    conv = read_dataset(i.convergence) if "convergence" in i.keys() else None
    fig = plots.surface_figure(read_dataset(i.surface), profile, conv, length_unit=p.units["length"])
    save_figure(fig, snakemake.output[0])
