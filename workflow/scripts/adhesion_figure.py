"""figures/adhesion.png from interface.nc, asperities.nc and the compared scenes' interfaces."""

from asperity.plots import adhesion as plots_adhesion
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "adhesion figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    fig = plots_adhesion.adhesion_figure(read_dataset(i.interface), read_dataset(i.asperities),
                                         others, length_unit=p.units["length"],
                                         pressure_unit=p.units.get("pressure", "Pa"))
    save_figure(fig, snakemake.output[0])
