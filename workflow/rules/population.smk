# Stage 3-4: the asperity population (report 2.4) and the response of each
# sample. The plan depends on the surface statistics (the effective support of
# the peak density), hence a checkpoint.


checkpoint plan:
    """The asperity samples to run: heights, curvatures, interference grid, keys."""
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/plan.nc",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        asperity=scene_part("asperity", {}),
        material=scene_part("material", {}),
        effects=scene_part("effects", []),
        units=scene_part("units"),
        accuracy=config["accuracy"],
    log:
        f"{RESULTS}/{{scene}}/logs/plan.log",
    script:
        "../scripts/plan.py"


def sample_files(wildcards):
    """The per-sample job outputs the plan asks for (none for analytic asperities)."""
    from asperity.plan import job_keys
    from asperity.io.netcdf import read_dataset

    plan_file = checkpoints.plan.get(scene=wildcards.scene).output[0]
    keys = job_keys(read_dataset(plan_file))
    return [f"{RESULTS}/{wildcards.scene}/samples/{key}.nc" for key in keys]


rule sample:
    """One asperity sample: its response to the plan's interference levels."""
    input:
        plan=f"{RESULTS}/{{scene}}/plan.nc",
    output:
        f"{RESULTS}/{{scene}}/samples/{{key}}.nc",
    params:
        scene=lambda w: w.scene,
        key=lambda w: w.key,
        asperity=scene_part("asperity", {}),
        material=scene_part("material", {}),
        effects=scene_part("effects", []),
        units=scene_part("units"),
        accuracy=config["accuracy"],
    log:
        f"{RESULTS}/{{scene}}/logs/samples/{{key}}.log",
    script:
        "../scripts/sample.py"


rule asperities:
    """Responses of all samples gathered on (height, curvature, interference)."""
    input:
        plan=f"{RESULTS}/{{scene}}/plan.nc",
        samples=sample_files,
    output:
        f"{RESULTS}/{{scene}}/asperities.nc",
    params:
        scene=lambda w: w.scene,
        asperity=scene_part("asperity", {}),
        material=scene_part("material", {}),
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/asperities.log",
    script:
        "../scripts/asperities.py"
