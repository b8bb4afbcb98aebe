"""Inelastic asperity: incremental (rate) solution along a prescribed history.

An inelastic body (report 3.2.2: `J2Plasticity` or `BodnerPartom`) pressed
by the rigid flat, whose interference is a prescribed piecewise linear
function of time (`History`, e.g. `History.load_unload`: loading at a
prescribed velocity, 0.25 um/s in report 8.2.2, then unloading).

Method (the incremental counterpart of report 3.22, in the backward-Euler
form that FE codes use): the time is divided into steps; at each step the
global equilibrium

    R(u) = int B^T sigma(eps(u); state_n, dt) dV + int t_N(a(u)) N ds = 0

is solved by Newton on the *full* system (all free dofs, no condensation,
which only holds for a linear body) with the material's consistent tangent
at the quadrature points plus the penalty contact tangent.  Internal
variables are carried per quadrature point and committed only when the
step is accepted.  Everything is vectorized over elements and quadrature
points (`Discretization.B`, sparse strain operator, one einsum for the
element matrices).

The mesh is FIXED: it is adapted once, by the existing machinery
(`solve.adapted_model` with the material's elastic constants), to elastic
solutions at a few interferences up to the largest of the history
(``mesh_levels``), so that it resolves the contact edge from first touch
to the largest load.  Plastic contacts are wider than elastic ones at the
same interference: the candidate contact zone is larger
(``INELASTIC_CANDIDATE_FACTOR``) and grows if reached, but the mesh is
not refined again.

Step control: a step is rejected and retried with half the time step
(counted in ``step_cuts``) when Newton does not converge (or gives
non-finite values), or when the step is too coarse: the interference
changed by more than ``max_interference_step`` times the largest
interference, or the equivalent inelastic strain changed somewhere by more
than ``max_inelastic_step``.  After an accepted step the time step grows
(x ``GROWTH``) when Newton converged in few iterations and shrinks when it
needed many, within those limits.  A step that would cross a knot of the
history ends on it.

Unloading: the history is followed in reverse.  The first time the force
falls to zero on unloading, the crossing is located by bisection of the
step (to ``event_tolerance`` of the largest interference) and the residual
interference is reported by linear interpolation of the force of the last
steps (attribute ``residual_interference``, NaN if the force never returned
to zero); with ``stop_at_zero_force`` (default) the run stops there, else
it follows the rest of the history.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
import xarray as xr

from .contact import PENALTY_FACTOR, C1Penalty, ContactZone, contact_edge
from .errors import ContactZoneError, ConvergenceError
from .material import METRIC, LinearElastic, equivalent_strain, von_mises
from .presets import resolve
from .solve import _check_levels, _dataset, adapted_model

#: a point counts as having yielded once its equivalent inelastic strain
#: exceeds this
INELASTIC_THRESHOLD = 1e-8
#: on unloading, a force below this fraction of the largest force counts as zero
ZERO_FORCE = 1e-6
#: small strain limit of report 7.3 (largest principal strain magnitude)
SMALL_STRAIN_LIMIT = 0.08
#: time step growth after a fast Newton (<= FAST iterations), shrink after a slow one
GROWTH, FAST, SLOW, SHRINK = 1.5, 4, 10, 0.7
#: default levels of the one-off mesh adaptation: MESH_LEVELS interferences
#: from MESH_RANGE x the largest one to the largest
MESH_LEVELS, MESH_RANGE = 6, 0.01
#: the candidate contact zone of an inelastic body: this multiple of the
#: geometric intersection radius at the largest interference (plastic
#: pile-up may lift the surface beyond it); grown if reached.
INELASTIC_CANDIDATE_FACTOR = 1.5


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


def elastic_part(material) -> LinearElastic:
    """The elastic constants of an inelastic material, for meshing."""
    return LinearElastic(material.E, material.nu)


class _StepFailed(Exception):
    def __init__(self, message: str, iterations: int = 0):
        super().__init__(message)
        self.iterations = iterations


class InelasticModel:
    """Full (uncondensed) Newton on a fixed mesh with per point state."""

    def __init__(self, disc, geometry, material, preset: dict, r_candidate: float,
                 penalty_factor: float = PENALTY_FACTOR, tolerance: float | None = None):
        self.disc = disc
        self.geometry = geometry
        self.material = material
        self.preset = preset
        self.penalty_factor = float(penalty_factor)
        self.tolerance = preset["tolerance"] if tolerance is None else float(tolerance)
        self.max_iterations = preset["max_iterations"]
        self.Bsp = disc.strain_operator()
        self.free = disc.free
        self.shape = disc.weights.shape  # (ne, nq)
        self.W4 = (METRIC[:, None, None] * disc.weights[None]).ravel()
        self._absBT = abs(self.Bsp).T.tocsr()
        self._pattern()
        self._set_zone(r_candidate)

    def _pattern(self):
        """Sparsity of the free-free tangent, built once (CSC), and the map of
        every element matrix entry to its slot (entries on fixed dofs dropped)."""
        disc = self.disc
        n = len(self.free)
        pos = np.full(disc.ndofs, -1)
        pos[self.free] = np.arange(n)
        self._pos = pos
        ed = pos[disc.element_dofs]  # (12, ne)
        rows = np.broadcast_to(ed[:, None, :], (ed.shape[0],) + ed.shape)
        cols = np.broadcast_to(ed[None, :, :], (ed.shape[0],) + ed.shape)
        # element matrices are stored (ne, 12, 12): entry order e, i, j
        rows = np.moveaxis(rows, 2, 0).ravel()
        cols = np.moveaxis(cols, 2, 0).ravel()
        keep = (rows >= 0) & (cols >= 0)
        key = cols[keep].astype(np.int64) * n + rows[keep]
        ukey, inverse = np.unique(key, return_inverse=True)
        self._keep = keep
        self._slot = inverse
        self._nnz = len(ukey)
        self._indices = (ukey % n).astype(np.int32)
        counts = np.bincount(ukey // n, minlength=n)
        self._indptr = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        self._keys = ukey
        self._n = n
        # strain-displacement matrices per point (ne, nq, 4, 12) for batched matmul
        self._Bm = np.ascontiguousarray(np.transpose(disc.B, (2, 3, 0, 1)))
        self._BtW = np.ascontiguousarray(np.swapaxes(
            self._Bm * (METRIC[:, None] * disc.weights[:, :, None, None]), 2, 3))  # (ne, nq, 12, 4)

    def _contact_slots(self):
        """Slots of the contact (facet) couplings of the zone's u_z dofs."""
        zone = self.zone
        fn = zone.facet_nodes
        g = self._pos[zone.dofs][fn]  # (3, nf) free positions
        ii = np.broadcast_to(g[:, None, :], (3, 3, g.shape[1])).ravel()
        jj = np.broadcast_to(g[None, :, :], (3, 3, g.shape[1])).ravel()
        if np.any(ii < 0):
            raise RuntimeError("a contact dof is fixed by the supports")
        key = jj.astype(np.int64) * self._n + ii
        slot = np.searchsorted(self._keys, key)
        if np.any(self._keys[np.minimum(slot, self._nnz - 1)] != key):
            raise RuntimeError("contact couplings outside the element pattern")
        return slot

    def _set_zone(self, r_candidate: float):
        top = self.disc.top
        outer = top.coords[0, 2::2]
        nf = int(np.searchsorted(outer, r_candidate)) + 1
        nf = max(2, min(nf, top.nfacets - 1))
        self.r_candidate = float(outer[nf - 1])
        self.zone = ContactZone(top, nf, self.geometry)
        self.law = C1Penalty.for_zone(self.zone, self.material.contact_modulus,
                                      self.penalty_factor)
        self._cslot = self._contact_slots()

    def grow_zone(self) -> bool:
        if self.zone.nfacets >= self.disc.top.nfacets - 1:
            return False
        self._set_zone(1.5 * self.r_candidate)
        return True

    @property
    def dofs(self) -> int:
        return len(self.free)

    # --- residual and tangent ------------------------------------------------
    def _contact(self, u, w):
        zone = self.zone
        a = zone.penetration(u[zone.dofs], w)
        t, dt = self.law.traction(a)
        return a, t, dt

    def evaluate(self, u, w, state, dt, tangent=True):
        """Residual (ndofs,) and the fields (with the point tangents ``D``)."""
        disc = self.disc
        strain = disc.strain(u)
        stress, D, new = self.material.update(strain, state, dt, tangent=tangent)
        f_int = self.Bsp.T @ (stress.ravel() * self.W4)
        _, t, tn = self._contact(u, w)
        R = f_int
        R[self.zone.dofs] += self.zone.nodal(t)
        out = dict(strain=strain, stress=stress, state=new, traction=t, D=D, dtraction=tn)
        return R, out

    def jacobian(self, out) -> sp.csc_matrix:
        """Consistent tangent on the free dofs: material plus contact penalty."""
        D = np.asarray(out["D"])
        if D.ndim == 2:
            D = np.broadcast_to(D[:, :, None, None], (4, 4) + self.shape)
        Dm = np.transpose(D, (2, 3, 0, 1))  # (ne, nq, 4, 4)
        DB = np.matmul(Dm, self._Bm)  # (ne, nq, 4, 12)
        ne, nq = self.shape
        Ke = np.matmul(self._BtW.transpose(0, 2, 1, 3).reshape(ne, -1, nq * 4),
                       DB.reshape(ne, nq * 4, -1))  # (ne, 12, 12)
        data = np.bincount(self._slot, weights=Ke.ravel()[self._keep], minlength=self._nnz)
        zone = self.zone
        q = out["dtraction"] * zone.weights
        vals = np.einsum("fg,ig,jg->ijf", q, zone.N, zone.N)
        data += np.bincount(self._cslot, weights=vals.ravel(), minlength=self._nnz)
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(self._n, self._n))

    def jacobian_reference(self, out) -> sp.csc_matrix:
        """The same tangent by the general assembly (`Discretization.stiffness`)."""
        K = self.disc.stiffness(np.asarray(out["D"]))
        zd = self.zone.dofs
        Kc = sp.coo_matrix(self.zone.matrix(out["dtraction"]))
        K = K + sp.csr_matrix((Kc.data, (zd[Kc.row], zd[Kc.col])), shape=K.shape)
        return K[self.free][:, self.free].tocsc()

    def solve_step(self, u0, w, state, dt):
        """Newton from u0 for the step ending at interference w; returns (u, out, its)."""
        free = self.free
        u = np.array(u0, float)
        R, out = self.evaluate(u, w, state, dt)
        scale = None
        for it in range(self.max_iterations + 1):
            Rf = R[free]
            rn = float(np.linalg.norm(Rf))
            if not np.isfinite(rn):
                raise _StepFailed("non-finite residual", it)
            conv = getattr(out["state"], "converged", None)
            if conv is not None and not np.all(conv):
                raise _StepFailed("local constitutive update did not converge", it)
            fc = float(np.linalg.norm(self.zone.nodal(out["traction"])))
            if scale is None or fc > scale:
                scale = fc
            # round-off of the internal forces (sum of |terms|)
            floor = 1e3 * np.finfo(float).eps * float(np.linalg.norm(
                (self._absBT @ np.abs(out["stress"].ravel() * self.W4))[free]))
            if rn <= max(self.tolerance * scale, floor) or (scale == 0.0 and rn <= floor):
                return u, out, it
            if it == self.max_iterations:
                break
            Kff = self.jacobian(out)
            try:
                d = spl.spsolve(Kff, -Rf)
            except Exception as exc:  # singular
                raise _StepFailed(f"linear solve failed: {exc}", it) from None
            if not np.all(np.isfinite(d)):
                raise _StepFailed("non-finite Newton correction", it)
            # backtracking on the residual norm (a few halvings at most)
            alpha = 1.0
            for _ in range(6):
                trial = u.copy()
                trial[free] += alpha * d
                R1, out1 = self.evaluate(trial, w, state, dt)
                r1 = np.linalg.norm(R1[free])
                if np.isfinite(r1) and r1 < rn:
                    break
                alpha *= 0.5
            u, R, out = trial, R1, out1
        raise _StepFailed(f"no convergence in {self.max_iterations} iterations",
                          self.max_iterations)

    # --- outputs -------------------------------------------------------------
    def record(self, u, w, out) -> dict:
        zone = self.zone
        t = out["traction"]
        force = zone.total(t)
        radius = 0.0
        if force > 0:
            pen = zone.node_penetration(u[zone.dofs], w)
            radius = contact_edge(zone.coords[0], -pen, pen > 0)
        strain, stress, state = out["strain"], out["stress"], out["state"]
        e11, e22, e33, e12 = strain
        c = 0.5 * (e11 + e22)
        rad = np.sqrt((0.5 * (e11 - e22)) ** 2 + e12**2)
        principal = np.max(np.stack((np.abs(c + rad), np.abs(c - rad), np.abs(e33))))
        return dict(
            interference=w,
            force=force,
            contact_radius=radius,
            contact_area=math.pi * radius**2 if self.geometry.axisymmetric else 2 * radius,
            max_equivalent_strain=float(equivalent_strain(strain).max()),
            max_inelastic_strain=float(equivalent_strain(state.inelastic_strain).max()),
            max_von_mises=float(von_mises(stress).max()),
            max_principal_strain=float(principal),
            overflow=bool(np.any(t[-1] > 0)),
        )


