"""plan.nc: the asperity samples the scene needs."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import population

with job_log(snakemake.log[0], "plan"):
    p = snakemake.params
    plan = population.plan_dataset(read_dataset(snakemake.input.surface), p.population, p.asperity,
                                   p.material, p.effects, p.units, p.accuracy, p.adhesion)
    write_dataset(plan, snakemake.output[0], scene=p.scene, title="asperity samples",
                  config={"population": p.population, "asperity": p.asperity, "material": p.material,
                          "effects": p.effects, "units": p.units, "accuracy": p.accuracy,
                          **({"adhesion": p.adhesion} if p.adhesion else {})},
                  version=p.version)
