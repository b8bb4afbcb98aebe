"""figures/friction.png from friction.nc (and the compared scenes' friction.nc)."""

from asperity.plots import friction as plots_friction
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "friction figure"):
    i, p = snakemake.input, snakemake.params
    others = {name: read_dataset(path) for name, path in zip(p.compare_with, i.others)}
    fig = plots_friction.friction_figure(read_dataset(i.friction), others,
                                         pressure_unit=p.units.get("pressure", "Pa"),
                                         length_unit=p.units["length"])
    save_figure(fig, snakemake.output[0])
