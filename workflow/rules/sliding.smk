# One 3-D asperity pressed and slid by a rigid flat (report 9.2, Figs. 9.4 and 9.5).


rule sliding:
    """Normal and tangential force histories, the deformed section y = 0 and where the
    largest deformation sits (a scene's `sliding` section, at the global accuracy preset)."""
    input:
        made("sliding.nc"),
    output:
        f"{RESULTS}/{{scene}}/sliding.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/sliding.log",
    conda:
        ENV
    params:
        version=code_version("sliding"),
        scene=lambda w: w.scene,
        title=scene_part("title"),
        report=scene_part("report"),
        units=scene_part("units"),
        sliding=scene_part("sliding"),
        accuracy=accuracy_of,
    script:
        "../scripts/sliding.py"


rule sliding_figure:
    """Fig. 9.4 (forces versus time) and Fig. 9.5 (deformed section, horizontal displacement)."""
    input:
        made("figures/sliding.png"),
        sliding=f"{RESULTS}/{{scene}}/sliding.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/sliding.png",
            category="{scene}",
            caption="../report/sliding.rst",
            labels={"scene": "{scene}", "figure": "pressed and slid"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/sliding_figure.log",
    conda:
        ENV
    params:
        version=code_version("sliding_figure"),
        units=scene_part("units"),
    script:
        "../scripts/sliding_figure.py"
