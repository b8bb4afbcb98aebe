# Static friction (report 9.1) -> friction.nc, and analytic laws (section 10) -> laws.nc,
# with their figures. Only for scenes with a `friction:` or `laws:` section.


rule friction:
    """mu = tau_s A_c / F plus interlocking, on the loading branch (9.41)."""
    input:
        made("friction.nc"),
        interface=f"{RESULTS}/{{scene}}/interface.nc",
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/friction.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/friction.log",
    conda:
        ENV
    params:
        version=code_version("friction"),
        scene=lambda w: w.scene,
        friction=scene_part("friction"),
        material=scene_part("material"),
        units=scene_part("units"),
    script:
        "../scripts/friction.py"


rule laws:
    """Oden-Martins (10.42, 10.43) and exponential laws fitted to the loading curve."""
    input:
        made("laws.nc"),
        interface=f"{RESULTS}/{{scene}}/interface.nc",
    output:
        f"{RESULTS}/{{scene}}/laws.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/laws.log",
    conda:
        ENV
    params:
        version=code_version("laws"),
        scene=lambda w: w.scene,
        laws=scene_part("laws"),
        units=scene_part("units"),
    script:
        "../scripts/laws.py"


rule friction_figure:
    input:
        made("figures/friction.png"),
        friction=f"{RESULTS}/{{scene}}/friction.nc",
        others=lambda w: [f"{RESULTS}/{other}/friction.nc" for other in friction_compared(w)],
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/friction.png",
            category="{scene}",
            caption="../report/friction.rst",
            labels={"scene": "{scene}", "figure": "coefficient of friction"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/friction_figure.log",
    conda:
        ENV
    params:
        version=code_version("friction_figure"),
        units=scene_part("units"),
        compare_with=friction_compared,
    script:
        "../scripts/friction_figure.py"


rule laws_figure:
    input:
        made("figures/laws.png"),
        laws=f"{RESULTS}/{{scene}}/laws.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/laws.png",
            category="{scene}",
            caption="../report/laws.rst",
            labels={"scene": "{scene}", "figure": "fitted laws"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/laws_figure.log",
    conda:
        ENV
    params:
        version=code_version("laws_figure"),
        units=scene_part("units"),
    script:
        "../scripts/laws_figure.py"
