"""figures/expectation.png: density, support and integration rectangle."""

from asperity import plots, stages
from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset, scene_config
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "expectation figure"):
    surface, expectation = read_dataset(snakemake.input.surface), read_dataset(snakemake.input.expectation)
    z, kappa, f = stages.density_on_grid(surface, scene_config(expectation)["population"],
                                         expectation["rectangle"].values)
    save_figure(plots.expectation_figure(f, z, kappa, expectation), snakemake.output[0])
