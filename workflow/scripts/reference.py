"""reference.nc: the boundary-element contact of the scene's map, elastic and at the hardness."""

from asperity.io import inputs
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import reference as stage

with job_log(snakemake.log[0], "boundary-element reference") as log:
    p, i = snakemake.params, snakemake.input
    z, dx, dy = inputs.read_map(i.map, spacing=p.spacing, length_unit=p.units["length"])
    log.info("map %s: %s points", i.map, z.shape)
    ds = stage.reference_dataset(z, dx, dy, read_dataset(i.surface), p.material, p.reference, p.units)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="boundary-element reference",
                  config={"material": p.material, "reference": p.reference, "units": p.units})
