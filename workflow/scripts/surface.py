"""surface.nc: statistics of the scene's profile, map, or given statistics."""

from pathlib import Path

from asperity.stages import surface
from asperity.io import inputs
from asperity.io.netcdf import write_dataset
from asperity.io.joblog import job_log

with job_log(snakemake.log[0], "surface statistics") as log:
    cfg, units = snakemake.params.surface, snakemake.params.units
    if "profile" in cfg:
        path = snakemake.input.data
        z, dx = inputs.read_profile(path, spacing=cfg["profile"].get("spacing"), length_unit=units["length"])
        log.info("profile %s: %d points, spacing %g m", path, z.size, dx)
        try:
            ds = surface.surface_from_profile(z, dx, cfg)
        except ValueError as err:
            raise inputs.InputError(path, str(err)) from err
    elif "profiles" in cfg:
        src = cfg["profiles"]
        if "generate" in src:
            folder = Path(snakemake.input.data)
            items = [(folder / surface.profile_file_name(d), d, None) for d in src["generate"]["directions"]]
        else:
            items = [(item["file"], item["direction"], item.get("spacing")) for item in src["files"]]
        profiles = []
        for path, direction, spacing in items:
            z, dx = inputs.read_profile(path, spacing=spacing, length_unit=units["length"])
            log.info("profile %s at %g deg: %d points, spacing %g m", path, direction, z.size, dx)
            profiles.append((z, dx))
        ds = surface.surface_from_profiles(profiles, [d for _, d, _ in items], cfg)
    elif "map" in cfg:
        path = snakemake.input.data
        spacing = cfg["map"].get("spacing", cfg["map"].get("generate", {}).get("spacing"))
        z, dx, dy = inputs.read_map(path, spacing=spacing, length_unit=units["length"])
        log.info("map %s: %s points", path, z.shape)
        try:
            ds = surface.surface_from_map(z, dx, dy, cfg)
        except ValueError as err:
            raise inputs.InputError(path, str(err)) from err
    else:
        ds = surface.surface_from_statistics(cfg, units)
    write_dataset(ds, snakemake.output[0], scene=snakemake.params.scene,
                  title="surface statistics", config={"surface": cfg, "units": units},
                  version=snakemake.params.version)
