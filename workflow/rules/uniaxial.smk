# Uniaxial material-point scenes (report 5, 6.3.1, 8.2.1) and what the
# accuracy of the Bodner-Partom integrators costs (results/accuracy/bodner_partom.nc).


rule uniaxial:
    """The tests of a scene's `uniaxial` section: one material point each, on dims (test, step)."""
    input:
        made("uniaxial.nc"),
    output:
        f"{RESULTS}/{{scene}}/uniaxial.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/uniaxial.log",
    conda:
        ENV
    params:
        version=code_version("uniaxial"),
        scene=lambda w: w.scene,
        title=scene_part("title"),
        report=scene_part("report"),
        units=scene_part("units"),
        uniaxial=scene_part("uniaxial"),
    script:
        "../scripts/uniaxial.py"


rule uniaxial_figure:
    """Panels like the report's Figs. 5.1-5.4, 6.14 and 8.13 (stress-strain, -time, strain-time)."""
    input:
        made("figures/uniaxial.png"),
        uniaxial=f"{RESULTS}/{{scene}}/uniaxial.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/uniaxial.png",
            category="{scene}",
            caption="../report/uniaxial.rst",
            labels={"scene": "{scene}", "figure": "uniaxial tests"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/uniaxial_figure.log",
    conda:
        ENV
    params:
        version=code_version("uniaxial_figure"),
    script:
        "../scripts/uniaxial_figure.py"


rule accuracy_bodner_partom:
    """Implicit against explicit integration: steps, wall time and end error per tolerance."""
    output:
        data=f"{RESULTS}/accuracy/bodner_partom.nc",
        figure=report(
            f"{RESULTS}/accuracy/bodner_partom.png",
            category="accuracy",
            caption="../report/accuracy_bodner_partom.rst",
            labels={"study": "Bodner-Partom integrators", "figure": "accuracy against cost"},
        ),
    log:
        f"{RESULTS}/accuracy/logs/bodner_partom.log",
    conda:
        ENV
    params:
        version=code_version("accuracy_bodner_partom"),
        study=config.get("accuracy_bodner_partom", {}),
    script:
        "../scripts/uniaxial_accuracy.py"
