# Stage 5: expectation over the asperity population (report 2.5) -> interface.nc


rule expectation:
    """Expectation of a constant over the peak density: the check of report 2.6.2."""
    input:
        made("expectation.nc"),
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/expectation.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/expectation.log",
    conda:
        ENV
    params:
        version=code_version("expectation"),
        scene=lambda w: w.scene,
        population=scene_part("population"),
        asperity=scene_part("asperity"),
        homogenization=scene_part("homogenization"),
        units=scene_part("units"),
    script:
        "../scripts/expectation.py"


rule unloading:
    """The blended family of unloading paths of every asperity (report 8.3)."""
    input:
        made("unloading.nc"),
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
    output:
        f"{RESULTS}/{{scene}}/unloading.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/unloading.log",
    conda:
        ENV
    params:
        version=code_version("unloading"),
        scene=lambda w: w.scene,
    script:
        "../scripts/unloading.py"


rule interface:
    """Nominal pressure, real contact area, stiffness versus separation (and branch)."""
    input:
        made("interface.nc"),
        unpack(interface_inputs),
    output:
        f"{RESULTS}/{{scene}}/interface.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/interface.log",
    conda:
        ENV
    params:
        version=code_version("interface"),
        scene=lambda w: w.scene,
        population=scene_part("population"),
        homogenization=scene_part("homogenization"),
        units=scene_part("units"),
        material=scene_part("material"),
        effects=scene_part("effects"),
        validity=scene_part("validity"),
    script:
        "../scripts/interface.py"


rule verification:
    """A result against a closed form: one FE asperity against Hertz (6.1), or
    the homogenized interface against Greenwood-Williamson (7.1)."""
    input:
        made("verification.nc"),
        unpack(verification_inputs),
    output:
        f"{RESULTS}/{{scene}}/verification.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/verification.log",
    conda:
        ENV
    params:
        version=code_version("verification"),
        scene=lambda w: w.scene,
        verification=scene_part("verification"),
        single_asperity=scene_part("single_asperity"),
        material=scene_part("material"),
        units=scene_part("units"),
    script:
        "../scripts/verification.py"
