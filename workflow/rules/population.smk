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
    # the plan and the FE samples first: the finite element jobs are a run's longest, and
    # started last they end it alone on one core
    priority: 10
    conda:
        ENV
    params:
        version=code_version("plan"),
        scene=lambda w: w.scene,
        population=scene_part("population"),
        asperity=scene_part("asperity"),
        material=scene_part("material"),
        effects=scene_part("effects"),
        adhesion=effect_section("adhesion"),
        units=scene_part("units"),
        accuracy=accuracy_of,
    script:
        "../scripts/plan.py"


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
    priority: 10
    conda:
        ENV
    params:
        version=sample_code_version,
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
    conda:
        ENV
    params:
        version=code_version("asperities"),
        scene=lambda w: w.scene,
    script:
        "../scripts/asperities.py"
