# Stage 3-4: the asperity population (report 2.4) and the response of each
# sample. The plan depends on the surface statistics (the effective support of
# the peak density), hence a checkpoint.


checkpoint plan:
    """The asperity samples to run: heights, curvatures, interference grid, keys."""
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/plan.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/plan.log",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        asperity=scene_part("asperity", {}),
        material=scene_part("material", {}),
        effects=scene_part("effects", []),
        adhesion=scene_part("adhesion", {}),
        units=scene_part("units"),
        accuracy=accuracy_of,
    script:
        "../scripts/plan.py"


SAMPLE_SPECS = {}  # key -> the JSON spec of its job, from the plans read so far


def _register_specs(plan):
    for key, spec in zip(plan["key"].values, plan["spec"].values):
        SAMPLE_SPECS.setdefault(str(key), str(spec))


def sample_files(wildcards):
    """The per-sample job outputs the plan asks for (none for analytic asperities).
    Samples live in one folder for all scenes: a key is the hash of what its job
    depends on, so scenes (and presets) that need the same asperity share it."""
    from asperity.population.plan import job_keys
    from asperity.io.netcdf import read_dataset

    plan = read_dataset(checkpoints.plan.get(scene=wildcards.scene).output[0])
    _register_specs(plan)
    return [f"{RESULTS}/samples/{key}.nc" for key in job_keys(plan)]


def sample_spec(wildcards):
    """The spec of sample `key`: from the plans already read, else from every plan on disk
    (a job run on its own, e.g. by a cluster executor)."""
    from asperity.io.netcdf import read_dataset

    if wildcards.key not in SAMPLE_SPECS:
        for plan_file in sorted(Path(RESULTS).glob("*/plan.nc")):
            _register_specs(read_dataset(plan_file))
    if wildcards.key not in SAMPLE_SPECS:
        raise WorkflowError(
            f"sample {wildcards.key}: in no plan under {RESULTS}/*/plan.nc; "
            "samples are made for a scene (build its plan first)"
        )
    return SAMPLE_SPECS[wildcards.key]


rule sample:
    """One asperity sample: its response over the interference range of its spec."""
    output:
        f"{RESULTS}/samples/{{key}}.nc",
    log:
        f"{RESULTS}/samples/logs/{{key}}.log",
    # here, not as a global block: a global wildcard_constraints in an included file shifts
    # the source Snakemake records for this rule, and every edit of any rules file then
    # reran every FE sample ("code has changed")
    wildcard_constraints:
        key="[0-9a-f]{12}",
    params:
        key=lambda w: w.key,
        spec=sample_spec,
    script:
        "../scripts/sample.py"


rule asperities:
    """Responses of all samples gathered on (height, curvature, interference)."""
    input:
        plan=f"{RESULTS}/{{scene}}/plan.nc",
        samples=sample_files,
    output:
        f"{RESULTS}/{{scene}}/asperities.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/asperities.log",
    params:
        scene=lambda w: w.scene,
        asperity=scene_part("asperity", {}),
        material=scene_part("material", {}),
        units=scene_part("units"),
    script:
        "../scripts/asperities.py"
