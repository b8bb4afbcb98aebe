"""results/accuracy/scenes.nc and its figure: what accuracy costs for a whole scene."""

from asperity.io.figures import save_figure
from asperity.io.joblog import job_log
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.stages import accuracy

with job_log(snakemake.log[0], "accuracy study of the scenes") as log:
    s = snakemake.params.study
    runs = snakemake.params.runs  # (scene, preset) of each input, in input order
    interfaces = {(scene, preset): read_dataset(path)
                  for (scene, preset), path in zip(runs, snakemake.input)}
    ds = accuracy.scenes_accuracy_dataset(interfaces, s)
    for scene in ds["scene"].values:
        for preset in ds["preset"].values:
            d = ds.sel(scene=scene, preset=preset)
            log.info("%s@%s: %d FE jobs, %.1f s CPU; deviation pressure %s, area %s; over the "
                     "valid separations %s, %s (loading, unloading)",
                     scene, preset, d["fe_jobs"], d["fe_cpu_time"],
                     d["deviation"].sel(quantity="nominal_pressure").values,
                     d["deviation"].sel(quantity="contact_area_ratio").values,
                     d["valid_deviation"].sel(quantity="nominal_pressure").values,
                     d["valid_deviation"].sel(quantity="contact_area_ratio").values)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title="what accuracy costs for a whole scene: deviation from the finest preset "
                        "against CPU time", config={"accuracy_scenes": s},
                  version=snakemake.params.version)
    save_figure(accuracy.scenes_accuracy_figure(read_dataset(snakemake.output.data)),
                snakemake.output.figure, version=snakemake.params.version)
