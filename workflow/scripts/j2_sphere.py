"""results/studies/j2_sphere.nc and its figure: the J2 sphere beside its models."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study J2 sphere"):
    p = snakemake.params
    ds = studies.j2_sphere_dataset(p.study)
    write_dataset(ds, snakemake.output.data, scene="studies",
                  title="the J2 sphere beside Kogut and Etsion's fits and the hardness-limited boundary elements",
                  config={"j2_sphere": p.study}, version=p.version)
    save_figure(studies.j2_sphere_figure(ds), snakemake.output.figure, version=p.version)
