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
        [f"{scene_folder(name, preset)}/interface.nc" for name, preset in accuracy_scene_runs()],
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


rule accuracy_sliding:
    """Force histories of a sliding asperity at each preset against the next finer one's,
    with what each run costs.  Not in `rule all` (it runs the scene at `fine`):
    snakemake --cores 2 accuracy_sliding
    """
    input:
        unpack(accuracy_sliding_files),
    output:
        data=f"{RESULTS}/accuracy/sliding.nc",
        figure=report(
            f"{RESULTS}/accuracy/sliding.png",
            category="accuracy",
            caption="../report/accuracy_sliding.rst",
            labels={"study": "sliding asperity", "figure": "accuracy against cost"},
        ),
    log:
        f"{RESULTS}/accuracy/logs/sliding.log",
    conda:
        ENV
    params:
        version=code_version("accuracy_sliding"),
        study=config["accuracy_sliding"],
    script:
        "../scripts/accuracy_sliding.py"


rule accuracy_inelastic:
    """Every case of config `accuracy_inelastic`: an inelastic asperity's meshes and
    kinematics at each preset against a finer run.  Not in `rule all` (most of an hour):
    snakemake --cores 2 accuracy_inelastic
    """
    input:
        expand(
            f"{RESULTS}/accuracy/inelastic_{{case}}.nc",
            case=config["accuracy_inelastic"]["cases"],
        ),


rule accuracy_inelastic_case:
    """One case of config `accuracy_inelastic` (a J2 sphere, a viscoplastic hill, a coupled
    steel hill): each variant at each preset against the reference run, and its CPU time."""
    output:
        data=f"{RESULTS}/accuracy/inelastic_{{case}}.nc",
        figure=report(
            f"{RESULTS}/accuracy/inelastic_{{case}}.png",
            category="accuracy",
            caption="../report/accuracy_inelastic.rst",
            labels={"study": "inelastic asperity", "figure": "{case}"},
        ),
    log:
        f"{RESULTS}/accuracy/logs/inelastic_{{case}}.log",
    wildcard_constraints:
        case="j2_sphere|viscoplastic_hill|steel_hill",
    conda:
        ENV
    params:
        version=code_version("accuracy_inelastic_case"),
        study=config["accuracy_inelastic"],
        case=lambda wildcards: wildcards.case,
    script:
        "../scripts/accuracy_inelastic.py"
