"""friction.nc: static coefficient of friction of the interface (report 9.1)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import friction

with job_log(snakemake.log[0], "friction") as log:
    p, i = snakemake.params, snakemake.input
    ds = friction.friction_dataset(read_dataset(i.interface), read_dataset(i.surface), p.friction,
                                   p.material, p.units)
    mu_i = ds["mu_interlocking"]  # on dim direction where the scene gives one
    log.info("tau_s %.6g Pa (%s); mu_interlocking %s; mu from %.4g to %.4g",
             float(ds["junction_shear_strength"]), ds.attrs["junction_shear_strength_origin"],
             f"{float(mu_i):.4g}" if mu_i.ndim == 0 else f"{float(mu_i.min()):.4g} to {float(mu_i.max()):.4g}",
             float(ds["mu"].min()), float(ds["mu"].max()))
    if "direction_dependence" in ds.attrs:
        log.info("direction: %s; %s", ds.attrs["direction_dependence"], ds.attrs["lay"])
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="static coefficient of friction (9.1)",
                  config={"friction": p.friction, "material": p.material, "units": p.units},
                  version=p.version)
