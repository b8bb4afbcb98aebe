# Stage 5: expectation over the asperity population (report 2.5) -> interface.nc


rule expectation:
    """Expectation of a constant over the peak density: the check of report 2.6.2."""
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/expectation.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/expectation.log",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        asperity=scene_part("asperity", {}),
        homogenization=scene_part("homogenization", {}),
        units=scene_part("units"),
    script:
        "../scripts/expectation.py"


def unloads(name):
    return "unloading" in SCENES[name].get("effects", [])


rule unloading:
    """The blended family of unloading paths of every asperity (report 8.3)."""
    input:
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
    output:
        f"{RESULTS}/{{scene}}/unloading.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/unloading.log",
    params:
        scene=lambda w: w.scene,
    script:
        "../scripts/unloading.py"


def interface_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {
        "surface": f"{out}/surface.nc",
        "plan": f"{out}/plan.nc",
        "asperities": f"{out}/asperities.nc",
    }
    if unloads(wildcards.scene):
        inputs["unloading"] = f"{out}/unloading.nc"
    return inputs


rule interface:
    """Nominal pressure, real contact area, stiffness versus separation (and branch)."""
    input:
        unpack(interface_inputs),
    output:
        f"{RESULTS}/{{scene}}/interface.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/interface.log",
    params:
        scene=lambda w: w.scene,
        population=scene_part("population", {}),
        homogenization=scene_part("homogenization", {}),
        units=scene_part("units"),
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
    log:
        f"{RESULTS}/{{scene}}/logs/verification.log",
    params:
        scene=lambda w: w.scene,
        verification=scene_part("verification"),
        single_asperity=scene_part("single_asperity"),
        material=scene_part("material", {}),
        units=scene_part("units"),
    script:
        "../scripts/verification.py"
