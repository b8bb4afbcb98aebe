"""results/studies/validity_summary.nc: where each scene's interface law holds."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study validity summary"):
    p = snakemake.params
    files = {}
    for key, path in snakemake.input.items():  # <scene>__<file>
        scene, kind = key.split("__")
        files.setdefault(scene, {})[kind] = path
    ds = studies.validity_summary_dataset(files)
    write_dataset(ds, snakemake.output.data, scene="studies", title="where each scene's interface law holds",
                  config={"validity_summary": p.study}, version=p.version)
