"""expectation.nc: expectation of a constant over the peak density (2.6.2)."""

from asperity.stages import homogenize
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "expectation") as log:
    p = snakemake.params
    ds = homogenize.expectation_dataset(read_dataset(snakemake.input.surface), p.population,
                                    p.asperity, p.homogenization, p.units)
    log.info("integral %.6g, I %.6g, E %.15g, macroscopic %.6g", float(ds.integral),
             float(ds.normalization), float(ds.expectation), float(ds.macroscopic))
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="expectation of X",
                  config={"population": p.population, "asperity": p.asperity,
                          "homogenization": p.homogenization, "units": p.units},
                  version=p.version)
