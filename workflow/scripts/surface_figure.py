"""figures/surface.png from surface.nc (and the profile or map, convergence.nc)."""

from asperity.io import inputs
from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import figures

with job_log(snakemake.log[0], "surface figure"):
    i, p = snakemake.input, snakemake.params
    surface = read_dataset(i.surface)
    data = None
    if p.kind == "map":
        data, _, _ = inputs.read_map(i.data, spacing=figures.map_spacing(surface, p.units),
                                     length_unit=p.units["length"])
    elif p.kind == "profile":
        data = inputs.read_profile(i.data, spacing=None, length_unit=p.units["length"])
    conv = read_dataset(i.convergence) if "convergence" in i.keys() else None
    save_figure(figures.surface_figure(p.kind, surface, p.units, data, conv), snakemake.output[0],
                version=p.version)