def _zero_force_crossing(rows) -> float:
    """Interference where the unloading force reaches zero.

    The last step has F ~ 0 (the penalty force vanishes once the surface
    separates; below ``ZERO_FORCE`` x the largest force counts as zero: the
    smoothed penalty leaves a vanishing force at first touch), so the force
    of the last two steps before it is extrapolated linearly to zero, the
    result kept between the last of them and the zero-force step.
    """
    b, a = rows[-1], rows[-2]
    lo, hi = sorted((b["interference"], a["interference"]))
    est = b["interference"]
    if len(rows) >= 3 and rows[-3]["force"] > a["force"] > 0:
        c = rows[-3]
        slope = (c["force"] - a["force"]) / (c["interference"] - a["interference"])
        if slope > 0:
            est = a["interference"] - a["force"] / slope
    return float(np.clip(est, lo, hi))


VARIABLES = {
    "time": ("s", "time"),
    "interference": ("m", "interference of the rigid flat (approach from first touch)"),
    "force": ("N", "total contact force"),
    "contact_area": ("m^2", "real contact area pi a^2"),
    "contact_radius": ("m", "contact radius a (edge located between nodes)"),
    "max_equivalent_strain": ("1", "largest von Mises equivalent total strain at the quadrature points"),
    "max_inelastic_strain": ("1", "largest von Mises equivalent inelastic strain at the quadrature points"),
    "max_von_mises": ("Pa", "largest von Mises stress at the quadrature points"),
    "elastic": ("1", f"no equivalent inelastic strain above {INELASTIC_THRESHOLD:g} anywhere"),
    "small_strain": ("1", f"largest principal strain magnitude below {SMALL_STRAIN_LIMIT:g} everywhere (report 7.3)"),
    "branch": ("1", "'loading' or 'unloading' segment of the history"),
    "newton_iterations": ("1", "Newton iterations of the step, including those of rejected tries"),
    "step_cuts": ("1", "times the step was rejected and its time step halved"),
    "time_step": ("s", "time step of the accepted step"),
    "dofs": ("1", "degrees of freedom (unknown displacement components)"),
    "wall_time": ("s", "wall time of the step, including its rejected tries"),
}

