# What accuracy costs in time: a study target (DESIGN.md, accuracy and cost).


rule accuracy_hertz:
    """Load and contact-radius error against wall time and dofs (report 6.1)."""
    output:
        data=f"{RESULTS}/accuracy/hertz.nc",
        figure=report(
            f"{RESULTS}/accuracy/hertz.png",
            category="accuracy",
            caption="../report/accuracy.rst",
            labels={"study": "Hertz problem", "figure": "accuracy against cost"},
        ),
    log:
        f"{RESULTS}/accuracy/logs/hertz.log",
    conda:
        ENV
    params:
        version=code_version("accuracy_hertz"),
        study=config["accuracy_study"],
    script:
        "../scripts/accuracy_hertz.py"


rule accuracy_scenes:
    """Deviation of pressure and contact area from the finest preset against CPU time, per scene.
    Not in `rule all` (it runs the scenes at `fine`): snakemake --cores 2 accuracy_scenes
    """
    input:
        [f"{RESULTS}/{name}@{preset}/interface.nc" for name, preset in accuracy_scene_runs()],
    output:
        data=f"{RESULTS}/accuracy/scenes.nc",
        figure=report(
            f"{RESULTS}/accuracy/scenes.png",
            category="accuracy",
            caption="../report/accuracy_scenes.rst",
            labels={"study": "whole scenes", "figure": "accuracy against cost"},
        ),
    log:
        f"{RESULTS}/accuracy/logs/scenes.log",
    conda:
        ENV
    params:
        version=code_version("accuracy_scenes"),
        study=config["accuracy_scenes"],
        runs=accuracy_scene_runs(),
    script:
        "../scripts/accuracy_scenes.py"
