"""results/accuracy/scenes.nc and its figure: what accuracy costs for a whole scene (issue #6)."""

from asperity.io.figures import save_figure
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.io.joblog import job_log
from asperity.plots.accuracy_scenes import scene_accuracy_figure
from asperity.studies.scenes import scene_accuracy

with job_log(snakemake.log[0], "accuracy study of the scenes") as log:
    s = snakemake.params.study
    runs = snakemake.params.runs  # (scene, preset) of each input, in input order
    interfaces = {(scene, preset): read_dataset(path)
                  for (scene, preset), path in zip(runs, snakemake.input)}
    ds = scene_accuracy(interfaces, s["scenes"], s["presets"], reference=s.get("reference"),
                        threshold=s.get("threshold", 1e-3))
    for scene in ds["scene"].values:
        for preset in ds["preset"].values:
            d = ds.sel(scene=scene, preset=preset)
            log.info("%s@%s: %d FE jobs, %.1f s CPU; deviation pressure %s, area %s (loading, unloading)",
                     scene, preset, d["fe_jobs"], d["fe_cpu_time"],
                     d["deviation"].sel(quantity="nominal_pressure").values,
                     d["deviation"].sel(quantity="contact_area_ratio").values)
    write_dataset(ds, snakemake.output.data, scene="accuracy",
                  title="what accuracy costs for a whole scene: deviation from the finest preset "
                        "against CPU time", config={"accuracy_scenes": s})
    save_figure(scene_accuracy_figure(read_dataset(snakemake.output.data)), snakemake.output.figure)