def solve_asperity_history(geometry, material, history: History, accuracy="standard",
                           initial_time_step: float | None = None,
                           max_time_step: float | None = None,
                           max_interference_step: float = 0.025,
                           max_inelastic_step: float = 2e-3,
                           max_cuts: int = 20, max_steps: int = 100_000,
                           stop_at_zero_force: bool = True,
                           event_tolerance: float = 1e-3,
                           penalty_factor: float | None = None,
                           tolerance: float | None = None,
                           mesh_levels=None) -> xr.Dataset:
    """Incremental solution of an inelastic asperity along `history`.

    Parameters
    ----------
    geometry
        a `Profile`.
    material
        an inelastic material with ``initial_state(shape)`` and
        ``update(strain, state, dt, tangent=True)`` (`J2Plasticity`,
        `BodnerPartom`).
    history
        `History`: the interference [m] as a piecewise linear function of
        time [s]; the body is stress free at its start (w <= 0: first
        touch at w = 0).
    accuracy
        preset name or dict (`presets.ACCURACY`); sets the mesh (adapted
        once, to elastic solutions at ``mesh_levels``) and the Newton
        tolerance and iteration limit.
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
        this anywhere (else rejected and cut).
    max_cuts
        rejections allowed per step before `ConvergenceError`.
    max_steps
        stop after this many accepted steps (attribute ``completed`` 0).
    event_tolerance
        see ``stop_at_zero_force``.
    penalty_factor
        c in kappa = c E' / h (default `contact.PENALTY_FACTOR`).
    tolerance
        Newton: ||R|| <= tolerance ||f_contact|| (default: the preset's),
        or the round-off level of the internal forces.
    mesh_levels
        interferences [m] driving the one-off adaptive meshing (elastic
        solutions, `solve.adapted_model`); default ``MESH_LEVELS`` levels
        spread geometrically from ``MESH_RANGE`` x the largest interference
        to the largest, so that the mesh also resolves the small contacts of
        first touch and of the end of unloading.
    stop_at_zero_force
        on unloading, stop once the force vanishes (falls below
        ``ZERO_FORCE`` x the largest force; the crossing is
        located to ``event_tolerance`` x largest interference either way).

    Returns an `xarray.Dataset` on dim ``step`` (variables in `VARIABLES`,
    step 0 the initial untouched state) with attributes including
    ``residual_interference`` (NaN if the force never returned to zero),
    ``steps``, ``total_step_cuts`` and ``total_wall_time``.
    """
    t_start = time.perf_counter()
    preset = resolve(accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    knots_w = np.asarray(history.interferences, float)
    w_max = float(knots_w.max())
    if not w_max > 0:
        raise ValueError("the history never presses the flat onto the asperity (max w <= 0)")
    _check_levels(geometry, [w_max])
    if not hasattr(material, "update"):
        raise TypeError("material must have initial_state/update (an inelastic material)")

    # --- mesh: adapted once to the elastic solution at the largest w --------
    if mesh_levels is None:
        mesh_levels = np.geomspace(MESH_RANGE * w_max, w_max, MESH_LEVELS)
    mesh_levels = _check_levels(geometry, mesh_levels)
    emodel, _ = adapted_model(geometry, elastic_part(material), mesh_levels, preset, "penalty",
                              factor)
    rg = float(geometry.intersection_radius(np.array([w_max]))[0])
    r_cand = max(INELASTIC_CANDIDATE_FACTOR * rg, emodel.r_candidate)
    model = InelasticModel(emodel.disc, geometry, material, preset, r_cand, factor, tolerance)
    t_mesh = time.perf_counter() - t_start

    # --- time stepping ---------------------------------------------------------
    t_end = history.end
    dw_max = max_interference_step * w_max
    slopes = np.abs(np.diff(knots_w)) / np.diff(np.asarray(history.times, float))
    vmax = float(slopes.max()) if slopes.max() > 0 else w_max / t_end
    dt = initial_time_step if initial_time_step is not None else 0.25 * dw_max / vmax
    dt_cap = math.inf if max_time_step is None else float(max_time_step)
    if not dt > 0:
        raise ValueError("initial_time_step must be positive")

    t = float(history.times[0])
    w = float(history(t))
    state = material.initial_state(model.shape)
    u = np.zeros(model.disc.ndofs)
    u_prev, t_prev = None, None
    rows = []
    eps_n = np.zeros(model.shape)

    def append(rec, **extra):
        rec.update(extra)
        rows.append(rec)

    # initial state (assumed stress free, w <= 0 or first touch)
    _, out0 = model.evaluate(u, w, state, 0.0, tangent=False)
    append(model.record(u, w, out0), time=t, branch=history.branch(t), newton_iterations=0,
           step_cuts=0, time_step=0.0, wall_time=0.0)
    residual = math.nan
    f_max = 0.0
    n = 0
    while t < t_end * (1 - 1e-12) and n < max_steps:
        n += 1
        step_start = time.perf_counter()
        cuts = 0
        iterations = 0
        branch = history.branch(t)
        while True:
            dt_try = min(dt, dt_cap)
            knot = history.next_knot(t)
            t_new = min(t + dt_try, knot)
            if knot - t_new < 1e-9 * (knot - t):  # snap onto the knot
                t_new = knot
            h = t_new - t
            w_new = float(history(t_new))
            reason = None
            if abs(w_new - w) > dw_max * (1 + 1e-9):
                reason = "interference step too large"
            else:
                # predictor: extrapolate the last increment on the same branch
                u0 = u.copy()
                if u_prev is not None and rows[-1]["branch"] == branch and t - t_prev > 0:
                    u0 += (h / (t - t_prev)) * (u - u_prev)
                try:
                    u_new, out, its = model.solve_step(u0, w_new, state, h)
                    iterations += its
                    eps_new = equivalent_strain(out["state"].inelastic_strain - state.inelastic_strain)
                    if float(np.max(eps_new)) > max_inelastic_step:
                        reason = "inelastic strain step too large"
                except _StepFailed as exc:
                    iterations += exc.iterations
                    reason = str(exc)
            if reason is None:
                rec = model.record(u_new, w_new, out)
                if rec["overflow"]:
                    if not model.grow_zone():
                        raise ContactZoneError("the contact reached the outer edge of the top surface")
                    continue  # same step on the larger zone (not a cut)
                f_zero = ZERO_FORCE * f_max
                if (branch == "unloading" and rec["force"] <= f_zero
                        and rows[-1]["force"] > f_zero and math.isnan(residual) and abs(w_new - w) > event_tolerance * w_max):
                    dt = 0.5 * h  # locate the zero force crossing: not a cut
                    continue
                break
            cuts += 1
            if cuts > max_cuts:
                raise ConvergenceError(n, w_new, w, cuts - 1, reason)
            dt = 0.5 * h
        # accept
        u_prev, t_prev = u, t
        u, t, w, state = u_new, t_new, w_new, out["state"]
        append(rec, time=t, branch=branch, newton_iterations=iterations, step_cuts=cuts,
               time_step=h, wall_time=time.perf_counter() - step_start)
        # next time step
        if iterations <= FAST and cuts == 0:
            dt = GROWTH * h
        elif iterations >= SLOW:
            dt = SHRINK * h
        else:
            dt = h
        v = history.velocity(t)
        if v > 0:
            dt = min(dt, dw_max / v)
        eps_step = float(np.max(eps_new))
        if eps_step > 0:
            dt = min(dt, h * max(0.5, 0.8 * max_inelastic_step / eps_step))
        f_zero = ZERO_FORCE * f_max
        f_max = max(f_max, rec["force"])
        if branch == "unloading" and rec["force"] <= f_zero and rows[-2]["force"] > f_zero \
                and math.isnan(residual):
            residual = _zero_force_crossing(rows)  # the first crossing only
            if stop_at_zero_force:
                break

    total = time.perf_counter() - t_start
    k = len(rows)
    rec = {}
    for name in VARIABLES:
        if name == "dofs":
            rec[name] = np.full(k, model.dofs)
        elif name == "elastic":
            rec[name] = np.array([r["max_inelastic_strain"] <= INELASTIC_THRESHOLD for r in rows])
        elif name == "small_strain":
            rec[name] = np.array([r["max_principal_strain"] < SMALL_STRAIN_LIMIT for r in rows])
        else:
            rec[name] = np.array([r[name] for r in rows])
    ds = _dataset(
        rec, geometry, material, accuracy, preset, "penalty", factor,
        "fixed, adapted once to the elastic solution at the largest interference",
        variables=VARIABLES, step_name="time step index", methods=False,
        extra_attrs=dict(
        history_times=np.asarray(history.times, float),
        history_interferences=knots_w,
        steps=k - 1,
        total_step_cuts=int(sum(r["step_cuts"] for r in rows)),
        residual_interference=float(residual),
        residual_interference_method="linear extrapolation to zero of the force of the last two "
                                     "unloading steps with force > 0, within the crossing step "
                                     "(located to event_tolerance)",
        completed=int(t >= t_end * (1 - 1e-12) or not math.isnan(residual)),
        mesh_wall_time=t_mesh,
        total_wall_time=total,
    ))
    return ds
