"""Inelastic asperity: incremental (rate) solution along a prescribed history.

An inelastic body (report 3.2.2: `J2Plasticity` or `BodnerPartom`) pressed
by the rigid flat, whose interference is a prescribed piecewise linear
function of time (`History`, e.g. `History.load_unload`: loading at a
prescribed velocity, 0.25 um/s in report 8.2.2, then unloading).

The mesh follows the contact where the preset's ``remesh`` key is on
(`remesh`; off in the built-in presets): it is refined around the current
contact edge and plastic zone only, rebuilt when the edge leaves the band of
radii it resolves or the plastic zone the region refined for it, the state at
the start of the step transferred to the new mesh (displacements, every field
of the material state, the flow rates of the time-error estimate) and the step
re-solved on it, with backward Euler (like after a knot). With ``remesh`` off
the mesh is FIXED: it is adapted once, by the existing machinery
(`elastic.adapted_model` with the material's elastic constants), to elastic
solutions at a few interferences up to the largest of the history
(``mesh_levels``), so that it resolves the contact edge from first touch to
the largest load, and with the preset key ``edge_size`` refined along the
surface where the wider plastic edge goes (`remesh.edge_band`). Either way,
plastic contacts are wider than elastic ones at the same interference: the
candidate contact zone is larger (``INELASTIC_CANDIDATE_FACTOR``) and grows if
reached.

The parts: the equilibrium of a step is `inelastic_model.InelasticModel` (Newton on
the full system, vectorized over elements and quadrature points); the time
integration of the material and its error estimate, `solvers.time_error`; what a
step tries, accepts and records (step control, rupture, the zero-force crossing of
unloading), `history_march.HistoryMarch`, marched by `march.march`.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np
import xarray as xr

from asperity.fe.discretization.assembly import Discretization
from asperity.fe.contact.penalty import EDGE_FROM_PRESSURES, PENALTY_FACTOR
from asperity.fe.discretization.kinematics import KINEMATICS
from asperity.fe.materials.elastic import equivalent_strain
from asperity.fe.outputs import INELASTIC_THRESHOLD, SMALL_STRAIN_LIMIT, dataset
from asperity.fe.presets import resolve
from asperity.fe.drivers.remesh import EDGE_BAND, ContactMeshes, edge_band
from asperity.fe.drivers.elastic import adapted_model, check_levels, run_attrs
from asperity.fe.drivers.march import march
from asperity.fe.drivers.inelastic_model import InelasticModel, elastic_part
from asperity.fe.drivers.history_march import HistoryMarch

log = logging.getLogger(__name__)

#: default time tolerance when the accuracy preset has none
TIME_TOLERANCE = 0.1


#: Newton tolerance of a rate-dependent material: this x time_tolerance where
#: that is looser than the preset's
NEWTON_FRACTION = 1e-2


#: default levels of the one-off mesh adaptation: MESH_LEVELS interferences
#: from MESH_RANGE x the largest one to the largest
MESH_LEVELS, MESH_RANGE = 6, 0.01


#: the candidate contact zone of an inelastic body: this multiple of the
#: geometric intersection radius at the largest interference (plastic
#: pile-up may lift the surface beyond it); grown if reached.
INELASTIC_CANDIDATE_FACTOR = 1.5


#: what the solver does when a point ruptures
ON_RUPTURE = ("continue", "stop", "raise")


#: time integration of a rate-dependent material
INTEGRATION = ("bdf2", "euler")


@dataclass(frozen=True)
class History:
    """Piecewise linear interference w(t) through the knots (times [s], w [m])."""

    times: tuple
    interferences: tuple

    def __post_init__(self):
        t = np.asarray(self.times, float)
        w = np.asarray(self.interferences, float)
        if t.ndim != 1 or t.shape != w.shape or t.size < 2:
            raise ValueError("a history needs at least two knots (times, interferences)")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(w))):
            raise ValueError("history knots must be finite")
        if np.any(np.diff(t) <= 0):
            raise ValueError("history times must increase")

    @classmethod
    def load_unload(cls, max_interference: float, velocity: float,
                    final_interference: float = 0.0, start: float = 0.0) -> "History":
        """Load from `start` to `max_interference` and back to
        `final_interference`, at `velocity` [m/s] both ways."""
        if not (velocity > 0 and max_interference > start):
            raise ValueError("need velocity > 0 and max_interference > start")
        t1 = (max_interference - start) / velocity
        t2 = t1 + (max_interference - final_interference) / velocity
        return cls((0.0, t1, t2), (start, max_interference, final_interference))

    @classmethod
    def loading(cls, max_interference: float, velocity: float, start: float = 0.0) -> "History":
        return cls((0.0, (max_interference - start) / velocity), (start, max_interference))

    @property
    def end(self) -> float:
        return float(self.times[-1])

    def __call__(self, t) -> np.ndarray:
        return np.interp(t, self.times, self.interferences)

    def branch(self, t: float) -> str:
        """'loading' (w not decreasing) or 'unloading' on the segment after t."""
        tk = np.asarray(self.times)
        i = int(np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2))
        return "unloading" if self.interferences[i + 1] < self.interferences[i] else "loading"

    def velocity(self, t: float) -> float:
        """|dw/dt| on the segment after t."""
        tk = np.asarray(self.times, float)
        wk = np.asarray(self.interferences, float)
        i = int(np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2))
        return float(abs(wk[i + 1] - wk[i]) / (tk[i + 1] - tk[i]))

    def next_knot(self, t: float) -> float:
        tk = np.asarray(self.times)
        later = tk[tk > t * (1 + 1e-14) + 1e-300]
        return float(later[0]) if later.size else self.end


#: the variables of `solve_asperity_history` (units and long names:
#: `outputs.VARIABLES`)
OUTPUTS = ("time", "interference", "force", "contact_area", "contact_radius",
           "max_equivalent_strain", "max_inelastic_strain", "max_von_mises", "max_damage",
           "ruptured_points", "elastic", "small_strain", "branch", "newton_iterations",
           "step_cuts", "time_step", "integration_order", "time_error", "dofs", "wall_time")


#: the variables of `mesh_fields` (`solve_asperity_history`'s ``end_fields``)
END_FIELDS = ("vertex_r", "vertex_z", "triangle_vertices", "vertex_displacement_r",
              "vertex_displacement_z", "element_inelastic_strain", "element_jacobian")


def mesh_fields(disc: Discretization, u: np.ndarray, state) -> xr.Dataset:
    """The mesh of `disc` and the fields of displacement `u` and material `state` on it,
    on dims ``vertex``, ``triangle`` and ``corner`` (`END_FIELDS`): the undeformed
    vertices (r or x, z), the corners of the triangles (the P2 elements'
    straight-sided skeleton), the displacement at the vertices, the equivalent inelastic
    strain averaged over each element (by volume: its quadrature weights), and the
    smallest det(I + grad u) at the element's quadrature points (times the hoop stretch
    1 + u_r / r of a body of revolution): at or below zero the displacement turns the
    element inside out, which a small-strain solution allows far past its range."""
    m = disc.mesh.vertices
    ur, uz = u[disc.basis.nodal_dofs]
    ep = equivalent_strain(state.inelastic_strain)
    ep_e = np.sum(ep * disc.weights, axis=1) / np.sum(disc.weights, axis=1)
    field = disc.basis.interpolate(u)
    g = field.grad  # (2, 2, ne, nq): d u_i / d x_j
    jac = (1 + g[0, 0]) * (1 + g[1, 1]) - g[0, 1] * g[1, 0]
    if disc.axisymmetric:
        jac = jac * (1 + np.asarray(field)[0] / disc.x[0])
    x = "r" if disc.axisymmetric else "x"

    def var(dims, values, units, long_name):
        return dims, values, dict(units=units, long_name=long_name)

    return xr.Dataset(
        {"vertex_r": var("vertex", m.p[0], "m", f"{x} of the mesh vertex (undeformed)"),
         "vertex_z": var("vertex", m.p[1], "m", "z of the mesh vertex (undeformed, up)"),
         "triangle_vertices": var(("triangle", "corner"), m.t.T.astype(np.int32), "1",
                                  "vertex indices of the element's corners"),
         "vertex_displacement_r": var("vertex", ur, "m",
                                      f"displacement u_{x} at the vertex, end of the run"),
         "vertex_displacement_z": var("vertex", uz, "m",
                                      "displacement u_z at the vertex, end of the run"),
         "element_inelastic_strain": var("triangle", ep_e, "1",
                                         "equivalent inelastic strain, the element's volume "
                                         "mean, end of the run"),
         "element_jacobian": var("triangle", jac.min(axis=1), "1",
                                 "smallest det(I + grad u) at the element's quadrature points, "
                                 "end of the run (<= 0: turned inside out)")},
        coords={"vertex": var("vertex", np.arange(m.p.shape[1]), "1", "mesh vertex"),
                "triangle": var("triangle", np.arange(m.t.shape[1]), "1", "mesh element"),
                "corner": var("corner", np.arange(3), "1", "element corner")})


def solve_asperity_history(geometry, material, history: History, accuracy="standard",
                           initial_time_step: float | None = None,
                           max_time_step: float | None = None,
                           max_interference_step: float = 0.025,
                           max_inelastic_step: float = 0.05,
                           max_cuts: int = 20, max_steps: int = 100_000,
                           stop_at_zero_force: bool = True,
                           event_tolerance: float = 1e-3,
                           penalty_factor: float | None = None,
                           tolerance: float | None = None,
                           mesh_levels=None,
                           time_tolerance: float | None = None,
                           integration: str = "bdf2",
                           on_rupture: str = "continue",
                           remesh_times=(), kinematics: str = "small",
                           end_fields: bool = False, progress=None) -> xr.Dataset:
    """Incremental solution of an inelastic asperity along `history`.

    Parameters
    ----------
    geometry
        a `Profile`.
    material
        an inelastic material with ``initial_state(shape)`` and
        ``update(strain, state, dt, tangent=True)`` (`J2Plasticity`,
        `BodnerPartom`); with ``rates(state)`` it is rate dependent (time
        error control, BDF2).
    history
        `History`: the interference [m] as a piecewise linear function of
        time [s]; the body is stress free at its start (w <= 0: first
        touch at w = 0).
    accuracy
        preset name or dict (`presets.INELASTIC_ACCURACY`); sets the mesh (with
        ``remesh`` on: rebuilt as the contact moves, `remesh`; off: adapted
        once, to elastic solutions at ``mesh_levels``), the Newton
        tolerance and iteration limit, and the default ``time_tolerance``.
    initial_time_step
        first time step [s] (default: the one giving an interference step
        of ``max_interference_step / 4`` of the largest interference).
    max_time_step
        upper bound of the time step [s] (default none).
    max_interference_step
        accepted steps change w by at most this fraction of the largest
        interference (larger steps are rejected and cut).
    max_inelastic_step
        accepted steps change the equivalent inelastic strain by at most
        this anywhere (else rejected and cut); a safety bound.
    max_cuts
        rejections allowed per step before `ConvergenceError`.
    max_steps
        stop after this many accepted steps (attribute ``completed`` 0).
    event_tolerance
        see ``stop_at_zero_force``.
    penalty_factor
        c in kappa = c E' / h (default `contact.PENALTY_FACTOR`).
    tolerance
        Newton: ||R|| <= tolerance ||f_contact|| (default: the preset's,
        for a rate-dependent material at least ``NEWTON_FRACTION`` x
        time_tolerance), or the round-off level of the internal forces.
    mesh_levels
        interferences [m] driving the one-off adaptive meshing (elastic
        solutions, `solve.adapted_model`); default ``MESH_LEVELS`` levels
        spread geometrically from ``MESH_RANGE`` x the largest interference
        to the largest, so that the mesh also resolves the small contacts of
        first touch and of the end of unloading.  With ``remesh`` on, the
        first mesh is the one for the elastic contact at the smallest level.
        The elastic contact edge at the largest level lies inside a plastic
        one (a sphere: sqrt(R w) against up to sqrt(2 R w)): the preset key
        ``edge_size`` (set at 'fine') refines the band of radii the plastic
        edge sweeps (`remesh.edge_band`; docs: theory/single-asperity.md,
        'Inelastic histories'); with ``remesh`` on it is not read.
    stop_at_zero_force
        on unloading, stop once the force vanishes (falls below
        ``ZERO_FORCE`` x the largest force; the crossing is
        located to ``event_tolerance`` x largest interference either way).
    time_tolerance
        bound of the time-integration error indicator of a step of a
        rate-dependent material (`solvers.time_error`; default: the preset's
        ``time_tolerance``, else ``TIME_TOLERANCE``); ``inf`` switches the
        control off.
    integration
        ``"bdf2"`` (default) or ``"euler"`` (backward Euler throughout) for
        a rate-dependent material.
    on_rupture
        ``"continue"`` (default), ``"stop"`` or ``"raise"`` (`RuptureError`)
        when a material point ruptures (`history_march`).
    remesh_times
        times [s] at which a new mesh is built whatever the preset's
        ``remesh``: after the first step ending at or after each, which is
        re-solved on it (e.g. at a load reversal).
    kinematics
        ``"small"`` (default: linearized strains, report 3.23) or
        ``"finite"``: total Lagrangian with the logarithmic strain
        (`kinematics.FiniteStrain`), for contacts whose strains leave the
        small-strain range (report 7.3: about 8 %).  The strain outputs are
        then Hencky strains, the stresses their work conjugates (rotated
        Kirchhoff stresses), the contact radius that of the deformed surface.
    end_fields
        also return the mesh of the end of the run and its fields there
        (`mesh_fields`: the vertices, the triangles, the displacement at the
        vertices, each element's equivalent inelastic strain and whether the
        displacement turns it inside out), to draw the mesh and the deformed
        body (report Figs. 6.15, 6.16, 6.19 to 6.21).
    progress
        optional callable(str), told of every accepted step (time and the history's end,
        interference, force, Newton iterations, cuts, wall time).

    Returns an `xarray.Dataset` on dim ``step`` (variables `OUTPUTS`,
    step 0 the initial untouched state) with attributes including
    ``residual_interference`` (NaN if the force never returned to zero),
    ``steps``, ``total_step_cuts``, ``total_factorizations``,
    ``time_tolerance``, ``max_time_error``, ``time_error_rejections``,
    ``remeshes`` and ``remeshed_steps`` (the steps re-solved on a new mesh;
    ``dofs`` is per step),
    ``ruptured`` (0/1) and, after a rupture, ``rupture_step``,
    ``rupture_time``, ``rupture_interference``, ``rupture_position`` (r or
    x of the first ruptured point) and ``rupture_depth`` (below the
    surface); ``completed`` (0 if the run stopped before the end of the
    history, other than at the zero force) with ``stop_reason``, and
    ``total_wall_time``.

    Raises `ConvergenceError` naming the step and the interference when a
    step fails ``max_cuts`` times.
    """
    t_start = time.perf_counter()
    preset = resolve("inelastic", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    rate_dependent = hasattr(material, "rates")
    if time_tolerance is None:
        time_tolerance = preset.get("time_tolerance", TIME_TOLERANCE)
    time_tolerance = float(time_tolerance)
    if not time_tolerance > 0:
        raise ValueError("time_tolerance must be positive (inf: no control)")
    if on_rupture not in ON_RUPTURE:
        raise ValueError(f"on_rupture must be one of {ON_RUPTURE}, got {on_rupture!r}")
    if integration not in INTEGRATION:
        raise ValueError(f"integration must be one of {INTEGRATION}, got {integration!r}")
    if kinematics not in KINEMATICS:
        raise ValueError(f"kinematics must be one of {KINEMATICS}, got {kinematics!r}")
    knots_w = np.asarray(history.interferences, float)
    w_max = float(knots_w.max())
    if not w_max > 0:
        raise ValueError("the history never presses the flat onto the asperity (max w <= 0)")
    check_levels(geometry, [w_max])
    if not hasattr(material, "update"):
        raise TypeError("material must have initial_state/update (an inelastic material)")
    if tolerance is None and rate_dependent and math.isfinite(time_tolerance):
        tolerance = max(preset["tolerance"], NEWTON_FRACTION * time_tolerance)
    mesh = _first_mesh(geometry, material, preset, factor, w_max, mesh_levels)
    model = InelasticModel(mesh.disc, geometry, material, preset, mesh.r_candidate, factor,
                           tolerance, kinematics)
    t_mesh = time.perf_counter() - t_start

    # --- time stepping: `march` with the steps of `HistoryMarch`
    dw_max = max_interference_step * w_max
    slopes = np.abs(np.diff(knots_w)) / np.diff(np.asarray(history.times, float))
    vmax = float(slopes.max()) if slopes.max() > 0 else w_max / history.end
    dt = initial_time_step if initial_time_step is not None else 0.25 * dw_max / vmax
    if not dt > 0:
        raise ValueError("initial_time_step must be positive")
    run = HistoryMarch(
        model, mesh.meshes, history, r_candidate=mesh.r_candidate, tolerance=tolerance,
        kinematics=kinematics, integration=integration, dw_max=dw_max,
        dt_cap=math.inf if max_time_step is None else float(max_time_step),
        max_inelastic_step=max_inelastic_step, max_cuts=max_cuts,
        time_tolerance=time_tolerance, event_tolerance=event_tolerance, w_max=w_max,
        stop_at_zero_force=stop_at_zero_force, on_rupture=on_rupture,
        remesh=mesh.remesh, remesh_times=remesh_times, rg=mesh.rg, progress=progress)
    march(run, dt, max_steps)
    model, rows, t, residual = run.model, run.rows, run.t, run.residual

    total = time.perf_counter() - t_start
    k = len(rows)
    done = bool(t >= history.end * (1 - 1e-12) or not math.isnan(residual))
    stop_reason = run.stop_reason
    if not done and not stop_reason:
        stop_reason = f"max_steps ({max_steps}) reached at time {t:.6g} s"
    rec = {}
    for name in OUTPUTS:
        if name == "elastic":
            rec[name] = np.array([r["max_inelastic_strain"] <= INELASTIC_THRESHOLD for r in rows])
        elif name == "small_strain":
            rec[name] = np.array([r["max_principal_strain"] < SMALL_STRAIN_LIMIT for r in rows])
        else:
            rec[name] = np.array([r[name] for r in rows])
    errors = rec["time_error"][1:]
    rupture = run.rupture
    extra = dict(
        history_times=np.asarray(history.times, float),
        history_interferences=knots_w,
        steps=k - 1,
        total_step_cuts=int(sum(r["step_cuts"] for r in rows)),
        total_factorizations=int(run.factorizations + model.factorizations),
        remeshes=len(run.remeshed_steps),
        remeshed_steps=np.asarray(run.remeshed_steps, dtype=np.int64),
        residual_interference=float(residual),
        residual_interference_method="linear extrapolation to zero of the force of the last two "
                                     "unloading steps with force > 0, within the crossing step "
                                     "(located to event_tolerance)",
        integration=(integration if rate_dependent
                     else "backward Euler (rate-independent material)"),
        time_tolerance=time_tolerance,
        max_time_error=float(np.nanmax(errors)) if np.any(np.isfinite(errors)) else math.nan,
        time_error_rejections=int(run.error_rejections),
        time_error_method="local truncation error of backward Euler (against the trapezoidal "
                          "rule) or BDF2 from the flow rates at the step ends (report 3.36): "
                          "nodal forces of the stress error over the contact forces; damage "
                          "kappa error over its rupture value",
        ruptured=int(rupture is not None),
        on_rupture=on_rupture,
        kinematics=kinematics,
        completed=int(done),
        stop_reason=stop_reason,
        mesh_wall_time=t_mesh,
        total_wall_time=total,
    )
    if rupture is not None:
        extra.update(rupture_step=rupture["step"], rupture_time=rupture["time"],
                     rupture_interference=rupture["interference"],
                     rupture_position=rupture["position"], rupture_depth=rupture["depth"])
    ds = dataset(rec, geometry, material, accuracy, preset, "time step index", {
        **run_attrs("penalty", factor, mesh.strategy, EDGE_FROM_PRESSURES), **extra})
    return xr.merge([ds, mesh_fields(model.disc, run.u, run.state)], combine_attrs="override") \
        if end_fields else ds


@dataclass
class _FirstMesh:
    """The mesh a history starts on (`_first_mesh`)."""

    disc: Discretization
    meshes: ContactMeshes
    r_candidate: float
    rg: float
    remesh: bool
    strategy: str


def _first_mesh(geometry, material, preset: dict, factor: float, w_max: float,
                mesh_levels) -> _FirstMesh:
    """The first mesh of a history to the largest interference `w_max`: adapted once to
    the elastic solutions at `mesh_levels` (with the band of the preset's ``edge_size``),
    or, with the preset's ``remesh``, the one for the elastic contact at the smallest
    level, rebuilt as the contact moves (`solve_asperity_history`)."""
    if mesh_levels is None:
        mesh_levels = np.geomspace(MESH_RANGE * w_max, w_max, MESH_LEVELS)
    mesh_levels = check_levels(geometry, mesh_levels)
    rg = float(geometry.intersection_radius(np.array([w_max]))[0])
    r_cand = INELASTIC_CANDIDATE_FACTOR * rg
    remesh = bool(preset["remesh"])
    # the band of the one mesh; with remesh on the meshes follow the contact edge
    edge_size = None if remesh else preset["edge_size"]
    if edge_size is not None:
        if not 0 < float(edge_size) < 1:
            raise ValueError(f"accuracy key edge_size must be None or between 0 and 1 "
                             f"(times the intersection radius), got {edge_size!r}")
    meshes = ContactMeshes(geometry, elastic_part(material), preset, factor, INELASTIC_THRESHOLD)
    if remesh:
        # the elastic contact radius at the smallest mesh level
        a_first = float(geometry.intersection_radius(mesh_levels.min())) / math.sqrt(2.0)
        disc = meshes.build(a_first)
    else:
        emodel, _ = adapted_model(geometry, elastic_part(material), mesh_levels, preset,
                                  "penalty", factor)
        r_cand = max(r_cand, emodel.r_candidate)
        disc = emodel.disc
        if edge_size is not None:  # the band the plastic edge sweeps
            disc = Discretization(edge_band(emodel.mesh, geometry, w_max, float(edge_size)))
    if remesh:
        strategy = "rebuilt around the contact edge and the plastic zone as they move (remesh)"
    else:
        strategy = (f"fixed, adapted once to the elastic solutions at {mesh_levels.size} "
                    f"interferences from {mesh_levels.min():.6g} to {mesh_levels.max():.6g} m")
        if edge_size is not None:
            strategy += (f", then refined along the surface where the plastic contact edge "
                         f"goes ({EDGE_BAND[0]:g} to {EDGE_BAND[1]:g} times the intersection "
                         f"radius at the largest interference, to {float(edge_size):g} of it)")
    return _FirstMesh(disc, meshes, r_cand, rg, remesh, strategy)
