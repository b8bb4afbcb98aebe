"""Write the synthetic profile of a scene (report 2.6.1) as a text file."""

from asperity.stages import surface
from asperity.io.writers import write_profile
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "synthetic profile"):
    gen = snakemake.params.generate
    x, z = surface.synthetic_profile(gen)
    write_profile(
        snakemake.output[0], x, z,
        comment=f"synthetic profile {gen} in {snakemake.params.units['length']}",
    )
