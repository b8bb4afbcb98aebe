"""Elastic asperity with Lennard-Jones adhesion: approach, retract, jumps, pull-off.

`solve_asperity_adhesive` presses a rigid flat onto an elastic asperity
whose free surface carries the Lennard-Jones traction of report 3.3.3
(`adhesion.LennardJones`) and pulls it off again, under displacement
control, through the jumps into and out of contact (report 7.3).  The
parts, each with its method and equations:

- `asperity.fe.solvers.adhesive`: the stationarity of the energy

      Pi(u; w) = 1/2 u^T K_S u + int Phi_c(a) W ds + int Phi_a(a) W ds

  (report 3.23 with the boundary integrals of 3.4.1; penalty and adhesion
  potentials of the penetration a) solved for a stable minimum at each
  position w of the flat;
- `asperity.fe.solvers.arclength`: a branch followed through its fold by
  arc length, and the jump from the fold;
- `asperity.fe.drivers.adhesive_model`: the mesh graded to the adhesive
  ring (or a window of it that follows the contact), the operators, and
  the energy-balance test of a step's continuity;
- `asperity.fe.drivers.adhesive_trace`: the path's levels, its step
  control, jumps, retracing and moving meshes, and the pull-off's
  refinement.

Sign convention: ``force`` is the total normal force of the flat on the
asperity, compressive positive as in `solve_asperity`; adhesion makes it
negative (attractive).  ``contact_force`` (>= 0, the penalty) and
``adhesive_force`` (<= 0) are its two parts.  ``pull_off_force`` is the
largest tensile force on retraction, a positive number (per unit length in
plane strain): the minimum of the force on the retract branch, located by
bisecting the path around the smallest recorded force (continuing the
branch from it) until the neighbouring states are d / 64 apart.  Runs of
several asperities stack on a common dimension (`stack_runs`).
"""

from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from asperity.fe.contact.adhesion import LennardJones
from asperity.fe.contact.penalty import PENALTY_FACTOR
from asperity.fe.discretization.geometry import Profile
from asperity.fe.drivers.adhesive_model import adhesive_model, tip_radius
from asperity.fe.drivers.adhesive_trace import (Overflow, adhesive_path, evaluate_states,
                                                refine_pull_off, retract_indices, trace)
from asperity.fe.errors import ContactZoneError
from asperity.fe.outputs import dataset, describe
from asperity.fe.presets import resolve


def _pull_off(w, F, branch) -> tuple[float, float]:
    """Largest tensile force on retraction and where: (force > 0, w)."""
    idx = retract_indices(branch)
    if idx.size == 0:
        return math.nan, math.nan
    i = idx[np.argmin(F[idx])]
    if F[i] >= 0:
        return 0.0, math.nan
    return float(-F[i]), float(w[i])


def _main_jump(w, F, branch, jump, which) -> float:
    """Interference before the jump of `which` branch with the largest force change.

    (A coarse mesh can peel a hanging neck in a few small snaps before the
    final jump-off; the largest is the jump into or out of contact.)
    """
    hit = np.nonzero(jump & (branch == which))[0]
    if not hit.size:
        return math.nan
    k = hit[np.argmax(np.abs(F[hit] - F[hit - 1]))]
    return float(w[k - 1])


def _levels(adhesion: LennardJones, interferences, w_max, w_min, pre: dict, R: float,
            Es: float, mu: float) -> np.ndarray:
    """The flat positions of `solve_asperity_adhesive`: `interferences`, checked, or
    the default path to ``w_max`` (twice the JKR interference at zero load, at least
    4 d) and back to ``w_min`` (beyond the cut-off and (2 mu + 4) d)."""
    if interferences is None:
        if w_max is None:
            d0 = (math.pi**2 * adhesion.dgamma**2 * R / Es**2) ** (1 / 3)  # JKR zero-load scale
            w_max = max(4.0 * adhesion.d, 2.0 * d0)
        if w_min is None:
            w_min = -max(adhesion.range - adhesion.d, (2.0 * mu + 4.0) * adhesion.d)
        return adhesive_path(adhesion, w_max, w_min, pre["steps_per_d"], pre["far_steps"])
    path = np.atleast_1d(np.asarray(interferences, dtype=float))
    if path.ndim != 1 or path.size == 0 or not np.all(np.isfinite(path)):
        raise ValueError("interferences must be a non-empty finite 1-D sequence")
    return path


