# Stage 5: expectation over the asperity population (report 2.5) -> interface.nc


rule expectation:
    """Expectation of a constant over the peak density: the check of report 2.6.2."""
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/expectation.nc",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        asperity=scene_part("asperity", {}),
        homogenization=scene_part("homogenization", {}),
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/expectation.log",
    script:
        "../scripts/expectation.py"


rule interface:
    """Nominal pressure, real contact area, stiffness versus separation."""
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
        plan=f"{RESULTS}/{{scene}}/plan.nc",
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
    output:
        f"{RESULTS}/{{scene}}/interface.nc",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        homogenization=scene_part("homogenization", {}),
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/interface.log",
    script:
        "../scripts/interface.py"


def verification_inputs(wildcards):
    if "single_asperity" in SCENES[wildcards.scene]:
        return {}  # one asperity against Hertz: nothing upstream
    out = f"{RESULTS}/{wildcards.scene}"
    return {"surface": f"{out}/surface.nc", "interface": f"{out}/interface.nc"}


rule verification:
    """A result against a closed form: one FE asperity against Hertz (6.1), or
    the homogenized interface against Greenwood-Williamson (7.1)."""
    input:
        unpack(verification_inputs),
    output:
        f"{RESULTS}/{{scene}}/verification.nc",
    params:
        scene=lambda w: w.scene,
        verification=scene_part("verification"),
        single_asperity=scene_part("single_asperity"),
        material=scene_part("material", {}),
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/verification.log",
    script:
        "../scripts/verification.py"
