# The report's single-asperity studies that are no scene (asperity.stages.studies): each a
# target of its own, not in `rule all`.


rule adhesion_curves:
    """Report 7.3, Fig. 7.6: load-deflection curves of smooth elastic aluminum asperities
    with adhesion, approach and retraction, at each tip radius of config `adhesion_curves`.
    Not in `rule all` (about a minute at draft): snakemake --cores 2 adhesion_curves
    """
    output:
        data=f"{RESULTS}/studies/adhesion_curves.nc",
        figure=report(
            f"{RESULTS}/studies/adhesion_curves.png",
            category="studies",
            caption="../report/adhesion_curves.rst",
            labels={"study": "adhesion curves", "figure": "Fig. 7.6"},
        ),
    log:
        f"{RESULTS}/studies/logs/adhesion_curves.log",
    conda:
        ENV
    params:
        version=code_version("adhesion_curves"),
        study=config["adhesion_curves"],
    script:
        "../scripts/adhesion_curves.py"
