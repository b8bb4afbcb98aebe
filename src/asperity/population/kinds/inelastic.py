"""The ``inelastic`` kind: the finite element asperity of a J2 or Bodner-Partom body
under the effect ``plasticity`` (report 3.2.2, 7.3, 7.4, 8.2), loaded and, with the
effect ``unloading``, unloaded from levels (8.3).

A job loads the flat at the scene's ``velocity`` (8.2.2; a rate-independent J2 body
answers the same at any rate, so its spec leaves the velocity out) to the top of its
range, or to its unloading level and back to zero force
(`asperity.fe.solve_asperity_history`). With unloading, every sample has one job per
level (`asperity.population.geometry.unloading_levels`), on one mesh adapted to the
asperity's whole range so that the loading branches of its levels coincide (the
corners of the blend, 8.3). Coupled cosine hills (2.5.1) are loaded only: one job per
sample, or per aspect of their family under ``scaling: self_similar`` (8.2.2). With the
effect ``finite_strain`` the jobs are in finite-strain kinematics (`asperity.fe.discretization.kinematics`);
the effect enters the spec with the others, so it reruns them.

The band the plastic contact edge sweeps (`edge_band_accuracy`: the spec's accuracy is
the preset with its ``edge_size``, the one mesh refined where the plastic contact edge
goes) is in fine's preset for every body, and the spec adds it at standard for a
rate-independent (J2) body (`wants_band`): on the J2 sphere of `accuracy_inelastic` it puts
standard's contact area within 1 % of fine's (3 % on the default mesh) for about twice
standard's CPU. A rate-dependent body has it at fine only: its steps are set by the
time-error control, whose indicator grows as the surface is refined, so the band takes
it many more steps (docs: changelog, "Meshes that follow the plastic contact"). Draft
stays a first look on the default mesh: the J2 cosine hill of
`tests/fe/test_self_similar.py` takes 4.6 times as long with draft's band. A scene's
``asperity: {edge_band: true}`` or ``false`` says which at every preset.
"""

from __future__ import annotations

import math
import time

import numpy as np

from asperity.population.geometry import job_range, sample_geometry, self_similar, spec_geometry
from asperity.population.geometry import unloading_levels
from asperity.population.kinds.base import FiniteElementKind
from asperity.scene import Material, build, kinematics

#: the first step of an inelastic history, as a fraction of the job's largest interference
FIRST_STEP = 1e-4
#: the levels added to the one mesh's adaptation for each decade its range reaches below
#: the default (`mesh_levels`)
LEVELS_PER_DECADE = 2


def mesh_levels(top: float, curvature: float, material: Material) -> np.ndarray:
    """The interferences [m] the one mesh of a job to `top` is adapted at: the finite
    element default (`asperity.fe.drivers.inelastic.MESH_LEVELS` from `MESH_RANGE` of
    `top`), reaching down to the critical interference w_c of the tip of a body with a
    yield stress (J2; `asperity.references.kogut_etsion.critical_interference`) where
    that is lower, with LEVELS_PER_DECADE more levels a decade, so that the onset of
    yield is resolved (tests/fe/test_kogut_etsion.py)."""
    from asperity.fe.drivers.inelastic import MESH_LEVELS, MESH_RANGE
    from asperity.references.hertz import plane_strain_modulus
    from asperity.references.kogut_etsion import critical_interference

    low = MESH_RANGE * top
    if material.model == "j2" and material.yield_stress and curvature > 0:
        modulus = float(plane_strain_modulus(material.youngs_modulus, material.poisson))
        low = min(low, critical_interference(1.0 / curvature, modulus, material.poisson,
                                             material.yield_stress))
    extra = math.ceil(LEVELS_PER_DECADE * math.log10(MESH_RANGE * top / low) - 1e-9)
    return np.geomspace(low, top, MESH_LEVELS + extra)


def history(level: float, top: float, velocity: float | None):
    """Load at `velocity` to `level` and back to zero force (NaN level: load to `top`)."""
    from asperity import fe

    w_max = top if math.isnan(level) else level
    v = velocity if velocity else top / 100.0  # rate-independent body: any rate
    if math.isnan(level):
        return fe.History.loading(w_max, v)
    return fe.History.load_unload(w_max, v)


