"""Accuracy presets of the finite element models: the tables of each kind,
documented values, and `resolve(kind, accuracy)`.

Each preset sets the numerical parameters only; the model (geometry,
material, contact law) is the same, except that the cut-off distance of a
body of revolution is part of the approximation of the half space and
grows with the preset.

Accuracy on the Hertz problem of report 6.1 (paraboloid, R = 1, E = 1000,
nu = 0.3, w = 0.001 ... 0.02, five levels; docs: theory/single-asperity.md,
'Accuracy presets'):

    preset    dofs    |load error|   |radius error|
    draft     2 100   <= 0.4 %       <= 0.5 %
    standard  6 800   <= 0.12 %      <= 0.17 %
    fine     30 600   <= 0.03 %      <= 0.03 %

Keys
----
domain_factor
    cut-off radius L of the block / `Profile.length_scale` (footprint
    radius of the hill) for bodies of revolution.  Fixing u = 0 at L makes
    the body stiffer, by about 1.1 a / L relative in load on the Hertz
    problem (a the contact radius, measured by `asperity.studies.hertz`); at 300
    that is most of the 'standard' preset's 0.12 % load error there.
    Plane-strain sections use
    the fixed `PLANE_STRAIN_DOMAIN` instead (see below).
apex_fraction
    innermost ring radius of the initial mesh / the smallest contact radius
    estimate (the geometric intersection radius at the smallest interference).
growth, n_theta
    ring radius ratio and sectors per ring of the initial mesh: elements are
    about (growth - 1) times their distance from the apex.
sweeps
    maximum number of adaptive refinement sweeps.
theta
    marking threshold: refine elements whose indicator exceeds theta times
    the largest (`skfem.adaptive_theta`).
target_error
    stop refining once every level's estimated relative energy-norm error
    (ZZ) is below this.
adapt_levels
    at most this many interference levels (spread evenly in contact radius)
    drive the refinement of the shared mesh; all levels are solved on the
    final mesh.
tolerance
    Newton: relative residual ||R|| / ||f_contact|| to stop.
max_iterations, max_cuts
    Newton iterations before a step is cut in half; cuts per requested step.
exact_tolerance
    exact contact option: penetration / interference and relative force
    change between Uzawa updates to stop.
time_tolerance
    inelastic histories (`inelastic.solve_asperity_history`) of a
    rate-dependent material: bound of the time-integration error indicator
    of a step (nodal forces of the local error over the contact forces;
    local: the stiff flow relaxes most of it, the error of the results is
    far smaller).  What each preset's tolerance costs and how far its
    results are from tighter ones: docs, changelog, 'Inelastic histories
    and the material point'.
remesh
    inelastic histories: rebuild the mesh around the contact edge and the
    plastic zone as they move (`remesh`), instead of one mesh adapted once
    to elastic solutions up to the largest interference.  Off in every
    preset (what it costs and gains: docs, changelog, 'Meshes that follow
    the plastic contact').
remesh_band
    a new mesh resolves the contact edge from its current radius a to
    remesh_band x a (elastic solutions drive the refinement, as above),
    and refines the region the plastic zone can reach while its extent
    grows by (remesh_band - 1) x max(extent, a); beyond either, the mesh
    is rebuilt.
plastic_size
    largest element in the plastic zone of a new mesh / the contact radius.
edge_size
    inelastic histories on one mesh (``remesh`` off): None, or the largest
    element of the top surface / r_g over the radii the plastic contact edge
    sweeps, ``remesh.EDGE_BAND`` x r_g (r_g the geometric intersection
    radius at the largest interference), refined on top of the elastic
    adaptation, which resolves the elastic edges only.  Not read with
    ``remesh`` on (the meshes then follow the edge).  None at draft and
    standard, `EDGE_SIZE` at fine (`INELASTIC_ACCURACY`): on a J2 sphere
    0.02 at standard is sized to put standard's contact area within 1 % of
    fine's from a tenth of the largest interference on; on a rate-dependent
    body the time-error indicator grows as the surface is refined, so the
    band makes a viscoplastic hill take many more steps (docs: changelog,
    'Meshes that follow the plastic contact').  `EDGE_SIZE` holds the size
    of each preset, which a scene's ``asperity: {edge_band: true}`` sets,
    and which a scene's J2 jobs have at standard without the key
    (`asperity.population.kinds.inelastic.wants_band`: a J2 body's steps
    are not set by the time-error control).

Adhesive presets (`ADHESIVE_ACCURACY`, `adhesive.solve_asperity_adhesive`)
add to the elastic preset of the same name: the mesh of the adhesive band
(process_zone_elements, ring_elements, grading, max_band_facets,
follow_above: a band of more ring elements follows the contact, and
edge_band: a contact edge far inside the cohesive zone gets a band of its
own; False gives one band from the contact edge to the ring, the
alternative `benchmarks/adhesion_cost.py --bands` compares; follow_margin
and follow_margin_elements: a following band reaches the larger of
follow_margin x the radius its zone reaches and follow_margin_elements
ring elements beyond the zone on either side: 20 elements in every
preset; 0.15 x radius and 40 elements are the wider margins
`benchmarks/adhesion_cost.py --margins` compares), the
surface rule (gauss_points, subdivisions), the path (steps_per_d,
far_steps) and its step control (jump_tolerance, energy_tolerance,
min_step); the adhesive module docstring says what each does.  Sliding
presets (`SLIDING_ACCURACY`, `solid3d.solve_sliding`) are a table of their
own (comment at the table).  `resolve(kind, accuracy)` gives the preset of
each kind of model (`KINDS`).
"""

