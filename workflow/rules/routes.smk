# The routes beyond independent asperities: interacting asperities, Persson's theory, the
# boundary elements (a scene's `route` section; asperity.stages.routes) -> interface.nc,
# in the contract of every interface.nc. A reference scene's routes with a `route`
# section run here as the scenes <scene>+<route>.


ruleorder: route_interface > interface


rule route_interface:
    """The interface law of the scene's map by its route: depends on the map, its
    preparation (form, filter, lateral scale), the material, the route and the separations."""
    input:
        unpack(route_inputs),
    output:
        f"{RESULTS}/{{scene}}/interface.nc",
    log:
        f"{RESULTS}/{{scene}}/logs/route_interface.log",
    wildcard_constraints:
        # a route scene, at the run's preset or its own (@preset); none: never
        scene="(" + ("|".join(re.escape(n) for n in ROUTE_SCENES) or "(?!)") + r")(@[a-z]+)?",
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
        effects=scene_part("effects"),
        units=scene_part("units"),
    script:
        "../scripts/route_interface.py"
