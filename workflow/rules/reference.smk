# The deterministic reference (scene deterministic_reference): the boundary-element
# contact of the scene's map, and the statistical routes' error against it. Each route
# is a scene of its own, <scene>+<route> (asperity.stages.reference.route_scene),
# through the usual surface -> plan -> samples -> interface rules.


rule reference:
    """Boundary-element contact of the map: depends on the map, the material and the
    solver settings only (a route or comparison change does not rerun it)."""
    input:
        map=reference_map,
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/reference.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/reference.log",
    conda:
        ENV
    params:
        version=code_version("reference"),
        scene=lambda w: w.scene,
        surface=scene_part("surface"),
        material=scene_part("material"),
        reference=scene_part("reference"),
        units=scene_part("units"),
    script:
        "../scripts/reference.py"


rule reference_comparison:
    """Each statistical route against the elastic boundary-element solution."""
    input:
        reference=f"{RESULTS}/{{scene}}/reference.nc",
        interfaces=route_interfaces,
    output:
        f"{RESULTS}/{{scene}}/comparison.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/reference_comparison.log",
    conda:
        ENV
    params:
        version=code_version("reference_comparison"),
        scene=lambda w: w.scene,
        routes=reference_routes,
        route_config=scene_part("routes"),
        reference=scene_part("reference"),
    script:
        "../scripts/reference_comparison.py"


rule reference_figure:
    input:
        reference=f"{RESULTS}/{{scene}}/reference.nc",
        comparison=f"{RESULTS}/{{scene}}/comparison.nc",
    output:
        report(
            f"{RESULTS}/{{scene}}/figures/reference.png",
            category="{scene}",
            caption="../report/reference.rst",
            labels={"scene": "{scene}", "figure": "statistical routes against boundary elements"},
        ),
    log:
        f"{RESULTS}/{{scene}}/logs/reference_figure.log",
    conda:
        ENV
    params:
        version=code_version("reference_figure"),
        units=scene_part("units"),
    script:
        "../scripts/reference_figure.py"
