"""figures/uniaxial.png: the uniaxial tests, from uniaxial.nc only."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import uniaxial

with job_log(snakemake.log[0], "uniaxial figure"):
    save_figure(uniaxial.uniaxial_figure(read_dataset(snakemake.input.uniaxial)), snakemake.output[0],
                version=snakemake.params.version)