from __future__ import annotations

#: cut-off radius / extent of the hill for plane-strain sections.  In plane
#: strain the displacement of a loaded half plane grows like log(distance),
#: so there is no limit as L -> infinity: the block size is part of the
#: model (as the report's "section of a circle", 6.3.2), fixed here.
PLANE_STRAIN_DOMAIN = 10.0

ACCURACY: dict[str, dict] = {
    "draft": dict(
        domain_factor=100.0,
        apex_fraction=0.3,
        growth=1.4,
        n_theta=4,
        sweeps=2,
        theta=0.5,
        target_error=0.03,
        adapt_levels=3,
        tolerance=1e-6,
        max_iterations=40,
        max_cuts=8,
        exact_tolerance=1e-7,
        time_tolerance=0.1,
        remesh=False,
        remesh_band=1.5,
        plastic_size=0.5,
        edge_size=None,
    ),
    "standard": dict(
        domain_factor=300.0,
        apex_fraction=0.3,
        growth=1.3,
        n_theta=6,
        sweeps=4,
        theta=0.5,
        target_error=0.005,
        adapt_levels=20,
        tolerance=1e-8,
        max_iterations=40,
        max_cuts=8,
        exact_tolerance=1e-9,
        time_tolerance=0.6,
        remesh=False,
        remesh_band=2.0,
        plastic_size=0.4,
        edge_size=None,
    ),
    "fine": dict(
        domain_factor=1000.0,
        apex_fraction=0.2,
        growth=1.2,
        n_theta=8,
        sweeps=7,
        theta=0.4,
        target_error=0.002,
        adapt_levels=10,
        tolerance=1e-10,
        max_iterations=40,
        max_cuts=8,
        exact_tolerance=1e-11,
        time_tolerance=0.2,
        remesh=False,
        remesh_band=1.4,
        plastic_size=0.15,
        edge_size=None,
    ),
}


#: numerical parameters of the adhesive solver, on top of an FE preset (`base`)
ADHESIVE_ACCURACY: dict[str, dict] = {
    "draft": dict(base="draft", process_zone_elements=1.5, ring_elements=4.0, grading=0.5,
                  gauss_points=5, subdivisions=2, steps_per_d=3.0, far_steps=8,
                  jump_tolerance=0.25, energy_tolerance=0.03, min_step=2e-3,
                  max_band_facets=1500, follow_above=400, edge_band=True,
                  follow_margin=0.0, follow_margin_elements=20.0),
    "standard": dict(base="standard", process_zone_elements=3.0, ring_elements=8.0, grading=0.3,
                     gauss_points=5, subdivisions=2, steps_per_d=6.0, far_steps=16,
                     jump_tolerance=0.25, energy_tolerance=0.02, min_step=1e-3,
                     max_band_facets=3000, follow_above=800, edge_band=True,
                     follow_margin=0.0, follow_margin_elements=20.0),
    "fine": dict(base="fine", process_zone_elements=6.0, ring_elements=16.0, grading=0.2,
                 gauss_points=5, subdivisions=4, steps_per_d=10.0, far_steps=24,
                 jump_tolerance=0.25, energy_tolerance=0.01, min_step=5e-4,
                 max_band_facets=6000, follow_above=1600, edge_band=True,
                 follow_margin=0.0, follow_margin_elements=20.0),
}

#: ``edge_size`` at each preset where a scene asks for the band the plastic contact edge
#: sweeps (``asperity: {edge_band: true}``, and a J2 body at standard without the key),
#: sized to put standard's contact area on a J2 sphere within 1 % of fine's.  'fine' has
#: its band in every inelastic history (`INELASTIC_ACCURACY`)
EDGE_SIZE = {"draft": 0.04, "standard": 0.02, "fine": 0.0125}

#: the presets at which a scene's rate-independent (J2) body gets the band without the
#: scene's key (`asperity.population.kinds.inelastic.wants_band`; fine's inelastic preset
#: has it for every body): its steps are not set by the time-error control, whose
#: indicator grows as the surface is refined, so that on the band a viscoplastic hill
#: takes many more steps; draft stays a first look
RATE_INDEPENDENT_EDGE_BAND = ("standard",)