def edge_band_accuracy(preset: str) -> dict:
    """The accuracy of a job of a scene with ``asperity: {edge_band: true}``: the preset
    with its one mesh refined where the plastic contact edge goes (preset key
    ``edge_size``, `asperity.fe.presets.EDGE_SIZE`)."""
    from asperity.fe.presets import EDGE_SIZE

    return {"base": preset, "edge_size": EDGE_SIZE[preset]}


def wants_band(planning) -> bool:
    """Whether the jobs' spec adds the band to the preset: the scene's
    ``asperity.edge_band`` if it sets it, else for a rate-independent body at
    `asperity.fe.presets.RATE_INDEPENDENT_EDGE_BAND`."""
    from asperity.fe.presets import RATE_INDEPENDENT_EDGE_BAND

    if planning.asperity.edge_band is not None:
        return planning.asperity.edge_band
    return (planning.material.rate_independent(planning.effects)
            and planning.accuracy in RATE_INDEPENDENT_EDGE_BAND)


class Inelastic(FiniteElementKind):
    name = "inelastic"
    edge_band = True

    def check(self, asperity, material, effects):
        if "unloading" in effects and not asperity.shift_invariant:
            raise ValueError("effect `unloading` needs an asperity whose response does not depend "
                             "on its peak height (mapping: representative, sphere or paraboloid)")
        super().check(asperity, material, effects - {"unloading", "finite_strain"})

    def scalable(self, asperity, material, effects):
        return self_similar(asperity, material, effects)

    def unloads(self, effects):
        return "unloading" in effects

    def levels(self, planning, height, curvature):
        geometry = sample_geometry(planning.asperity, curvature, planning.width_to_height, height)
        _, top = job_range(geometry, planning.asperity, planning.grid, curvature, planning.family)
        return unloading_levels(top, planning.asperity)

    def spec(self, planning, height, curvature, level):
        spec = self.base_spec(planning, height, curvature)
        if wants_band(planning):
            spec["accuracy"] = edge_band_accuracy(planning.accuracy)
        if not planning.material.rate_independent(planning.effects):
            spec["velocity"] = planning.asperity.velocity
        if not math.isnan(level):
            spec["unloading_level"] = float(level)
        return spec

    def solve(self, spec, key):
        """`solve_asperity_history` of the job's `history`: the first step presses
        `FIRST_STEP` of the range (first touch, where most asperities of an interface
        are, is resolved in time; steps grow geometrically from there). The mesh
        resolves contacts from a hundredth of the range on, or from the first yield of a
        J2 body where that is lower (`mesh_levels`): below it the located area is the
        apex elements' (0.5 to 1.5 times Hertz's on `smooth_aluminum`), and below the
        first step the gather follows Hertz's first touch
        (`asperity.population.gather.FIRST_TOUCH`). Raises `SampleFailed` naming
        the sample, its unloading level and the step."""
        from asperity import fe

        curvature = float(spec["curvature"])
        geometry = spec_geometry(spec)
        top = spec["range"][1]
        body = Material.from_spec(spec["material"])
        material = build(body, spec["effects"])
        level = float(spec.get("unloading_level", math.nan))
        cpu = time.process_time()
        try:
            path = history(level, top, spec.get("velocity"))
            ds = fe.solve_asperity_history(geometry, material, path, accuracy=spec["accuracy"],
                                           mesh_levels=mesh_levels(top, curvature, body),
                                           initial_time_step=FIRST_STEP * top / path.velocity(0.0),
                                           kinematics=kinematics(spec["effects"]),
                                           progress=self.progress(key))
        except (fe.ConvergenceError, fe.ContactZoneError) as err:
            detail = "" if math.isnan(level) else f", unloading from {level:.6g} m"
            raise self.failed(key, curvature, err, detail) from err
        return self.record(ds, spec, key, geometry, level, time.process_time() - cpu)


INELASTIC = Inelastic()
