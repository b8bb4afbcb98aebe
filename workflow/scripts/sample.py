"""samples/<key>.nc: the response of one asperity sample (or the record of its failure)."""

import json

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import population

with job_log(snakemake.log[0], f"sample {snakemake.params.key}"):
    p = snakemake.params
    spec = json.loads(p.spec)
    ds = population.sample_dataset(spec, p.key)
    write_dataset(ds, snakemake.output[0], scene="shared by every scene whose plan holds the key",
                  title=f"asperity sample {p.key}", config={"spec": spec}, version=p.version)
