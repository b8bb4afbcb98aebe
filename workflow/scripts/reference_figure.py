"""figures/reference.png from reference.nc and comparison.nc."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.plots.reference import reference_figure

with job_log(snakemake.log[0], "reference figure"):
    i, p = snakemake.input, snakemake.params
    fig = reference_figure(read_dataset(i.reference), read_dataset(i.comparison),
                           length_unit=p.units["length"], pressure_unit=p.units.get("pressure", "Pa"))
    save_figure(fig, snakemake.output[0])
