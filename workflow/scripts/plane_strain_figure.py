"""figures/plane_strain.png: Figs. 6.17 and 6.22 of the report, from plane_strain.nc only."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import plane_strain

with job_log(snakemake.log[0], "plane-strain figure"):
    save_figure(plane_strain.plane_strain_figure(read_dataset(snakemake.input.plane_strain),
                                                 snakemake.params.units),
                snakemake.output[0], version=snakemake.params.version)
