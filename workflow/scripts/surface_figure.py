"""figures/surface.png from surface.nc (and the profile or map, convergence.nc)."""

import numpy as np

from asperity import plots
from asperity.io import inputs
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log
from asperity.units import length_scale

with job_log(snakemake.log[0], "surface figure"):
    i, p = snakemake.input, snakemake.params
    surface = read_dataset(i.surface)
    if p.kind == "profiles":
        fig = plots.directional_figure(surface, length_unit=p.units["length"])
    elif p.kind == "map":
        unit = p.units["length"]
        spacing = float(surface["spacing_x"]) / length_scale(unit)  # back to the scene's unit
        z, _, _ = inputs.read_map(i.data, spacing=spacing, length_unit=unit)
        fig = plots.map_figure(z, surface, length_unit=p.units["length"])
    else:
        profile = None
        if p.kind == "profile":
            z, dx = inputs.read_profile(i.data, spacing=None, length_unit=p.units["length"])
            profile = (dx * np.arange(z.size), z)
        conv = read_dataset(i.convergence) if "convergence" in i.keys() else None
        fig = plots.surface_figure(surface, profile, conv, length_unit=p.units["length"])
    save_figure(fig, snakemake.output[0])
