"""asperities.nc: responses of all samples on (height, curvature, interference)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, scene_config, write_dataset
from asperity.stages import population

with job_log(snakemake.log[0], "asperities"):
    p = snakemake.params
    plan = read_dataset(snakemake.input.plan)
    samples = {path: read_dataset(path) for path in snakemake.input.samples}
    ds = population.asperities_dataset(plan, samples)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="asperity responses",
                  config=scene_config(plan), version=p.version)
