# What accuracy costs in time: a study target (DESIGN.md, accuracy and cost).


rule accuracy_hertz:
    """Load and contact-radius error against wall time and dofs (report 6.1)."""
    output:
        data=f"{RESULTS}/accuracy/hertz.nc",
        figure=report(
            f"{RESULTS}/accuracy/hertz.png", category="accuracy", caption="../report/accuracy.rst"
        ),
    log:
        f"{RESULTS}/accuracy/logs/hertz.log",
    params:
        study=config.get("accuracy_study", {}),
    script:
        "../scripts/accuracy_hertz.py"


def _accuracy_scene_runs():
    """(scene, preset) of every run the scene accuracy study compares."""
    study = config.get("accuracy_scenes", {})
    return [
        (name, preset) for name in study.get("scenes", []) for preset in study.get("presets", [])
    ]


rule accuracy_scenes:
    """Deviation of pressure and contact area from the finest preset against CPU time, per scene
    (issue #6). Not in `rule all` (it runs the scenes at `fine`): snakemake --cores 2 accuracy_scenes
    """
    input:
        [f"{RESULTS}/{name}@{preset}/interface.nc" for name, preset in _accuracy_scene_runs()],
    output:
        data=f"{RESULTS}/accuracy/scenes.nc",
        figure=report(
            f"{RESULTS}/accuracy/scenes.png",
            category="accuracy",
            caption="../report/accuracy_scenes.rst",
        ),
    log:
        f"{RESULTS}/accuracy/logs/scenes.log",
    params:
        study=config.get("accuracy_scenes", {}),
        runs=_accuracy_scene_runs(),
    script:
        "../scripts/accuracy_scenes.py"
