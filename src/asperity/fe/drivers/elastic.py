"""Driver: one asperity pressed by a rigid flat, adaptive, to an xarray Dataset.

`solve_asperity` builds a graded initial mesh, refines it adaptively
(ZZ estimator, `adapt`), solves each interference level by Newton with
step control (`newton`) and returns one record per level.

Mesh strategy (``adapt=``):

- ``"shared"`` (default): one adaptive mesh sequence serves all levels.
  A few levels spread over the range of contact radii (``adapt_levels``
  of the preset) drive the refinement; every element's indicator is the
  largest over those levels of its share of the level's energy-norm error;
  all levels are then solved on the final mesh.  Cheap for long loading
  curves.
- ``"per_level"``: a fresh adaptive loop from the coarse initial mesh for
  every level (elastic response is path independent, so each level is
  solved from first touch).  Each level gets a mesh tuned to its own
  contact edge.

Outputs per step (`xarray.Dataset` on dim ``step``, `outputs.dataset`):
those of `_records`; `normal_stiffness` is dF/dw from the consistent
tangent of the converged state (one extra solve with the converged Newton
matrix), the contact radius is located between nodes by `contact.contact_edge`.
Quantities of a plane-strain section are per unit length of the ridge
(both halves of the symmetric section).
"""

from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from asperity.fe.discretization.adapt import StressRecovery, mark, relative_indicator
from asperity.fe import analytic
from asperity.fe.discretization.assembly import CondensedStiffness, Discretization
from asperity.fe.contact.penalty import (EDGE_FROM_GAPS, PENALTY_FACTOR, C1Penalty, ContactZone,
                                        contact_edge)
from asperity.fe.errors import ContactZoneError
from asperity.fe.discretization.geometry import Profile
from asperity.fe.materials.elastic import equivalent_strain, von_mises
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec
from asperity.fe.drivers.path import Steps, follow
from asperity.fe.solvers.newton import (EXACT_TANGENT_SCALE, ContactNewton, LevelState,
                                        solve_uzawa, untouched)
from asperity.fe.outputs import dataset, describe
from asperity.fe.presets import PLANE_STRAIN_DOMAIN, resolve

#: the zone of surface nodes allowed to touch the flat extends to this
#: multiple of the geometric intersection radius at the largest interference
#: (an elastic surface only sinks under the load, so the contact radius is
#: below that radius); it grows automatically if the contact reaches it.
CANDIDATE_FACTOR = 1.15

CONTACT_METHODS = ("penalty", "exact")

#: levels whose fields are recovered at once (bounds the memory of strains
#: and stresses at the quadrature points)
EVALUATION_CHUNK = 8


class _Levels(Steps):
    """The elastic loading path for `follow`: Newton from the tangent predictor
    u + dw du/dw, on the penalty law or, with `exact_tolerance`, by Uzawa
    updates of the multipliers the state carries (`solve_uzawa`); no folds."""

    def __init__(self, newton: ContactNewton, law: C1Penalty, max_cuts: int,
                 exact_tolerance: float | None):
        self.newton, self.law = newton, law
        self.limit, self.exact = max_cuts, exact_tolerance

    def solve(self, state: LevelState, goal: float, small: bool):
        newton = self.newton
        u0 = state.u + (goal - state.w) * state.dudw
        lam = None
        if self.exact is None:
            u, t, dt, its = newton.solve(self.law, goal, u0)
        else:
            start = (np.zeros(newton.zone.weights.shape) if state.multipliers is None
                     else state.multipliers)
            u, t, dt, its, lam = solve_uzawa(newton, self.law.kappa, goal, u0, start,
                                             self.exact)
            # tangent of the exact condition: the active points held (their
            # spring stiffened by EXACT_TANGENT_SCALE)
            dt = dt * EXACT_TANGENT_SCALE
        new = newton.state(goal, u, t, dt)
        new.multipliers = lam
        return new, its, u0


