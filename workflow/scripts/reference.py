"""reference.nc: the boundary-element contact of the scene's map, elastic and at the hardness."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.topography import read_measurement
from asperity.stages import reference as stage

with job_log(snakemake.log[0], "boundary-element reference") as log:
    p, i = snakemake.params, snakemake.input
    data = read_measurement(i.map, **stage.reading(p.surface, p.units))
    z = stage.prepared_roughness(data.heights, data.spacing, p.surface, p.units, defined=data.defined)
    log.info("map %s: %s points, read by %s; form and filter of the scene removed", i.map, z.shape,
             data.reader)
    ds = stage.reference_dataset(z, *data.spacing, read_dataset(i.surface), p.material, p.reference,
                                 p.units)
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="boundary-element reference",
                  config={"material": p.material, "reference": p.reference, "surface": p.surface,
                          "units": p.units}, version=p.version)
