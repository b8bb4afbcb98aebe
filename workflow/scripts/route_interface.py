"""interface.nc of a route beyond independent asperities (interacting, Persson, boundary elements)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.topography import read_measurement
from asperity.stages import routes as stage

with job_log(snakemake.log[0], "route interface") as log:
    p, i = snakemake.params, snakemake.input
    data = read_measurement(i.map, **stage.reading(p.surface, p.units))
    z = stage.prepared_roughness(data.heights, data.spacing, p.surface, p.units, defined=data.defined)
    log.info("map %s: %s points, read by %s; route %s", i.map, z.shape, data.reader, p.route["kind"])
    asperities = read_dataset(i.asperities) if "asperities" in i.keys() else None
    ds = stage.route_interface(z, *data.spacing, read_dataset(i.surface), p.route, p.material,
                               p.homogenization, p.units, p.validity, asperities=asperities,
                               effects=p.effects or ())
    write_dataset(ds, snakemake.output[0], scene=p.scene, title=f"interface by route {p.route['kind']}",
                  config={"route": p.route, "surface": p.surface, "material": p.material,
                          "homogenization": p.homogenization, "validity": p.validity,
                          "effects": p.effects,
                          "units": p.units}, version=p.version)
