# The deterministic reference (scene deterministic_reference): the boundary-element
# contact of the scene's map, and the statistical routes' error against it. Each route
# is a scene of its own, <scene>+<route> (asperity.stages.reference.route_scene),
# through the usual surface -> plan -> samples -> interface rules.

from asperity.stages.reference import ROUTE_SEPARATOR


def reference_routes(wildcards):
    return list(SCENES[wildcards.scene].get("routes") or {})


def route_interfaces(wildcards):
    """interface.nc of every route of the scene (at the scene's preset, if it has one)."""
    base, at, preset = wildcards.scene.partition("@")
    return [f"{RESULTS}/{base}{ROUTE_SEPARATOR}{route}{at}{preset}/interface.nc"
            for route in reference_routes(wildcards)]


rule reference:
    """Boundary-element contact of the map: depends on the map, the material and the
    solver settings only (a route or comparison change does not rerun it)."""
    input:
        map=lambda w: surface_inputs(w)["data"],
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/reference.nc",
    params:
        scene=lambda w: w.scene,
        surface=scene_part("surface"),
        material=scene_part("material"),
        reference=scene_part("reference"),
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/reference.log",
    script:
        "../scripts/reference.py"


rule reference_comparison:
    """Each statistical route against the elastic boundary-element solution."""
    input:
        reference=f"{RESULTS}/{{scene}}/reference.nc",
        interfaces=route_interfaces,
    output:
        f"{RESULTS}/{{scene}}/comparison.nc",
    params:
        scene=lambda w: w.scene,
        routes=reference_routes,
        route_config=scene_part("routes"),
        agreement=lambda w: SCENES[w.scene]["reference"].get("agreement", 0.25),
    log:
        f"{RESULTS}/{{scene}}/logs/reference_comparison.log",
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
        ),
    params:
        units=scene_part("units"),
    log:
        f"{RESULTS}/{{scene}}/logs/reference_figure.log",
    script:
        "../scripts/reference_figure.py"
