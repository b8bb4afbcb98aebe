"""results/studies/scale_study.nc and its figure: the lateral scale of the asperities."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study scale of the asperities"):
    p = snakemake.params
    ds = studies.scale_study_dataset(dict(snakemake.input.items()), p.scenes, p.study)
    write_dataset(ds, snakemake.output.data, scene="studies",
                  title="summits and the routes' errors against the lateral scale",
                  config={"scale_study": p.study, "scenes": p.scenes}, version=p.version)
    save_figure(studies.scale_study_figure(ds), snakemake.output.figure, version=p.version)
