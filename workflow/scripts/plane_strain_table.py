"""results/studies/plane_strain_table.nc: the plane-strain scenes side by side."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import studies

with job_log(snakemake.log[0], "study plane-strain table"):
    p = snakemake.params
    ds = studies.plane_strain_table_dataset(dict(snakemake.input.items()))
    write_dataset(ds, snakemake.output.data, scene="studies", title="the plane-strain scenes side by side",
                  config={"plane_strain_table": p.study}, version=p.version)
