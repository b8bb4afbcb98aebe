"""results/<scene>/plane_strain.nc: a plane-strain asperity pressed by the flat (report 6.3.2,
6.3.3)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.stages import plane_strain

p = snakemake.params
scene = {"units": p.units, "plane_strain": p.plane_strain, "material": p.material,
         "effects": p.effects}
with job_log(snakemake.log[0], f"plane-strain asperity of {p.scene}") as log:
    ds = plane_strain.plane_strain_dataset(p.scene, scene, p.accuracy, progress=log.info)
    ds.attrs["report"] = p.report
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=p.title,
                  config={**scene, "accuracy": p.accuracy}, version=p.version)
