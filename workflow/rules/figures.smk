# Figures drawn from the netCDF files only (asperity.plots).


def compared(wildcards, name):
    """The `name` result files of the scenes this scene compares with."""
    return [
        f"{RESULTS}/{other}/{name}" for other in SCENES[wildcards.scene].get("compare_with", [])
    ]


def interface_figure_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {
        "interface": f"{out}/interface.nc",
        "surface": f"{out}/surface.nc",
        "others": compared(wildcards, "interface.nc"),
    }
    if SCENES[wildcards.scene].get("verification"):
        inputs["verification"] = f"{out}/verification.nc"
    return inputs


def surface_figure_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {"surface": f"{out}/surface.nc"}
    if surface_kind(wildcards.scene) in ("profile", "map"):
        inputs.update(surface_inputs(wildcards))
    gen = generated(wildcards.scene)
    if gen and gen.get("convergence_spacings"):
        inputs["convergence"] = f"{out}/convergence.nc"
    return inputs


rule surface_figure:
    input:
        unpack(surface_figure_inputs),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/surface.png",
            category="{scene}",
            caption="../report/surface.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/surface_figure.log",
    params:
        kind=lambda w: surface_kind(w.scene),
        units=scene_part("units"),
    script:
        "../scripts/surface_figure.py"


rule expectation_figure:
    input:
        surface=f"{RESULTS}/{{scene}}/surface.nc",
        expectation=f"{RESULTS}/{{scene}}/expectation.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/expectation.png",
            category="{scene}",
            caption="../report/expectation.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/expectation_figure.log",
    params:
        population=scene_part("population", {}),
    script:
        "../scripts/expectation_figure.py"


rule interface_figure:
    input:
        unpack(interface_figure_inputs),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/interface.png",
            category="{scene}",
            caption="../report/interface.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/interface_figure.log",
    params:
        units=scene_part("units"),
        compare_with=scene_part("compare_with", []),
    script:
        "../scripts/interface_figure.py"


rule adhesion_figure:
    """With and without adhesion (report 7.3, Figs. 7.6 to 7.9): scenes with the effect."""
    input:
        interface=f"{RESULTS}/{{scene}}/interface.nc",
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
        others=lambda w: compared(w, "interface.nc"),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/adhesion.png",
            category="{scene}",
            caption="../report/adhesion.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/adhesion_figure.log",
    params:
        units=scene_part("units"),
        compare_with=scene_part("compare_with", []),
    script:
        "../scripts/adhesion_figure.py"


rule asperities_figure:
    input:
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
        others=lambda w: compared(w, "asperities.nc"),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/asperities.png",
            category="{scene}",
            caption="../report/asperities.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/asperities_figure.log",
    params:
        units=scene_part("units"),
        compare_with=scene_part("compare_with", []),
    script:
        "../scripts/asperities_figure.py"


rule verification_figure:
    input:
        verification=f"{RESULTS}/{{scene}}/verification.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/verification.png",
            category="{scene}",
            caption="../report/verification.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/verification_figure.log",
    script:
        "../scripts/verification_figure.py"


rule unloading_figure:
    input:
        unloading=f"{RESULTS}/{{scene}}/unloading.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/unloading.png",
            category="{scene}",
            caption="../report/unloading.rst",
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/unloading_figure.log",
    params:
        units=scene_part("units"),
    script:
        "../scripts/unloading_figure.py"