def _traced(geometry: Profile, material, adhesion: LennardJones, path: np.ndarray, pre: dict,
            factor: float, label: str, progress):
    """(the model the path started on, its records) (`adhesive_trace.trace`); a path
    whose adhesive ring outgrows the refined band (`Overflow`) starts again on a band
    1.5 times wider, at most four times in all."""
    band = 1.0
    for _ in range(4):
        model = adhesive_model(geometry, material, adhesion, float(path.max()), pre, factor, band)
        try:
            return model, trace(model, path, pre, label, progress)
        except Overflow:
            if model.scales.r_band >= 0.9 * geometry.extent:
                raise ContactZoneError("the adhesive ring reached the edge of the hill") from None
            band *= 1.5
            if progress is not None:
                progress("the adhesive ring outgrew the refined band: the path again, on a "
                         "band 1.5 times wider")
    raise ContactZoneError("the adhesive ring outgrew the refined band")


def _variables(records: list, geometry: Profile, material, t_start: float) -> tuple[dict, float]:
    """(the per-step variables of the Dataset, the run's wall time so far): the
    records' states, each evaluated on its own mesh (`adhesive_trace.evaluate_states`);
    a state's wall time is its own plus an equal share of the rest of the run's."""
    states = [r.state for r in records]
    evaluate_states(states)
    ev = {name: np.array([s.fields[name] for s in states]) for name in states[0].fields}
    axi = geometry.axisymmetric
    a = ev["contact_radius"]
    w = np.array([s.w for s in states])
    F = np.array([s.force for s in states])
    branch = np.array([r.branch for r in records])
    jump = np.array([r.jump for r in records])
    total = time.perf_counter() - t_start
    own = np.array([s.wall_time for s in states])
    return dict(
        interference=w,
        force=F,
        contact_force=np.array([s.contact_force for s in states]),
        adhesive_force=np.array([s.adhesive_force for s in states]),
        contact_area=np.pi * a**2 if axi else 2 * a,
        contact_radius=a,
        normal_stiffness=np.array([s.stiffness for s in states]),
        tip_separation=ev["tip_separation"],
        max_equivalent_strain=ev["max_equivalent_strain"],
        max_von_mises=ev["max_von_mises"],
        elastic=ev["max_von_mises"] < getattr(material, "yield_stress", math.inf),
        branch=branch,
        jump=jump,
        requested=np.array([r.requested for r in records]),
        dofs=np.array([s.model.dofs for s in states]),
        newton_iterations=np.array([s.iterations for s in states]),
        step_cuts=np.array([s.cuts for s in states]),
        wall_time=own + (total - own.sum()) / len(states),
    ), total