def continuation(newton: ContactNewton, law: C1Penalty, levels, max_cuts: int = 8,
                 exact_tolerance: float | None = None, steps=None) -> list[LevelState]:
    """The interference levels solved in order by the path-following driver
    (`asperity.fe.drivers.path.follow`), each from the last converged state.

    `law` is the penalty law; with `exact_tolerance` set, each level is
    solved exactly by Uzawa updates (augmented Lagrangian with the same
    stiffness).  Levels <= 0 (flat not touching) give the untouched state;
    the path always starts from first touch (w = 0, u = 0), so no step
    skips first contact.  A step whose Newton fails is cut in half, up to
    `max_cuts` times per level.  `steps` are the caller's indices of the
    levels (named by `ConvergenceError`; default 0, 1, ...).
    """
    steps = range(len(levels)) if steps is None else list(steps)
    zone = newton.zone
    path = _Levels(newton, law, max_cuts, exact_tolerance)
    state = untouched(zone)
    out = []
    for n, target in enumerate(levels):
        target = float(target)
        if target <= 0:
            out.append(untouched(zone, target))
            state = untouched(zone)
            continue
        start = time.perf_counter()
        state, _, iterations, cuts = follow(path, state, target, int(steps[n]))
        state.iterations, state.cuts = iterations, cuts
        state.wall_time = time.perf_counter() - start
        out.append(state)
    return out


class Model:
    """One mesh with its operators, ready to solve interference levels."""

    def __init__(self, mesh: AsperityMesh, material, r_candidate: float, preset: dict,
                 contact: str = "penalty", penalty_factor: float = PENALTY_FACTOR):
        if not getattr(material, "is_linear", False):
            raise NotImplementedError("only linear (elastic) materials are supported so far")
        if contact not in CONTACT_METHODS:
            raise ValueError(f"contact must be one of {CONTACT_METHODS}, got {contact!r}")
        t0 = time.perf_counter()
        self.mesh = mesh
        self.geometry = mesh.geometry
        self.material = material
        self.preset = preset
        self.contact = contact
        self.penalty_factor = float(penalty_factor)
        self.disc = Discretization(mesh)
        _, D = material.response(np.zeros((4, 1)))
        self.K = self.disc.stiffness(np.asarray(D))
        self._recovery = None
        self._set_zone(r_candidate)
        self.setup_time = time.perf_counter() - t0

    # --- contact zone ------------------------------------------------------
    def _set_zone(self, r_candidate: float):
        top = self.disc.top
        outer = top.coords[0, 2::2]  # outer vertex radius of each facet
        nf = int(np.searchsorted(outer, r_candidate)) + 1
        nf = max(2, min(nf, top.nfacets - 1))
        self.r_candidate = float(outer[nf - 1])
        self.zone = ContactZone(top, nf, self.geometry)
        self.cond = CondensedStiffness(self.disc, self.K, self.zone.dofs)

    @property
    def dofs(self) -> int:
        return len(self.disc.free)

    def _solve_once(self, levels, steps=None):
        pre = self.preset
        zone = self.zone
        law = C1Penalty.for_zone(zone, self.material.contact_modulus, self.penalty_factor)
        newton = ContactNewton(self.cond.stiffness, zone, pre["tolerance"],
                               pre["max_iterations"])
        exact = pre["exact_tolerance"] if self.contact == "exact" else None
        return continuation(newton, law, levels, pre["max_cuts"], exact, steps)

    def solve(self, levels, steps=None, estimate: bool = False):
        """States and their evaluation (`evaluate`) for the interference levels.

        The contact zone is grown as needed.  `steps`: the caller's step
        indices of the levels (for error messages).
        """
        levels = np.asarray(levels, dtype=float)
        for _ in range(6):
            states = self._solve_once(levels, steps)
            ev = self.evaluate(states, estimate)
            if not ev["overflow"].any():
                return states, ev
            if self.zone.nfacets >= self.disc.top.nfacets - 1:
                break
            self._set_zone(1.5 * self.r_candidate)
        bad = int(np.flatnonzero(ev["overflow"])[0])
        step = bad if steps is None else int(np.asarray(steps)[bad])
        raise ContactZoneError(f"the contact reached the outer edge of the top surface at step {step} "
                               f"(interference {levels[bad]:.6g} m)")

    # --- fields at the quadrature points --------------------------------------
    def evaluate(self, states, estimate: bool = False) -> dict:
        """Scalar outputs of the states from their displacement fields.

        Fields are recovered (u = K^-1 f, strains and stresses at the
        quadrature points) a few levels at a time (`EVALUATION_CHUNK`) to
        bound memory.  With `estimate`, also the squared ZZ indicators
        ``eta2`` (ne, k) and squared energy norms ``norm2`` (k,).
        """
        zone, disc, mat = self.zone, self.disc, self.material
        k = len(states)
        top = disc.top
        z_top = top.coords[1] + self.geometry.gap_offset(top.coords[0])
        beyond = np.arange(len(top.node_dofs)) > zone.ndofs - 3
        ev = dict(
            overflow=np.array([np.any(s.traction[-1] > 0) for s in states], dtype=bool),
            max_equivalent_strain=np.zeros(k),
            max_von_mises=np.zeros(k),
        )
        if estimate:
            ev["eta2"] = np.zeros((disc.weights.shape[0], k))
            ev["norm2"] = np.zeros(k)
        for lo in range(0, k, EVALUATION_CHUNK):
            part = slice(lo, min(lo + EVALUATION_CHUNK, k))
            sub = states[part]
            f = np.array([-zone.nodal(s.traction) for s in sub]).T.reshape(zone.ndofs, len(sub))
            U = self.cond.full_displacement(f)
            strain = disc.strain(U)  # (4, ne, nq, chunk)
            stress, _ = mat.response(strain)
            n = len(sub)
            ev["max_equivalent_strain"][part] = equivalent_strain(strain).reshape(-1, n).max(axis=0)
            ev["max_von_mises"][part] = von_mises(stress).reshape(-1, n).max(axis=0)
            # no penetration beyond the zone allowed to touch
            w = np.array([s.w for s in sub])
            pen_top = z_top[:, None] + U[top.node_dofs] + w[None, :]
            ev["overflow"][part] |= np.any((pen_top > 0) & beyond[:, None], axis=0)
            if estimate:
                ev["eta2"][:, part], ev["norm2"][part] = self.recovery().indicators(stress)
        radius = np.zeros(k)
        tol_touch = 100 * self.preset["exact_tolerance"] if self.contact == "exact" else 0.0
        for j, s in enumerate(states):  # one scalar search per level
            if s.w <= 0 or s.force <= 0:
                continue
            pen = zone.node_penetration(s.u, s.w)
            radius[j] = contact_edge(zone.coords[0], -pen, pen > -tol_touch * s.w)
        ev["contact_radius"] = radius
        return ev

    def recovery(self) -> StressRecovery:
        if self._recovery is None:
            self._recovery = StressRecovery(self.disc, self.material)
        return self._recovery


