"""figures/laws.png from laws.nc."""

from asperity.plots import friction as plots_friction
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "laws figure"):
    i, p = snakemake.input, snakemake.params
    fig = plots_friction.laws_figure(read_dataset(i.laws), pressure_unit=p.units.get("pressure", "Pa"),
                                     length_unit=p.units["length"])
    save_figure(fig, snakemake.output[0])
