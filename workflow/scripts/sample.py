"""samples/<key>.nc: the response of one asperity sample."""

from asperity import stages
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.joblog import job_log

with job_log(snakemake.log[0], f"sample {snakemake.params.key}"):
    p = snakemake.params
    ds = stages.sample_dataset(read_dataset(snakemake.input.plan), p.key, p.asperity,
                               p.material, p.units, p.accuracy, p.effects)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=f"asperity sample {p.key}",
                  config={"asperity": p.asperity, "material": p.material, "effects": p.effects,
                          "units": p.units, "accuracy": p.accuracy})