def _relative_error(eta2: np.ndarray, norm2: np.ndarray) -> np.ndarray:
    """Estimated relative energy-norm error of each level."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.sqrt(np.where(norm2 > 0, eta2.sum(axis=0) / norm2, 0.0))


# --- mesh design and adaptivity ------------------------------------------------
def _initial_spec(geometry: Profile, levels_pos: np.ndarray, preset: dict) -> MeshSpec:
    rg = geometry.intersection_radius(levels_pos)
    small = float(np.min(rg))
    if geometry.axisymmetric:
        L = preset["domain_factor"] * geometry.length_scale
    else:
        L = PLANE_STRAIN_DOMAIN * geometry.length_scale
    apex = min(preset["apex_fraction"] * small, L / 100.0)
    return MeshSpec(L, apex, preset["growth"], preset["n_theta"])


def _spread(values: np.ndarray, k: int) -> np.ndarray:
    """Indices of at most k values spread evenly in log scale (ends included)."""
    if len(values) <= k:
        return np.arange(len(values))
    logv = np.log(values)
    targets = np.linspace(logv.min(), logv.max(), k)
    idx = np.unique([int(np.argmin(np.abs(logv - t))) for t in targets])
    return idx


def adapted_model(geometry: Profile, material, levels, preset: dict,
                  contact: str = "penalty", penalty_factor: float = PENALTY_FACTOR,
                  steps=None):
    """Adaptive loop for a set of levels; returns (model, history).

    The history lists per sweep the dofs and the estimated relative error
    of each driving level.  `steps` are the caller's indices of `levels`
    (named by a `ConvergenceError`).
    """
    levels = np.asarray(levels, dtype=float)
    steps = np.arange(len(levels)) if steps is None else np.asarray(steps)
    order = np.argsort(levels, kind="stable")
    order = order[levels[order] > 0]
    pos = levels[order]
    if pos.size == 0:  # nothing touches: a mesh sized for a small contact, no solve
        pos = np.array([1e-3 * geometry.height])
        rg = geometry.intersection_radius(pos)
        mesh = AsperityMesh.initial(geometry, _initial_spec(geometry, pos, preset))
        model = Model(mesh, material, CANDIDATE_FACTOR * float(rg[0]), preset, contact,
                      penalty_factor)
        model.adapt_time = model.setup_time
        return model, []
    rg = geometry.intersection_radius(pos)
    pick = _spread(rg, preset["adapt_levels"])
    drive, drive_steps = pos[pick], steps[order[pick]]
    r_candidate = CANDIDATE_FACTOR * float(np.max(rg))
    mesh = AsperityMesh.initial(geometry, _initial_spec(geometry, pos, preset))
    history = []
    t0 = time.perf_counter()
    for sweep in range(preset["sweeps"] + 1):
        model = Model(mesh, material, r_candidate, preset, contact, penalty_factor)
        states, ev = model.solve(drive, drive_steps, estimate=True)
        eta2, norm2 = ev["eta2"], ev["norm2"]
        rel = _relative_error(eta2, norm2)
        history.append(dict(sweep=sweep, dofs=model.dofs, error=rel))
        r_candidate = max(r_candidate, model.r_candidate)
        if sweep == preset["sweeps"] or np.max(rel) <= preset["target_error"]:
            break
        mesh = mesh.refined(mark(relative_indicator(eta2, norm2), preset["theta"]))
    model.adapt_time = time.perf_counter() - t0
    return model, history


# --- public API -------------------------------------------------------------------
def _records(model: Model, states, ev) -> dict[str, np.ndarray]:
    k = len(states)
    a = ev["contact_radius"]
    axi = model.geometry.axisymmetric
    err = _relative_error(ev["eta2"], ev["norm2"]) if "eta2" in ev else np.full(k, np.nan)
    yield_stress = getattr(model.material, "yield_stress", math.inf)
    return dict(
        interference=np.array([s.w for s in states]),
        force=np.array([s.force for s in states]),
        contact_area=np.pi * a**2 if axi else 2 * a,
        contact_radius=a,
        normal_stiffness=np.array([s.stiffness for s in states]),
        max_equivalent_strain=ev["max_equivalent_strain"],
        max_von_mises=ev["max_von_mises"],
        elastic=ev["max_von_mises"] < yield_stress,
        estimated_error=err,
        dofs=np.full(k, model.dofs),
        newton_iterations=np.array([s.iterations for s in states]),
        step_cuts=np.array([s.cuts for s in states]),
        wall_time=np.array([s.wall_time for s in states]),
    )


def run_attrs(contact: str, penalty_factor: float, strategy: str,
              edge_method: str = EDGE_FROM_GAPS) -> dict:
    """The attributes of an axisymmetric or plane-strain run (elastic or
    inelastic) beside those of `outputs.dataset`: `edge_method` says how the
    contact edge was located (`contact.EDGE_FROM_GAPS`, `contact.EDGE_FROM_PRESSURES`)."""
    return dict(
        contact=contact,
        penalty_factor=float(penalty_factor),
        mesh_strategy=strategy,
        contact_edge_method=edge_method,
    )


def check_levels(geometry, interferences) -> np.ndarray:
    w = np.atleast_1d(np.asarray(interferences, dtype=float))
    if w.ndim != 1 or w.size == 0:
        raise ValueError("interferences must be a non-empty 1-D sequence")
    if not np.all(np.isfinite(w)):
        raise ValueError("interferences must be finite")
    if np.any(w >= geometry.height):
        raise ValueError(
            f"interference {w.max():.6g} m reaches the foot of the hill "
            f"(height {geometry.height:.6g} m)")
    return w


def solve_asperity(geometry: Profile, material, interferences, accuracy="standard",
                   contact: str = "penalty", penalty_factor: float | None = None,
                   adapt: str = "shared") -> xr.Dataset:
    """Force, area, stiffness... of one asperity pressed by a rigid flat.

    Parameters
    ----------
    geometry
        a `Profile` (`CosineHill`, `Sphere`, `Paraboloid`, `Cylinder`,
        `TruncatedV`); its ``axisymmetric`` flag selects body of revolution
        or plane strain.
    material
        e.g. `LinearElastic(E, nu, yield_stress)`.
    interferences
        approach of the flat from first touch [m], one step each, solved
        in the given order by continuation from first touch; values <= 0
        give the untouched state.
    accuracy
        "draft", "standard", "fine" (`presets.ACCURACY`) or a dict of
        overrides.
    contact
        "penalty" (C1 penalty of report 3.3.2) or "exact" (augmented
        Lagrangian to the preset's tolerance).
    penalty_factor
        c in kappa = c E' / h (default `contact.PENALTY_FACTOR`).
    adapt
        "shared" or "per_level" (see module docstring).

    Raises `ConvergenceError` (with the step index and interference) if a
    level cannot be reached even with step cutting.
    """
    t_start = time.perf_counter()
    w = check_levels(geometry, interferences)
    preset = resolve("elastic", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    if not factor > 0:
        raise ValueError("penalty_factor must be positive")
    if adapt == "shared":
        model, history = adapted_model(geometry, material, w, preset, contact, factor)
        t_mesh = time.perf_counter() - t_start
        states, ev = model.solve(w, estimate=True)
        rec = _records(model, states, ev)
        total = time.perf_counter() - t_start
        own = rec["wall_time"]
        rec["wall_time"] = own + (total - own.sum()) / len(w)
        extra = dict(adaptive_sweeps=max(len(history) - 1, 0), mesh_wall_time=t_mesh,
                     total_wall_time=total)
    elif adapt == "per_level":
        parts = []
        for i, wi in enumerate(w):
            t0 = time.perf_counter()
            model, history = adapted_model(geometry, material, [wi], preset, contact, factor,
                                           steps=[i])
            states, ev = model.solve([wi], [i], estimate=True)
            r = _records(model, states, ev)
            r["wall_time"] = np.array([time.perf_counter() - t0])
            parts.append(r)
        rec = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
        extra = dict(total_wall_time=time.perf_counter() - t_start)
    else:
        raise ValueError(f"adapt must be 'shared' or 'per_level', got {adapt!r}")
    return dataset(rec, geometry, material, accuracy, preset, "load step index",
                   {**run_attrs(contact, factor, adapt),
                    "normal_stiffness_method": "consistent tangent of the converged state",
                    **extra})


def penalty_error(geometry: Profile, material, interferences, accuracy="standard",
                  penalty_factors=(10.0, 100.0, 1000.0, 10000.0)) -> xr.Dataset:
    """The penalty method's own error, against the exact option on the same mesh.

    The mesh is adapted once (exact contact); then every penalty factor and
    the exact option solve the same levels on it.  Returns relative errors
    of force, contact radius and stiffness on dims (penalty_factor, step)
    and the largest penetration relative to the interference.
    """
    w = check_levels(geometry, interferences)
    preset = resolve("elastic", accuracy)
    model, _ = adapted_model(geometry, material, w, preset, "exact")
    exact_states, exact_ev = model.solve(w)
    F0 = np.array([s.force for s in exact_states])
    a0 = exact_ev["contact_radius"]
    k0 = np.array([s.stiffness for s in exact_states])
    errF, erra, errk, pen = [], [], [], []
    model.contact = "penalty"
    for c in penalty_factors:
        model.penalty_factor = float(c)
        states, ev = model.solve(w)
        F = np.array([s.force for s in states])
        a = ev["contact_radius"]
        kk = np.array([s.stiffness for s in states])
        with np.errstate(divide="ignore", invalid="ignore"):
            errF.append(np.where(F0 > 0, F / F0 - 1, 0.0))
            erra.append(np.where(a0 > 0, a / a0 - 1, 0.0))
            errk.append(np.where(k0 > 0, kk / k0 - 1, 0.0))
            # the apex of a body of revolution has no measure: left out
            nodes = model.zone.coords[0] > 0 if geometry.axisymmetric else slice(None)
            pen.append([float(np.max(model.zone.node_penetration(s.u, s.w)[nodes])) / s.w
                        if s.w > 0 else 0.0 for s in states])
    dims = ("penalty_factor", "step")
    ds = xr.Dataset(
        dict(
            force_error=(dims, np.array(errF), dict(units="1", long_name="relative force error of the penalty")),
            radius_error=(dims, np.array(erra), dict(units="1", long_name="relative contact radius error of the penalty")),
            stiffness_error=(dims, np.array(errk), dict(units="1", long_name="relative stiffness error of the penalty")),
            max_penetration=(dims, np.array(pen), dict(units="1", long_name="largest nodal penetration / interference")),
            exact_force=("step", F0, dict(units="N" if geometry.axisymmetric else "N/m",
                                          long_name="force with exact non-penetration")),
            interference=("step", w, dict(units="m", long_name="interference")),
        ),
        coords=dict(
            penalty_factor=("penalty_factor", np.asarray(penalty_factors, dtype=float),
                            dict(units="1", long_name="c in kappa = c E' / h")),
            step=("step", np.arange(len(w)), dict(units="1", long_name="load step index")),
        ),
    )
    ds.attrs.update(geometry=describe(geometry), material=describe(material), dofs=model.dofs)
    return ds


def hertz(radius: float, material, interference) -> dict[str, np.ndarray]:
    """Hertz's solution for `material` (see `analytic.hertz`)."""
    return analytic.hertz(radius, material.E, material.nu, interference)
