# The studies that are no scene (asperity.stages.studies): the report's single-asperity
# studies, and tables gathered over several scenes; each a target of its own, not in
# `rule all`.


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


rule route_errors:
    """Every route's error against the boundary elements on each map of table `table` of
    config `route_errors` (issue #48), from the reference scenes' comparisons.  Not in `rule
    all` (minutes at draft): snakemake --cores 2 results/studies/route_errors_maps.nc
    """
    input:
        unpack(route_error_files),
    output:
        data=f"{RESULTS}/studies/route_errors_{{table}}.nc",
        figure=report(
            f"{RESULTS}/studies/route_errors_{{table}}.png",
            category="studies",
            caption="../report/route_errors.rst",
            labels={"study": "routes against the boundary elements", "figure": "{table}"},
        ),
    log:
        f"{RESULTS}/studies/logs/route_errors_{{table}}.log",
    conda:
        ENV
    params:
        version=code_version("route_errors"),
        study=config["route_errors"],
    script:
        "../scripts/route_errors.py"


rule scale_study:
    """The lateral scale of the asperities against what it changes (issue #48, item 1):
    summits, the boundary elements' resolution and the routes' errors at each scale of
    config `scale_study`, on each of its scenes' maps.  Not in `rule all` (minutes):
    snakemake --cores 2 results/studies/scale_study.nc
    """
    input:
        unpack(scale_study_files),
    output:
        data=f"{RESULTS}/studies/scale_study.nc",
        figure=report(
            f"{RESULTS}/studies/scale_study.png",
            category="studies",
            caption="../report/scale_study.rst",
            labels={"study": "lateral scale of the asperities", "figure": "scale study"},
        ),
    log:
        f"{RESULTS}/studies/logs/scale_study.log",
    conda:
        ENV
    params:
        version=code_version("scale_study"),
        study=config["scale_study"],
        scenes=scale_study_scenes,
    script:
        "../scripts/scale_study.py"


rule j2_sphere:
    """The J2 sphere of the reference scenes' aluminum beside Kogut and Etsion's fits and
    the boundary elements limited by the hardness, at each preset of config `j2_sphere`.
    Not in `rule all` (minutes): snakemake --cores 2 results/studies/j2_sphere.nc
    """
    output:
        data=f"{RESULTS}/studies/j2_sphere.nc",
        figure=report(
            f"{RESULTS}/studies/j2_sphere.png",
            category="studies",
            caption="../report/j2_sphere.rst",
            labels={"study": "J2 sphere", "figure": "against its models"},
        ),
    log:
        f"{RESULTS}/studies/logs/j2_sphere.log",
    conda:
        ENV
    params:
        version=code_version("j2_sphere"),
        study=config["j2_sphere"],
    script:
        "../scripts/j2_sphere.py"


rule validity_summary:
    """Where each scene of config `validity_summary` holds, from its interface.nc: valid
    separations, the limit that fails, hardness and plasticity index, the load beyond the
    FE jobs' range.  Not in `rule all`; after a default run it only reads:
    snakemake --cores 2 results/studies/validity_summary.nc
    """
    input:
        unpack(scene_files("validity_summary", ("interface", "surface"))),
    output:
        data=f"{RESULTS}/studies/validity_summary.nc",
    log:
        f"{RESULTS}/studies/logs/validity_summary.log",
    conda:
        ENV
    params:
        version=code_version("validity_summary"),
        study=config["validity_summary"],
    script:
        "../scripts/validity_summary.py"


rule friction_report:
    """The shear part of the friction coefficient of each scene of config `friction_report`
    against the report's (9.1, Fig. 9.2).  Not in `rule all`; after a default run it only
    reads: snakemake --cores 2 results/studies/friction_report.nc
    """
    input:
        unpack(scene_files("friction_report", ("friction", "interface"))),
    output:
        data=f"{RESULTS}/studies/friction_report.nc",
    log:
        f"{RESULTS}/studies/logs/friction_report.log",
    conda:
        ENV
    params:
        version=code_version("friction_report"),
        study=config["friction_report"],
        scenes=friction_report_scenes,
    script:
        "../scripts/friction_report.py"


rule adhesion_report:
    """An adhesive scene beside its elastic twin (config `adhesion_report`; report 7.3,
    9.1).  Not in `rule all`; after a default run it only reads:
    snakemake --cores 2 results/studies/adhesion_report.nc
    """
    input:
        asperities=f"{RESULTS}/{config['adhesion_report']['scene']}/asperities.nc",
        interface=f"{RESULTS}/{config['adhesion_report']['scene']}/interface.nc",
        friction=f"{RESULTS}/{config['adhesion_report']['scene']}/friction.nc",
        surface=f"{RESULTS}/{config['adhesion_report']['scene']}/surface.nc",
        twin_interface=f"{RESULTS}/{config['adhesion_report']['twin']}/interface.nc",
        twin_friction=f"{RESULTS}/{config['adhesion_report']['twin']}/friction.nc",
        twin_surface=f"{RESULTS}/{config['adhesion_report']['twin']}/surface.nc",
    output:
        data=f"{RESULTS}/studies/adhesion_report.nc",
    log:
        f"{RESULTS}/studies/logs/adhesion_report.log",
    conda:
        ENV
    params:
        version=code_version("adhesion_report"),
        study=config["adhesion_report"],
    script:
        "../scripts/adhesion_report.py"


rule plane_strain_table:
    """The plane-strain scenes of config `plane_strain_table` side by side at each of its
    presets (report 6.3.2, 6.3.3).  Not in `rule all` (a minute):
    snakemake --cores 2 results/studies/plane_strain_table.nc
    """
    input:
        unpack(plane_strain_table_files),
    output:
        data=f"{RESULTS}/studies/plane_strain_table.nc",
    log:
        f"{RESULTS}/studies/logs/plane_strain_table.log",
    conda:
        ENV
    params:
        version=code_version("plane_strain_table"),
        study=config["plane_strain_table"],
    script:
        "../scripts/plane_strain_table.py"
