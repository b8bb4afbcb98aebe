"""surface.nc: statistics of the scene's profile, map, or given statistics."""

from pathlib import Path

from asperity.io.inputs import InputError
from asperity.io.joblog import job_log
from asperity.io.netcdf import write_dataset
from asperity.io.topography import read_measurement
from asperity.stages import surface

with job_log(snakemake.log[0], "surface statistics") as log:
    cfg, units = snakemake.params.surface, snakemake.params.units
    if "profile" in cfg or "map" in cfg:
        path = snakemake.input.data
        data = read_measurement(path, **surface.reading(cfg, units))
        log.info("%s %s: %s points, spacing %g m, read by %s", data.kind, path, data.heights.shape,
                 data.dx, data.reader)
        try:
            ds = surface.surface_from_data(data.heights, data.spacing, cfg, units, defined=data.defined,
                                           notes=data.notes)
        except ValueError as err:
            raise InputError(path, str(err)) from err
    elif "profiles" in cfg:
        folder = Path(snakemake.input.data) if "generate" in cfg["profiles"] else Path()
        profiles, directions = [], []
        for item in surface.profile_readings(cfg, units):
            path = folder / item["file"]
            data = read_measurement(path, "profile", unit=item["unit"], spacing=item["spacing"], key=item["key"])
            log.info("profile %s at %g deg: %d points, spacing %g m", path, item["direction"],
                     data.heights.size, data.dx)
            profiles.append((data.heights, data.dx))
            directions.append(item["direction"])
        ds = surface.surface_from_profiles(profiles, directions, cfg, units)
    else:
        ds = surface.surface_from_statistics(cfg, units)
    write_dataset(ds, snakemake.output[0], scene=snakemake.params.scene,
                  title="surface statistics", config={"surface": cfg, "units": units},
                  version=snakemake.params.version)
