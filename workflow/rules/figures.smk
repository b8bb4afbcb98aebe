# Figures drawn from the netCDF files only (asperity.plots).


rule surface_figure:
    input:
        made("figures/surface.png"),
        unpack(surface_figure_inputs),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/surface.png",
            category="{scene}",
            caption="../report/surface.rst",
            labels={"scene": "{scene}", "figure": "surface statistics"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/surface_figure.log",
    conda:
        ENV
    params:
        version=code_version("surface_figure"),
        kind=lambda w: surface_kind(w.scene),
        units=scene_part("units"),
    script:
        "../scripts/surface_figure.py"


rule expectation_figure:
    input:
        made("figures/expectation.png"),
        surface=f"{RESULTS}/{{scene}}/surface.nc",
        expectation=f"{RESULTS}/{{scene}}/expectation.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/expectation.png",
            category="{scene}",
            caption="../report/expectation.rst",
            labels={"scene": "{scene}", "figure": "expectation of a constant"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/expectation_figure.log",
    conda:
        ENV
    params:
        version=code_version("expectation_figure"),
        population=scene_part("population"),
        units=scene_part("units"),
    script:
        "../scripts/expectation_figure.py"


rule interface_figure:
    input:
        made("figures/interface.png"),
        unpack(interface_figure_inputs),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/interface.png",
            category="{scene}",
            caption="../report/interface.rst",
            labels={"scene": "{scene}", "figure": "interface"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/interface_figure.log",
    conda:
        ENV
    params:
        version=code_version("interface_figure"),
        units=scene_part("units"),
        compare_with=compare_with,
    script:
        "../scripts/interface_figure.py"


rule adhesion_figure:
    """With and without adhesion (report 7.3, Figs. 7.6 to 7.9): scenes with the effect."""
    input:
        made("figures/adhesion.png"),
        interface=f"{RESULTS}/{{scene}}/interface.nc",
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
        others=lambda w: compared(w, "interface.nc"),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/adhesion.png",
            category="{scene}",
            caption="../report/adhesion.rst",
            labels={"scene": "{scene}", "figure": "with and without adhesion"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/adhesion_figure.log",
    conda:
        ENV
    params:
        version=code_version("adhesion_figure"),
        units=scene_part("units"),
        compare_with=compare_with,
    script:
        "../scripts/adhesion_figure.py"


rule asperities_figure:
    input:
        made("figures/asperities.png"),
        asperities=f"{RESULTS}/{{scene}}/asperities.nc",
        others=lambda w: compared(w, "asperities.nc"),
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/asperities.png",
            category="{scene}",
            caption="../report/asperities.rst",
            labels={"scene": "{scene}", "figure": "asperity responses"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/asperities_figure.log",
    conda:
        ENV
    params:
        version=code_version("asperities_figure"),
        units=scene_part("units"),
        compare_with=compare_with,
    script:
        "../scripts/asperities_figure.py"


rule verification_figure:
    input:
        made("figures/verification.png"),
        verification=f"{RESULTS}/{{scene}}/verification.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/verification.png",
            category="{scene}",
            caption="../report/verification.rst",
            labels={"scene": "{scene}", "figure": "against Hertz"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/verification_figure.log",
    conda:
        ENV
    params:
        version=code_version("verification_figure"),
    script:
        "../scripts/verification_figure.py"


rule unloading_figure:
    input:
        made("figures/unloading.png"),
        unloading=f"{RESULTS}/{{scene}}/unloading.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/unloading.png",
            category="{scene}",
            caption="../report/unloading.rst",
            labels={"scene": "{scene}", "figure": "unloading paths"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/unloading_figure.log",
    conda:
        ENV
    params:
        version=code_version("unloading_figure"),
        units=scene_part("units"),
    script:
        "../scripts/unloading_figure.py"
