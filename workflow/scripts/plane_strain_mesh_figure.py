"""figures/plane_strain_meshes.png: Figs. 6.15, 6.16 and 6.19-6.21 of the report, from
plane_strain.nc only."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset
from asperity.stages import plane_strain

with job_log(snakemake.log[0], "plane-strain mesh figure"):
    save_figure(plane_strain.plane_strain_mesh_figure(read_dataset(snakemake.input.plane_strain),
                                                      snakemake.params.units),
                snakemake.output[0], version=snakemake.params.version)
