"""results/studies/adhesion_report.nc: an adhesive scene beside its elastic twin."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study adhesion report"):
    p = snakemake.params
    ds = studies.adhesion_report_dataset(dict(snakemake.input.items()))
    write_dataset(ds, snakemake.output.data, scene="studies", title="an adhesive scene beside its elastic twin",
                  config={"adhesion_report": p.study}, version=p.version)
