# The routes beyond independent asperities: interacting asperities, Persson's theory, the
# boundary elements (a scene's `route` section; asperity.stages.routes) -> interface.nc,
# in the contract of every interface.nc. A reference scene's routes with a `route`
# section run here as the scenes <scene>+<route>.

import re


def _route_scenes():
    """The scenes whose interface.nc comes from a route: the scene files with a `route`
    section, and the routes with one of the reference scenes (read at parse time, so
    that the rule below matches them alone; rule `interface` makes every other one)."""
    names = []
    for path in sorted(SCENE_DIR.glob("*.yaml")):
        try:
            definition = yaml.safe_load(path.read_text()) or {}
        except yaml.YAMLError:
            continue  # reported with its file and line where the scene is loaded
        if "route" in definition:
            names.append(path.stem)
        for name, part in (definition.get("routes") or {}).items():
            if isinstance(part, dict) and "route" in part:
                names.append(f"{path.stem}{ROUTE_SEPARATOR}{name}")
    return names


ROUTE_SCENES = _route_scenes()


def route_map(wildcards):
    return surface_inputs(wildcards)["data"]


ruleorder: route_interface > interface


rule route_interface:
    """The interface law of the scene's map by its route: depends on the map, its
    preparation (form, filter, lateral scale), the material, the route and the separations."""
    input:
        map=route_map,
        surface=f"{RESULTS}/{{scene}}/surface.nc",
    output:
        f"{RESULTS}/{{scene}}/interface.nc",
    wildcard_constraints:
        # a route scene, at the run's preset or its own (@preset); none: never
        scene="(" + ("|".join(re.escape(n) for n in ROUTE_SCENES) or "(?!)") + r")(@[a-z]+)?",
    log:
        f"{RESULTS}/{{scene}}/logs/route_interface.log",
    conda:
        ENV
    params:
        version=code_version("route_interface"),
        scene=lambda w: w.scene,
        route=scene_part("route"),
        surface=scene_part("surface"),
        material=scene_part("material"),
        homogenization=scene_part("homogenization"),
        validity=scene_part("validity"),
        units=scene_part("units"),
    script:
        "../scripts/route_interface.py"