def solve_asperity_adhesive(geometry: Profile, material, adhesion: LennardJones,
                            interferences=None, w_max: float | None = None,
                            w_min: float | None = None, accuracy="standard",
                            penalty_factor: float | None = None, label: str = "",
                            progress=None) -> xr.Dataset:
    """Approach and retraction of a rigid flat on an adhesive elastic asperity.

    Parameters
    ----------
    geometry, material
        as `solve_asperity` (elastic materials only).
    adhesion
        `LennardJones(dgamma, d, cutoff)`.
    interferences
        the path of the flat's position w [m] (negative: gap before first
        touch), in order; steps up are 'approach', steps down 'retract'.
        Default `adhesive_path(adhesion, w_max, w_min)` of the preset's density.
    w_max, w_min
        deepest interference and the retraction's end for the default path
        (w_max default: twice the JKR interference at zero load, at least 4 d).
    accuracy
        "draft", "standard", "fine" (`presets.ADHESIVE_ACCURACY` on top of
        `presets.ACCURACY`) or a dict of overrides.
    label
        a name for error messages (e.g. the pipeline's sample key).
    progress
        optional callable(str), told of every level of the path reached
        (flat position, force, Newton iterations, cuts, jumps, wall time).

    Returns a Dataset on dim ``step`` (`outputs.dataset`; the states before a
    jump and those bisecting the path around the pull-off are added to the
    requested levels, ``requested`` False) with attributes
    ``pull_off_force``, ``pull_off_interference``, ``tabor_parameter``,
    ``jump_in_interference`` and ``jump_off_interference`` (the flat's
    position before the largest jump of each branch; NaN if none),
    ``jumps`` (their number), the mesh scales, ``meshes`` (how many the
    recorded states lie on: more than one if the mesh follows the
    contact), and ``adhesion``.  A
    requested level's ``newton_iterations`` and ``step_cuts`` include
    those of the states added before it; a retraction's level that is the
    approach's state (`adhesive_trace`, "Control and jumps") has none.
    Raises `ConvergenceError` naming the step (and `label`).
    """
    t_start = time.perf_counter()
    pre = resolve("adhesive", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    R = tip_radius(geometry)
    Es = material.contact_modulus
    mu = adhesion.tabor_parameter(R, Es)
    path = _levels(adhesion, interferences, w_max, w_min, pre, R, Es, mu)
    model, records = _traced(geometry, material, adhesion, path, pre, factor, label, progress)
    refine_pull_off(records, pre, adhesion.d / 64.0)
    models = list({id(r.state.model): r.state.model for r in records}.values())
    rec, total = _variables(records, geometry, material, t_start)
    w, F, branch, jump = rec["interference"], rec["force"], rec["branch"], rec["jump"]
    pull, where = _pull_off(w, F, branch)
    sc = model.scales
    return dataset(rec, geometry, material, accuracy, pre, "path step index", dict(
        adhesion=describe(adhesion),
        contact="penalty",
        penalty_factor=factor,
        sign_convention="force compressive positive; adhesion (attraction) negative",
        pull_off_force=pull,
        pull_off_interference=where,
        pull_off_method="largest tensile force on the retract branch, the path bisected "
                        "around it to d / 64",
        tabor_parameter=mu,
        tabor_parameter_definition="(R dgamma^2 / (E*^2 d^3))^(1/3), E* = E / (1 - nu^2), z0 = d",
        tip_radius=R,
        jump_in_interference=_main_jump(w, F, branch, jump, "approach"),
        jump_off_interference=_main_jump(w, F, branch, jump, "retract"),
        jumps=int(jump.sum()),
        work_of_adhesion=adhesion.work_of_adhesion,
        process_zone=sc.process_zone,
        ring_element_size=sc.h_ring,
        band_radius=sc.r_band,
        band_facets=max(int(m.zone.nfacets) for m in models),
        meshes=len(models),
        resolution_capped=int(sc.capped),
        total_wall_time=total,
    ))


def stack_runs(runs, coord: str, values, coord_attrs: dict) -> xr.Dataset:
    """Adhesive runs on dims (coord, step), padded to the longest path.

    Padding: NaN for numbers (integers become floats), '' for the branch,
    False for flags; ``valid`` marks the steps a run has.
    """
    n = max(r.sizes["step"] for r in runs)
    data = {}
    for name, var in runs[0].data_vars.items():
        kind = var.dtype.kind
        if kind in "US":
            arr = np.full((len(runs), n), "", dtype="<U16")
        elif kind == "b":
            arr = np.zeros((len(runs), n), dtype=bool)
        else:
            arr = np.full((len(runs), n), np.nan)
        for i, r in enumerate(runs):
            arr[i, :r.sizes["step"]] = r[name].values
        data[name] = ((coord, "step"), arr, dict(var.attrs))
    valid = np.zeros((len(runs), n), dtype=bool)
    for i, r in enumerate(runs):
        valid[i, :r.sizes["step"]] = True
    data["valid"] = ((coord, "step"), valid, dict(units="1", long_name="the run has this step"))
    per = dict(
        pull_off_force=("N", "largest tensile force on retraction"),
        pull_off_interference=("m", "interference of the largest tensile force"),
        tabor_parameter=("1", "Tabor parameter (R dgamma^2 / (E*^2 d^3))^(1/3)"),
        jump_in_interference=("m", "interference where the asperity jumps into contact (NaN: none)"),
        jump_off_interference=("m", "interference where it jumps out of contact (NaN: none)"),
        band_facets=("1", "surface facets of the band refined for the adhesive ring "
                          "(the largest over the meshes)"),
        total_wall_time=("s", "wall time of the run"),
    )
    if not runs[0].attrs["symmetry"].startswith("axi"):
        per["pull_off_force"] = ("N/m", "largest tensile force per unit length on retraction")
    for name, (units, long_name) in per.items():
        data[name] = (coord, np.array([r.attrs[name] for r in runs], dtype=float),
                      dict(units=units, long_name=long_name))
    return xr.Dataset(data, coords={
        coord: (coord, np.asarray(values, dtype=float), coord_attrs),
        "step": ("step", np.arange(n), dict(units="1", long_name="path step index"))})
