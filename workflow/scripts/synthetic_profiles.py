"""Write the profiles of a synthetic anisotropic surface, one text file per direction."""

from pathlib import Path

from asperity.stages import surface
from asperity.io.writers import write_profile
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "synthetic profiles"):
    gen = snakemake.params.generate
    out = Path(snakemake.output[0])
    for direction, (x, z) in zip(gen["directions"], surface.synthetic_directional_profiles(gen)):
        write_profile(out / surface.profile_file_name(direction), x, z,
                      comment=f"direction {direction} deg of {gen} in {snakemake.params.units['length']}")
