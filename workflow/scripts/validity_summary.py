"""results/studies/validity_summary.nc: where each scene's interface law holds."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study validity summary"):
    p = snakemake.params
    ds = studies.validity_summary_dataset(studies.files_by_scene(snakemake.input.items()))
    write_dataset(ds, snakemake.output.data, scene="studies", title="where each scene's interface law holds",
                  config={"validity_summary": p.study}, version=p.version)