#: inelastic histories (`inelastic.solve_asperity_history`) on top of the preset of the
#: same name (`base`).  'fine', the reference, is meshed for a plastic contact: its one
#: mesh is adapted to the elastic solutions of the history's levels only as far as
#: standard's is (``sweeps``, ``target_error``), on its own finer rings, and refined
#: where the plastic contact edge goes (``edge_size``).  The elastic adaptation resolves
#: elastic contact edges, inside the plastic ones; sweeps beyond standard's would spend
#: most of the dofs at the small elastic contacts of the first levels, not where the
#: plastic edge goes (docs: changelog, 'Meshes that follow the plastic contact')
INELASTIC_ACCURACY: dict[str, dict] = {
    "draft": dict(base="draft"),
    "standard": dict(base="standard"),
    "fine": dict(base="fine", sweeps=ACCURACY["standard"]["sweeps"],
                 target_error=ACCURACY["standard"]["target_error"],
                 edge_size=EDGE_SIZE["fine"]),
}


#: accuracy presets of the sliding model: mesh sizes relative to the
#: contact radius estimate r (the geometric intersection radius at the
#: largest approach): the longest element edge ``tip_fraction`` r within
#: ``refine_fraction`` r of the apex, growing by ``grading`` per unit
#: distance, at most ``coarse_fraction`` x the footprint radius;
#: ``depth_grading`` None, the finest region is a ball about the apex, a
#: number, it is a disc on the surface and the edge grows by that per unit
#: depth (`half_model_mesh.MeshSpec`); time steps per segment of the motion (caps:
#: cuts may add steps); Newton tolerance; the largest change of the
#: equivalent inelastic strain in a step.
SLIDING_ACCURACY: dict[str, dict] = {
    "draft": dict(tip_fraction=1.0, refine_fraction=0.5, grading=0.7, coarse_fraction=0.5,
                  depth_grading=None, normal_steps=6, tangential_steps=12, tolerance=1e-6,
                  max_iterations=40, max_cuts=10, max_inelastic_step=0.3),
    # standard and fine resolve the contact surface: the contact on the facets' P2 nodes
    # grows a ring of nodes at a time, so the force histories converge with the
    # surface's node spacing, not with the dofs (docs: changelog, 'Sliding of one
    # asperity', 'The presets').  fine refines the mesh only; its time steps are standard's
    "standard": dict(tip_fraction=0.25, refine_fraction=0.8, grading=0.5, coarse_fraction=0.35,
                     depth_grading=1.0, normal_steps=16, tangential_steps=32, tolerance=1e-7,
                     max_iterations=40, max_cuts=10, max_inelastic_step=0.1),
    "fine": dict(tip_fraction=0.18, refine_fraction=0.8, grading=0.35, coarse_fraction=0.25,
                 depth_grading=0.7, normal_steps=16, tangential_steps=32, tolerance=1e-7,
                 max_iterations=40, max_cuts=10, max_inelastic_step=0.1),
}


#: the press of a 3-D elliptic paraboloid for the anisotropic route (the ``elliptic`` kind of
#: `asperity.population.kinds.elliptic`), on the sliding preset of the same name: the
#: interference levels of a job (each pressed from zero on its own mesh) and the steps to
#: each.  Its J2 body is loaded monotonically, but not proportionally: at draft (ratio 1/8,
#: 1 to 1000 times first yield) one step and two differ by up to 4 % in force (at 100
#: times), and two cost 10 % less CPU (fewer Newton iterations at the deepest level); at
#: standard four steps and sixteen through a geometric path agree within 2.1 %
PRESS_3D: dict[str, dict] = {"draft": dict(levels=4, normal_steps=2),
                             "standard": dict(levels=6, normal_steps=4),
                             "fine": dict(levels=9, normal_steps=8)}


#: the tables of each kind of model: the inelastic and the adhesive presets change
#: or add keys to the elastic preset of the same name (the inelastic histories read
#: ``time_tolerance`` and their meshing keys from the elastic tables)
KINDS = ("elastic", "inelastic", "adhesive", "sliding")


def preset(kind: str, name: str) -> dict:
    """The preset `name` of a kind of model (`KINDS`), a new dict."""
    table = {"elastic": ACCURACY, "inelastic": INELASTIC_ACCURACY,
             "adhesive": ADHESIVE_ACCURACY, "sliding": SLIDING_ACCURACY}.get(kind)
    if table is None:
        raise ValueError(f"unknown kind of model {kind!r}; known: {', '.join(KINDS)}")
    if name not in table:
        raise ValueError(f"unknown accuracy {name!r}; known: {', '.join(table)}")
    entry = dict(table[name])
    base = entry.pop("base", None)  # a table that changes or adds keys to an elastic preset
    return entry if base is None else {**ACCURACY[base], **entry}


def resolve(kind: str, accuracy: str | dict) -> dict:
    """The numerical parameters of a kind of model (`KINDS`): a preset by name,
    or a dict overriding 'standard' (or its 'base' key).  A resolved dict
    resolves to itself."""
    if isinstance(accuracy, str):
        return preset(kind, accuracy)
    extra = dict(accuracy)
    base = preset(kind, extra.pop("base", "standard"))
    unknown = set(extra) - set(base)
    if unknown:
        raise ValueError(f"unknown accuracy keys of the {kind} model: {sorted(unknown)}")
    base.update(extra)
    return base
