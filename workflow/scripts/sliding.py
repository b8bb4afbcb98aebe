"""results/<scene>/sliding.nc: one asperity pressed and slid by the flat (report 9.2)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import sliding

p = snakemake.params
with job_log(snakemake.log[0], f"sliding asperity of {p.scene}") as log:
    ds = sliding.sliding_dataset(p.scene, p.sliding, p.units, p.accuracy, progress=log.info)
    log.info("largest deformation %s (depth %.3g m below the flat)",
             ds.attrs["largest_deformation"], ds.attrs["largest_deformation_depth"])
    ds.attrs["report"] = p.report
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=p.title,
                  config={"units": p.units, "sliding": p.sliding, "accuracy": p.accuracy},
                  version=p.version)
