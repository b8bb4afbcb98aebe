"""results/studies/friction_report.nc: mu_shear against the report's."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study friction against the report"):
    p = snakemake.params
    ds = studies.friction_report_dataset(studies.files_by_scene(snakemake.input.items()), p.scenes)
    write_dataset(ds, snakemake.output.data, scene="studies",
                  title="the shear part of the friction coefficient against the report's",
                  config={"friction_report": p.study, "scenes": p.scenes}, version=p.version)
