"""results/studies/route_errors_<table>.nc and its figure: every route on every map."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], f"study route errors ({snakemake.wildcards.table})"):
    p = snakemake.params
    ds = studies.route_errors_dataset(studies.files_by_scene(snakemake.input.items()))
    write_dataset(ds, snakemake.output.data, scene="studies",
                  title=f"every route's error against the boundary elements ({snakemake.wildcards.table})",
                  config={"route_errors": p.study}, version=p.version)
    save_figure(studies.route_errors_figure(ds), snakemake.output.figure, version=p.version)
