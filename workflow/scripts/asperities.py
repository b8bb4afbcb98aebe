"""asperities.nc: responses of all samples on (height, curvature, interference)."""

from asperity.stages import population
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "asperities"):
    p = snakemake.params
    samples = {path: read_dataset(path) for path in snakemake.input.samples}
    ds = population.asperities_dataset(read_dataset(snakemake.input.plan), p.asperity, p.material,
                                   p.units, samples)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="asperity responses",
                  config={"asperity": p.asperity, "material": p.material, "units": p.units})
