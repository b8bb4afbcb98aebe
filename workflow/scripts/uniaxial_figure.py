"""figures/uniaxial.png: the uniaxial tests, from uniaxial.nc only."""

from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset
from asperity.io.joblog import job_log
from asperity.plots.uniaxial import uniaxial_figure

with job_log(snakemake.log[0], "uniaxial figure"):
    save_figure(uniaxial_figure(read_dataset(snakemake.input.uniaxial)), snakemake.output[0])
