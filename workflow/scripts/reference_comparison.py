"""comparison.nc: each statistical route's error against the boundary-element reference."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import reference as stage

with job_log(snakemake.log[0], "statistical routes against the reference"):
    p, i = snakemake.params, snakemake.input
    interfaces = {route: read_dataset(path) for route, path in zip(p.routes, i.interfaces)}
    ds = stage.comparison_dataset(read_dataset(i.reference), interfaces, p.reference["agreement"])
    write_dataset(ds, snakemake.output[0], scene=p.scene,
                  title="statistical routes against the boundary-element reference",
                  config={"routes": p.route_config, "reference": p.reference}, version=p.version)
