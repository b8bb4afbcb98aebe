"""Write the synthetic height map of a scene as .npy."""

from asperity.stages import surface
from asperity.io.writers import write_map
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "synthetic map"):
    write_map(snakemake.output[0], surface.synthetic_map(snakemake.params.generate))
