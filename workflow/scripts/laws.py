"""laws.nc: analytic laws fitted to the loading curve (report section 10)."""

from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import friction

with job_log(snakemake.log[0], "laws") as log:
    p, i = snakemake.params, snakemake.input
    ds = friction.laws_dataset(read_dataset(i.interface), p.laws, p.units)
    for law in ds["law"].values:
        est = ds["estimate"].sel(law=law)
        log.info("%s: %s; R^2 %.6f", law, ", ".join(
            f"{name} = {float(v):.6g} +- {float(s):.2g}" for name, v, s in
            zip(ds["parameter"].values, est.values, ds["standard_error"].sel(law=law).values)
            if v == v), float(ds["r_squared"].sel(law=law)))
    write_dataset(ds, snakemake.output[0], scene=p.scene, title="analytic interface laws (section 10)",
                  config={"laws": p.laws, "units": p.units}, version=p.version)
