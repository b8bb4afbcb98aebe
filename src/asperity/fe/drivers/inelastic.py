"""Inelastic asperity: incremental (rate) solution along a prescribed history.

An inelastic body (report 3.2.2: `J2Plasticity` or `BodnerPartom`) pressed
by the rigid flat, whose interference is a prescribed piecewise linear
function of time (`History`, e.g. `History.load_unload`: loading at a
prescribed velocity, 0.25 um/s in report 8.2.2, then unloading).

Method (the incremental counterpart of report 3.22, in the implicit form
that FE codes use): the time is divided into steps; at each step the
global equilibrium

    R(u) = int B^T sigma(eps(u); state_n, dt) dV + int t_N(a(u)) N ds = 0

is solved by Newton on the *full* system (all free dofs, no condensation,
which only holds for a linear body) with the material's consistent tangent
at the quadrature points plus the penalty contact tangent.  Internal
variables are carried per quadrature point and committed only when the
step is accepted.  Everything is vectorized over elements and quadrature
points (`Discretization.B`, sparse strain operator, one batched matmul for
the element matrices scattered into a sparsity pattern built once).

The mesh follows the contact where the preset's ``remesh`` key is on
(`remesh`; off in the built-in presets): it is refined around the current contact edge and plastic
zone only, rebuilt when the edge leaves the band of radii it resolves or
the plastic zone the region refined for it, the state at the start of the
step transferred to the new mesh (displacements, every field of the
material state, the flow rates of the time-error estimate) and the step
re-solved on it, with backward Euler (like after a knot).  With ``remesh``
off the mesh is FIXED: it is adapted once, by the existing machinery
(`solve.adapted_model` with the material's elastic constants), to elastic
solutions at a few interferences up to the largest of the history
(``mesh_levels``), so that it resolves the contact edge from first touch
to the largest load, and with the preset key ``edge_size`` refined along
the surface where the wider plastic edge goes (`remesh.edge_band`).  Either
way, plastic contacts are wider than elastic ones at the same interference:
the candidate contact zone is larger (``INELASTIC_CANDIDATE_FACTOR``) and
grows if reached.

Time integration of the material (report 3.6).  The material's own update
is backward Euler (BE): y_n+1 = y_n + dt f(y_n+1) for the internal
variables y (inelastic strain, hardness, damage).  For a rate-dependent
material (one with ``rates``: `BodnerPartom`) the solver makes it second
order, the variable-step BDF2

    y_n+1 = a y_n - b y_n-1 + c h f(y_n+1),   omega = h / h_prev,
    a = (1 + omega)^2 / (1 + 2 omega), b = omega^2 / (1 + 2 omega),
    c = (1 + omega) / (1 + 2 omega),

which is the material's backward-Euler update from the start value
y* = a y_n - b y_n-1 over c h (`bdf2_start`): no change to the material,
and the consistent tangent stays exact.  BDF2 is L-stable like BE (stiff
flow at fast-flowing points is damped, not oscillating) and stable for
step ratios below 1 + sqrt 2 (the controller grows the step at most
twofold).  The first step and the first step after a knot of the history
(where the loading rate jumps) are BE.  ``integration="euler"`` keeps BE
throughout.  A rate-independent material (`J2Plasticity`) has no time
scale: its "time" is a load parameter, its inelastic rate jumps at first
yield, at every knot and wherever a point starts or stops yielding, and
BE is its return map; it is integrated by BE and its steps are not
estimated (``time_error`` NaN): ``max_interference_step`` and
``max_inelastic_step`` control them.

Time-integration error (report 3.4, 3.33-3.36, carried over to the
implicit schemes).  The rate of the flow rule at the end of a step is
r_n+1 = (y_n+1 - y*) / (c h) (the material's increment over its time
step); the rates at the ends of the last steps give the local truncation
error of the step:

    BE:    e = h (r_n+1 - r_n) / 2 = (h^2 / 2) y'',  the difference between
           the backward-Euler increment and the trapezoidal one
           h (r_n + r_n+1) / 2 (the report's predictor-corrector
           difference, 3.36, for an implicit step);
    BDF2:  e = k h^3 y''',  k = (1 + omega)^2 / (6 omega (1 + 2 omega)),
           y''' the second divided difference of r_n-1, r_n, r_n+1.

The error of the inelastic strain is measured by what it does to the
equilibrium: the nodal forces of the stress error 2 G e (the inelastic
strain is deviatoric), relative to the contact forces, the measure of the
Newton residual; the error of the damage kappa (3.15) by the largest
|e_kappa| relative to its rupture value.  Ruptured points are left out.
The indicator of the step is

    E = max( ||B^T (2 G e) dV|| / ||f_contact||,  max |e_kappa| / kappa_r ).

A step with E > 2 ``time_tolerance`` is rejected and retried with the time
step h 0.9 (tol / E)^(1/(p+1)) (p the order, at least 0.2 h); after an
accepted step the time step becomes h min(2, 0.9 (tol / E)^(1/(p+1))).
(Rejecting only above twice the tolerance: the estimate jumps when a node
of the surface comes into contact, and rejecting at the tolerance takes
more steps for no gain in accuracy.)  E is recorded per step
(``time_error``), its largest value and the rejections it caused as
attributes.  With local error control the error of the end of the
history falls roughly in proportion to the tolerance
(tests/fe/test_inelastic_time_error.py).  The Newton tolerance of a
rate-dependent material is 1e-2 ``time_tolerance`` where that is looser
than the preset's (``NEWTON_FRACTION``): equilibrium two orders tighter
than the time error of a step, in the same measure.  Newton's scale is
the contact force of the current iterate (not the largest of the
iterations: an overshooting predictor pushes a node deep into the stiff
penalty and would inflate it), or, if larger, up to twice that of the last
accepted step.

Other step control (the steps are marched by `march.march`): a step is
rejected and retried with half the time step (counted in ``step_cuts``, with
the error rejections) when Newton does not converge (or gives non-finite
values), or when the step is too coarse for the output: the interference
changed by more than ``max_interference_step`` times the largest interference,
or the equivalent inelastic strain changed somewhere by more than
``max_inelastic_step`` (a safety bound; the error control decides). Slow
Newton convergence shrinks the next time step. A step that would cross a knot
of the history ends on it.

Points with negligible flow (`InelasticModel.point_time_steps`): a
rate-dependent material flows at every stressed point, but the exponential
flow law of Bodner-Partom makes the flow of most of the body vanishingly
small; the material update treats those points as elastic (time step 0),
which saves their local Newton iterations and tangents.

Rupture (Bodner-Partom with damage, 3.15: w -> 1).  `BodnerPartom` declares
a point ruptured when w reaches ``omega_rupture`` or its inelastic strain
rate runs away past ``rupture_strain_rate``, then freezes its damage and
keeps a finite, softened state (Z sqrt(1 - w^2)).  The solver reports the
first rupture (step, time, interference and the position of the point:
attributes ``rupture_*``) and the number of ruptured points per step
(``ruptured_points``), and, by ``on_rupture``, continues (default: the
ruptured points keep the state the material gives them and are left out
of the time error), stops there (``"stop"``: the dataset ends at the
rupture step, ``completed`` 0, ``stop_reason`` says why), or raises
`RuptureError` naming the step, the interference and the position
(``"raise"``).  A Newton failure after a rupture says how many points
had ruptured.

Unloading: the history is followed in reverse.  The first time the force
falls to zero on unloading, the crossing is located by bisection of the
step (to ``event_tolerance`` of the largest interference) and the residual
interference is reported by linear interpolation of the force of the last
steps (attribute ``residual_interference``, NaN if the force never returned
to zero); with ``stop_at_zero_force`` (default) the run stops there, else
it follows the rest of the history.

Linear solves: SuperLU with a symmetric minimum degree ordering of the
(structurally symmetric) tangent and diagonal pivots; if that fails or is
not finite, the default partial pivoting.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, fields, replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
import xarray as xr

from asperity.fe.solvers import nonlinear
from asperity.fe.discretization.assembly import Discretization, OrderedLU
from asperity.fe.contact.penalty import (EDGE_FROM_PRESSURES, PENALTY_FACTOR, C1Penalty,
                                         ContactZone, contact_edge_pressure)
from asperity.fe.errors import ContactZoneError, RuptureError, StepFailed
from asperity.fe.discretization.kinematics import KINEMATICS, SmallStrain, kinematics_for
from asperity.fe.materials.elastic import LinearElastic, equivalent_strain, von_mises
from asperity.fe.solvers.nonlinear import (Pace, Problem, ResidualSearch, check_local_update,
                                           strain_limited)
from asperity.fe.outputs import INELASTIC_THRESHOLD, SMALL_STRAIN_LIMIT, dataset
from asperity.io.run_report import StepProgress

from asperity.fe.presets import resolve
from asperity.fe.drivers.remesh import EDGE_BAND, ContactMeshes, Transfer, edge_band
from asperity.fe.drivers.elastic import adapted_model, check_levels, run_attrs
from asperity.fe.drivers.march import Accepted, Marching, Trial, march

log = logging.getLogger(__name__)

#: on unloading, a force below this fraction of the largest force counts as zero
ZERO_FORCE = 1e-6
#: time-error controller: safety factor, largest growth, smallest factor, and
#: a step is rejected when its indicator exceeds REJECT x the tolerance
SAFETY, MAX_GROWTH, MIN_FACTOR, REJECT = 0.9, 2.0, 0.2, 2.0
#: Newton's say on the next time step: no growth after more than 4
#: iterations, a shrink by 0.7 after 10 or more
PACE = Pace(fast=4, growth=MAX_GROWTH, slow=10, shrink=0.7)
#: the iterations that `PACE` counts are those to a residual of this x the
#: contact forces (or to the step's own tolerance, if looser): a tighter Newton
#: tolerance (the 'fine' preset's 1e-10) polishes a converged step and says
#: nothing of whether the step was too long, so it does not keep the steps short
PACE_TOLERANCE = 1e-8
#: default time tolerance when the accuracy preset has none
TIME_TOLERANCE = 0.1
#: Newton tolerance of a rate-dependent material: this x time_tolerance where
#: that is looser than the preset's
NEWTON_FRACTION = 1e-2
#: points with negligible flow (see InelasticModel.point_time_steps)
FLOW_STRESS_MARGIN, NEGLIGIBLE_FLOW = 1.25, 1e-9
#: default levels of the one-off mesh adaptation: MESH_LEVELS interferences
#: from MESH_RANGE x the largest one to the largest
MESH_LEVELS, MESH_RANGE = 6, 0.01
#: the candidate contact zone of an inelastic body: this multiple of the
#: geometric intersection radius at the largest interference (plastic
#: pile-up may lift the surface beyond it); grown if reached.
INELASTIC_CANDIDATE_FACTOR = 1.5
#: Newton's line search: the residual norm, halved at most this many times
LINE_SEARCH = ResidualSearch(halvings=6)
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


def elastic_part(material) -> LinearElastic:
    """The elastic constants of an inelastic material, for meshing."""
    return LinearElastic(material.E, material.nu)


class InelasticModel:
    """Full (uncondensed) Newton on a fixed mesh with per point state."""

    def __init__(self, disc, geometry, material, preset: dict, r_candidate: float,
                 penalty_factor: float = PENALTY_FACTOR, tolerance: float | None = None,
                 kinematics: str = "small"):
        self.disc = disc
        self.geometry = geometry
        self.material = material
        self.preset = preset
        self.penalty_factor = float(penalty_factor)
        self.tolerance = preset["tolerance"] if tolerance is None else float(tolerance)
        self.max_iterations = preset["max_iterations"]
        self.kinematics = kinematics_for(disc, kinematics)
        # the linear kinematics also measure round-off and the time error
        self.linear = self.kinematics if not self.kinematics.finite else SmallStrain(disc)
        self.free = disc.free
        self.shape = disc.weights.shape  # (ne, nq)
        self._absBT = abs(self.linear.Bsp).T.tocsr()
        self._pattern()
        self._set_zone(r_candidate)
        self.factorizations = 0
        self._lu = OrderedLU(diag_pivot_thresh=0.0)

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
        self._keep = np.flatnonzero(keep)
        self._slot = inverse
        self._nnz = len(ukey)
        self._indices = (ukey % n).astype(np.int32)
        counts = np.bincount(ukey // n, minlength=n)
        self._indptr = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        self._keys = ukey
        self._n = n

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
        strain, deformation = self.kinematics.strain(u)
        dtp = self.point_time_steps(strain, state, dt)
        stress, D, new = self.material.update(strain, state, dtp, tangent=tangent)
        if dtp is not dt and hasattr(new, "time"):
            new.time = state.time + dt
        R = self.kinematics.internal_force(deformation, stress)
        _, t, tn = self._contact(u, w)
        R[self.zone.dofs] += self.zone.nodal(t)
        out = dict(strain=strain, stress=stress, state=new, traction=t, D=D, dtraction=tn,
                   deformation=deformation)
        return R, out

    def point_time_steps(self, strain, state, dt):
        """The time step of each point: `dt` where the material may flow, 0
        where its flow over the step is negligible, so that the material
        update treats those points as elastic (a rate-dependent material
        flows at every stressed point; the exponential flow law of
        Bodner-Partom makes most of the body's flow vanishingly small).

        Negligible: the inelastic strain the flow rule gives over dt at
        ``FLOW_STRESS_MARGIN`` times the elastic trial stress (an upper
        bound: the flow relaxes the stress and hardens) makes a Mises stress
        below ``NEGLIGIBLE_FLOW`` times the largest trial stress.
        """
        mat = self.material
        if not (np.ndim(dt) == 0 and dt > 0 and hasattr(mat, "rates")):
            return dt
        trial = np.tensordot(mat.tangent(), strain - state.inelastic_strain, axes=(1, 0))
        probe = replace(state, stress=FLOW_STRESS_MARGIN * trial)
        flow = equivalent_strain(mat.rates(probe)["inelastic_strain"]) * dt
        q = von_mises(trial)
        negligible = 3.0 * mat.G * flow <= NEGLIGIBLE_FLOW * float(np.max(q))
        if not np.any(negligible):
            return dt
        return np.where(negligible, 0.0, dt)

    def jacobian(self, out) -> sp.csc_matrix:
        """Consistent tangent on the free dofs: material plus contact penalty."""
        Ke = self.kinematics.element_matrices(out["deformation"], out["stress"], out["D"])
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

    def factorize(self, out):
        """LU factors of the consistent tangent at `out`: SuperLU with a
        symmetric ordering, kept for the mesh's pattern (`OrderedLU`), and
        diagonal pivots (the tangent is structurally symmetric, nearly always
        symmetric positive definite), or, if that fails, with the default
        partial pivoting.  Returns (lu, K, pivoted)."""
        K = self.jacobian(out)
        self.factorizations += 1
        try:
            with np.errstate(all="ignore"):
                return self._lu.factor(K), K, False
        except RuntimeError:
            return spl.splu(K), K, True

    def newton_correction(self, out, Rf):
        """The Newton correction d: K d = -R with the tangent at `out`."""
        lu, K, pivoted = self.factorize(out)
        with np.errstate(all="ignore"):
            d = lu.solve(-Rf)
        if not np.all(np.isfinite(d)) and not pivoted:
            d = spl.splu(K).solve(-Rf)
        return d

    def solve_step(self, u0, w, state, dt, reference: float = 0.0):
        """Newton from u0 for the step ending at interference w; returns (u, out,
        its, paced): paced the iterations to ``PACE_TOLERANCE`` (or to the
        tolerance, if looser), the count the step control reads (`PACE`).

        Converged when ||R|| <= tolerance x the norm of the nodal contact
        forces: those of the current iterate, or, if larger, up to twice
        `reference` (the contact forces of the last accepted step), so that
        an overshooting predictor (a node pushed deep into the stiff
        penalty) does not inflate the scale; or at the round-off level of
        the internal forces.
        """
        step = _Step(self, w, state, dt, reference, max(self.tolerance, PACE_TOLERANCE))
        u, out, its = nonlinear.newton(step, u0, self.tolerance, self.max_iterations, LINE_SEARCH)
        return u, out, its, its if step.paced is None else step.paced

    # --- outputs -------------------------------------------------------------
    def point_position(self, index) -> tuple:
        """(r or x, depth below the undeformed top surface) [m] of quadrature
        point `index` (flat index over (ne, nq))."""
        x = self.disc.x.reshape(2, -1)[:, index]
        top = self.disc.top.coords
        depth = float(np.interp(x[0], top[0], top[1]) - x[1])
        return float(x[0]), max(depth, 0.0)

    def record(self, u, w, out) -> dict:
        zone = self.zone
        t = out["traction"]
        force = zone.total(t)
        radius = 0.0
        if force > 0:
            pen = zone.node_penetration(u[zone.dofs], w)
            radius = contact_edge_pressure(zone.coords[0], -pen, zone.node_traction(t), pen > 0)
            if self.kinematics.finite:  # the edge on the deformed surface
                top = self.disc.top
                radius += float(np.interp(radius, top.coords[0], u[top.node_r_dofs]))
        strain, stress, state = out["strain"], out["stress"], out["state"]
        e11, e22, e33, e12 = strain
        c = 0.5 * (e11 + e22)
        rad = np.sqrt((0.5 * (e11 - e22)) ** 2 + e12**2)
        principal = np.max(np.stack((np.abs(c + rad), np.abs(c - rad), np.abs(e33))))
        damage = getattr(state, "damage", None)
        ruptured = getattr(state, "ruptured", None)
        return dict(
            interference=w,
            force=force,
            contact_radius=radius,
            contact_area=math.pi * radius**2 if self.geometry.axisymmetric else 2 * radius,
            max_equivalent_strain=float(equivalent_strain(strain).max()),
            max_inelastic_strain=float(equivalent_strain(state.inelastic_strain).max()),
            max_von_mises=float(von_mises(stress).max()),
            max_principal_strain=float(principal),
            max_damage=0.0 if damage is None else float(np.max(damage)),
            ruptured_points=0 if ruptured is None else int(np.count_nonzero(ruptured)),
            overflow=bool(np.any(t[-1] > 0)),
        )


class _Step(Problem):
    """Equilibrium at the end of a step (`InelasticModel.solve_step`)."""

    def __init__(self, model: InelasticModel, w, state, dt, reference: float,
                 pace_tolerance: float):
        self.model, self.w, self.state, self.dt = model, w, state, dt
        self.force_scale = nonlinear.ContactScale(reference)
        self.pace_tolerance = pace_tolerance
        self.paced = None  # the first iteration with ||R|| <= pace_tolerance x scale

    def monitor(self, iteration, rn, scale, out):
        if self.paced is None and rn <= self.pace_tolerance * scale:
            self.paced = iteration

    def evaluate(self, u):
        R, out = self.model.evaluate(u, self.w, self.state, self.dt)
        return R[self.model.free], out

    def check(self, out, iteration):
        check_local_update(out["state"], iteration)

    def scale(self, u, out):
        return self.force_scale(float(np.linalg.norm(self.model.zone.nodal(out["traction"]))))

    def floor(self, u, out):
        """Round-off of the internal forces (sum of |terms|)."""
        m = self.model
        return 1e3 * np.finfo(float).eps * float(np.linalg.norm(
            (m._absBT @ np.abs(out["stress"].ravel() * m.linear.W4))[m.free]))

    def direction(self, u, Rf, out, tangent, iteration):
        try:
            d = self.model.newton_correction(out, Rf)
        except RuntimeError as exc:  # singular
            raise StepFailed(f"linear solve failed: {exc}", iteration) from None
        full = np.zeros_like(u)
        full[self.model.free] = d
        return full


# --- time integration and its error ---------------------------------------------
#: state fields integrated in time: combined into the start value of a BDF2 step
INTEGRATED = ("inelastic_strain", "beta", "plastic_work", "hardness_iso", "kappa")


def bdf2_coefficients(omega: float) -> tuple:
    """Variable-step BDF2 with step ratio omega = h_n / h_n-1:

        y_n+1 = a y_n - b y_n-1 + c h f(y_n+1),

    i.e. a backward-Euler step of c h from y* = a y_n - b y_n-1, and its
    local error constant k (error = k h^3 d3y/dt3).  omega = 1: (4/3, 1/3,
    2/3, 2/9)."""
    w = float(omega)
    d = 1.0 + 2.0 * w
    return (1.0 + w) ** 2 / d, w * w / d, (1.0 + w) / d, (1.0 + w) ** 2 / (6.0 * w * d)


def bdf2_start(state, previous, a: float, b: float):
    """The start value y* = a y_n - b y_n-1 of the integrated fields of a
    material state (dataclass); the other fields, and all the fields of
    ruptured points (their damage is frozen), are those of y_n."""
    ruptured = getattr(state, "ruptured", None)
    frozen = ruptured is not None and bool(np.any(ruptured))
    kw = {}
    for f in fields(state):
        v = getattr(state, f.name)
        if f.name in INTEGRATED:
            combined = a * v - b * getattr(previous, f.name)
            v = np.where(ruptured, v, combined) if frozen else combined
        kw[f.name] = v
    return type(state)(**kw)


def _rates(material, start, new, dt: float) -> dict:
    """End-of-step rates of the controlled variables: (new - start) / dt,
    the rates of the flow rule at the new state for a backward-Euler step
    of dt from `start`."""
    out = {"inelastic_strain": (new.inelastic_strain - start.inelastic_strain) / dt}
    if getattr(material, "damage", False) is True:
        out["kappa"] = (new.kappa - start.kappa) / dt
    return out


def local_errors(order: int, h: float, h_prev: float, r_new: dict, r_n: dict,
                 r_prev: dict | None) -> dict:
    """Local truncation error estimates of the step, from the rates at its end
    (r_new), at its start (r_n) and one step back (r_prev).

    Backward Euler: (h^2 / 2) d2y/dt2 = h (r_new - r_n) / 2, the difference
    between the backward-Euler and the trapezoidal increments.  BDF2:
    k h^3 d3y/dt3 with d3y/dt3 the second divided difference of the rates."""
    if order == 1:
        return {k: 0.5 * h * (r_new[k] - r_n[k]) for k in r_new}
    _, _, _, kc = bdf2_coefficients(h / h_prev)
    return {k: kc * h**3 * 2.0 * ((r_new[k] - r_n[k]) / h - (r_n[k] - r_prev[k]) / h_prev)
            / (h + h_prev) for k in r_new}


def error_indicator(model, errors: dict, out) -> float:
    """E of a step (module docstring): the nodal forces of the stress error
    2 G e of the inelastic strain error e, relative to the contact forces
    (the measure of the Newton residual), and the error of the damage
    kappa relative to its rupture value; ruptured points left out."""
    material = model.material
    new = out["state"]
    ruptured = getattr(new, "ruptured", None)
    keep = None if ruptured is None or not np.any(ruptured) else ~np.asarray(ruptured)
    e = errors["inelastic_strain"]
    if keep is not None:
        e = e * keep
    fc = float(np.linalg.norm(model.zone.nodal(out["traction"])))
    E = 0.0
    if fc > 0:
        fe = model.linear.internal_force(None, (2.0 * material.G) * e)
        E = float(np.linalg.norm(fe[model.free])) / fc
    if "kappa" in errors:
        ek = np.abs(errors["kappa"])
        if keep is not None:
            ek = ek[keep]
        if ek.size:
            E = max(E, float(np.max(ek)) / material.kappa_rupture)
    return E if np.isfinite(E) else math.inf


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
        rate-dependent material (module docstring; default: the preset's
        ``time_tolerance``, else ``TIME_TOLERANCE``); ``inf`` switches the
        control off.
    integration
        ``"bdf2"`` (default) or ``"euler"`` (backward Euler throughout) for
        a rate-dependent material.
    on_rupture
        ``"continue"`` (default), ``"stop"`` or ``"raise"`` (`RuptureError`)
        when a material point ruptures (module docstring).
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

    # --- time stepping: `march` with the steps of `_HistoryMarch`
    dw_max = max_interference_step * w_max
    slopes = np.abs(np.diff(knots_w)) / np.diff(np.asarray(history.times, float))
    vmax = float(slopes.max()) if slopes.max() > 0 else w_max / history.end
    dt = initial_time_step if initial_time_step is not None else 0.25 * dw_max / vmax
    if not dt > 0:
        raise ValueError("initial_time_step must be positive")
    run = _HistoryMarch(
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


class _HistoryMarch(Marching):
    """The steps of `solve_asperity_history` for `march`: a try solves the step's
    equilibrium with BDF2 or backward Euler and checks its interference and inelastic
    strain steps and time error; an accepted step may first be re-solved on a new mesh
    (``remesh``), then is recorded, checked for rupture and the zero-force crossing of
    unloading, and sets the next time step (module docstring)."""

    def __init__(self, model: InelasticModel, meshes: ContactMeshes, history: History, *,
                 r_candidate, tolerance, kinematics, integration, dw_max, dt_cap,
                 max_inelastic_step, max_cuts, time_tolerance, event_tolerance, w_max,
                 stop_at_zero_force, on_rupture, remesh, remesh_times, rg, progress):
        self.model, self.meshes, self.history = model, meshes, history
        # what a new mesh's model is made with (`_remeshed`)
        self.r_cand, self.tolerance, self.kinematics = r_candidate, tolerance, kinematics
        self.material = model.material
        self.rate_dependent = hasattr(self.material, "rates")
        self.integration, self.dw_max, self.dt_cap = integration, dw_max, dt_cap
        self.max_inelastic_step, self.max_cuts = max_inelastic_step, max_cuts
        self.time_tolerance, self.event_tolerance = time_tolerance, event_tolerance
        self.w_max, self.stop_at_zero_force, self.on_rupture = w_max, stop_at_zero_force, on_rupture
        self.remesh, self.rg, self.progress = remesh, rg, progress
        self.remesh_times = sorted(float(x) for x in np.atleast_1d(remesh_times))
        self.end = history.end
        self.interior_knots = np.asarray(history.times, float)[1:-1]
        self.t = float(history.times[0])
        self.w = float(history(self.t))
        # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
        self.ticker, self.t_first = StepProgress(log, "asperity history: "), self.t
        self.state = self.material.initial_state(model.shape)
        self.u = np.zeros(model.disc.ndofs)
        self.u_prev, self.t_prev = None, None
        self.rows = []
        # rates of the controlled variables at the end of the last two steps (the
        # body starts at rest), the state one step back and that step's length
        self.r_n = {k: np.zeros_like(v)
                    for k, v in _rates(self.material, self.state, self.state, 1.0).items()}
        self.r_prev, self.state_prev, self.h_prev = None, None, math.nan
        self.f_ref = 0.0  # contact force norm of the last accepted step
        # initial state (assumed stress free, w <= 0 or first touch)
        _, out0 = model.evaluate(self.u, self.w, self.state, 0.0, tangent=False)
        self.rows.append(dict(
            model.record(self.u, self.w, out0), time=self.t, branch=history.branch(self.t),
            newton_iterations=0, step_cuts=0, time_step=0.0, integration_order=0,
            time_error=0.0, wall_time=0.0, dofs=model.dofs))
        self.residual = math.nan
        self.f_max = 0.0
        self.error_rejections = 0
        self.rupture = None
        self.stop_reason = ""
        self.factorizations = 0  # of the models replaced by remeshing
        self.redo = False  # the step is being re-solved on a new mesh
        self.carried = 0  # Newton iterations of a step solved on the mesh it left
        self.remeshed_steps = []

    def begin(self, n, dt):
        self.step_start = time.perf_counter()
        self.iterations, self.carried = self.carried, 0
        t = self.t
        self.branch = self.history.branch(t)
        # BDF2 from the second step on, restarted with backward Euler after a
        # knot of the history (where the loading rate jumps)
        at_knot = bool(np.any(np.abs(self.interior_knots - t) <= 1e-12 * self.end))
        self.order = 2 if (self.integration == "bdf2" and self.rate_dependent
                           and self.state_prev is not None and not at_knot) else 1
        return self.dt_cap, self.history.next_knot(t)

    def attempt(self, n, t_new, cuts):
        model, t, w, u, state = self.model, self.t, self.w, self.u, self.state
        h = t_new - t
        w_new = float(self.history(t_new))
        data = dict(h=h, w_new=w_new)
        if abs(w_new - w) > self.dw_max * (1 + 1e-9):
            return Trial(t_new, "interference step too large", data=data)
        reason, shrink = None, 0.5
        # predictor: extrapolate the last increment on the same branch
        u0 = u.copy()
        if self.u_prev is not None and self.rows[-1]["branch"] == self.branch \
                and t - self.t_prev > 0:
            u0 += (h / (t - self.t_prev)) * (u - self.u_prev)
        order = self.order
        if order == 2:
            a, b, c, _ = bdf2_coefficients(h / self.h_prev)
            start, h_m = bdf2_start(state, self.state_prev, a, b), c * h
        else:
            start, h_m = state, h
        try:
            u_new, out, its, to_pace = model.solve_step(u0, w_new, start, h_m, self.f_ref)
        except StepFailed as exc:
            self.iterations += exc.iterations
            return Trial(t_new, str(exc), data=data)
        self.iterations += its
        # what the step control reads: the tries before in full, this one to PACE_TOLERANCE
        paced = self.iterations - its + to_pace
        new = out["state"]
        if order == 2 and hasattr(new, "time"):
            new.time = state.time + h
        eps_step = float(np.max(equivalent_strain(new.inelastic_strain - state.inelastic_strain)))
        r_new = _rates(self.material, start, new, h_m)
        if self.rate_dependent:
            err = error_indicator(
                model, local_errors(order, h, self.h_prev, r_new, self.r_n, self.r_prev), out)
        else:
            err = math.nan
        tol = self.time_tolerance
        if eps_step > self.max_inelastic_step:
            reason = "inelastic strain step too large"
        elif err > REJECT * tol:
            reason = f"time error {err:.3g} above the tolerance {tol:g}"
            shrink = max(MIN_FACTOR, SAFETY * (tol / err) ** (1.0 / (order + 1)))
            self.error_rejections += 1
        if reason is not None:
            return Trial(t_new, reason, shrink, data=data)
        rec = model.record(u_new, w_new, out)
        if rec["overflow"]:
            if not model.grow_zone():
                raise ContactZoneError("the contact reached the outer edge of the top surface "
                                       f"at step {n} (interference {w_new:.6g} m)")
            return Trial(t_new, again=True)  # same step on the larger zone (not a cut)
        f_zero = ZERO_FORCE * self.f_max
        if (self.branch == "unloading" and rec["force"] <= f_zero
                and self.rows[-1]["force"] > f_zero and math.isnan(self.residual)
                and abs(w_new - w) > self.event_tolerance * self.w_max):
            # locate the zero force crossing: not a cut
            return Trial(t_new, again=True, dt=0.5 * h)
        data.update(u_new=u_new, out=out, new=new, rec=rec, r_new=r_new, err=err,
                    eps_step=eps_step, paced=paced)
        return Trial(t_new, data=data)

    def failure(self, cuts, trial):
        detail = trial.reason
        if self.rupture is not None:
            detail += (f" ({self.rows[-1]['ruptured_points']} points ruptured since step "
                       f"{self.rupture['step']})")
        return cuts.error(trial.data["w_new"], self.w, detail)

    def _remeshed(self, n, trial) -> bool:
        """A new mesh around the contact and the plastic zone of the step, the state at
        its start transferred, the step to be re-solved on it; whether it was built."""
        d = trial.data
        rec, new = d["rec"], d["new"]
        forced = bool(self.remesh_times) and trial.t_new >= self.remesh_times[0] * (1 - 1e-12)
        why = "" if self.redo or not (self.remesh or forced) else (
            "forced" if forced else self.meshes.due(rec["contact_radius"], self.model.disc, new))
        self.redo = False
        if not why:
            return False
        if forced:
            self.remesh_times.pop(0)
        model = self.model
        new_disc = self.meshes.build(max(rec["contact_radius"], 1e-3 * self.rg), model.disc, new)
        move = Transfer(model.disc, new_disc)
        self.factorizations += model.factorizations
        self.r_cand = max(self.r_cand, model.r_candidate)
        self.model = InelasticModel(new_disc, model.geometry, self.material, model.preset,
                                    self.r_cand, model.penalty_factor, self.tolerance,
                                    self.kinematics)
        self.u = move.displacement(self.u)
        self.u_prev = None if self.u_prev is None else move.displacement(self.u_prev)
        self.state = move.state(self.state)
        self.r_n = move.fields(self.r_n)
        self.state_prev, self.r_prev = None, None  # restart with backward Euler
        _, out_t = self.model.evaluate(self.u, self.w, self.state, 0.0, tangent=False)
        self.f_ref = float(np.linalg.norm(self.model.zone.nodal(out_t["traction"])))
        self.remeshed_steps.append(n)
        self.redo = True
        self.carried = self.iterations
        return True

    def accept(self, n, trial, cuts):
        d = trial.data
        h = d["h"]
        if self._remeshed(n, trial):
            return Accepted(h, redo=True)
        rec, err, order = d["rec"], d["err"], self.order
        self.u_prev, self.t_prev = self.u, self.t
        self.state_prev, self.h_prev = self.state, h
        self.r_prev, self.r_n = self.r_n, d["r_new"]
        self.u, self.t, self.w, self.state = d["u_new"], trial.t_new, d["w_new"], d["new"]
        t, w, branch, iterations = self.t, self.w, self.branch, self.iterations
        self.f_ref = float(np.linalg.norm(self.model.zone.nodal(d["out"]["traction"])))
        self.rows.append(dict(
            rec, time=t, branch=branch, newton_iterations=iterations, step_cuts=cuts.count,
            time_step=h, integration_order=order, time_error=err,
            wall_time=time.perf_counter() - self.step_start, dofs=self.model.dofs))
        t_end = self.end
        self.ticker.update(n, (t - self.t_first) / (t_end - self.t_first),
                           f"t = {t:.4g} of {t_end:.4g} s ({branch}), interference {w:.4g} m, "
                           f"force {rec['force']:.4g} N", iterations)
        if self.progress is not None:
            self.progress(f"step {n} ({branch}): t = {t:.6g} of {t_end:.6g} s, w = {w:.6g} m, "
                          f"force {rec['force']:.6g} N, {iterations} Newton iterations, "
                          f"{cuts.count} cuts, {self.rows[-1]['wall_time']:.3g} s")
        # next time step: the error controller, limited by Newton and the caps
        tol = self.time_tolerance
        if math.isnan(err) or err <= 0:
            fac = MAX_GROWTH
        else:
            fac = min(MAX_GROWTH, max(MIN_FACTOR, SAFETY * (tol / err) ** (1.0 / (order + 1))))
        dt = PACE.factor(d["paced"], cuts.count, fac) * h
        v = self.history.velocity(t)
        if v > 0:
            dt = min(dt, self.dw_max / v)
        dt = strain_limited(dt, h, d["eps_step"], self.max_inelastic_step)
        f_zero = ZERO_FORCE * self.f_max
        self.f_max = max(self.f_max, rec["force"])
        if rec["ruptured_points"] and self.rupture is None and self._ruptured(n, rec):
            return Accepted(dt, stop=True)
        if branch == "unloading" and rec["force"] <= f_zero and self.rows[-2]["force"] > f_zero \
                and math.isnan(self.residual):
            self.residual = _zero_force_crossing(self.rows)  # the first crossing only
            if self.stop_at_zero_force:
                return Accepted(dt, stop=True)
        return Accepted(dt)

    def _ruptured(self, n, rec) -> bool:
        """Record the first rupture (step `n`); raise or say to stop, by ``on_rupture``."""
        state, t, w = self.state, self.t, self.w
        rt = getattr(state, "rupture_time", None)
        mask = np.asarray(state.ruptured).ravel()
        first = (int(np.argmin(np.where(mask, np.asarray(rt).ravel(), np.inf)))
                 if rt is not None else int(np.argmax(mask)))
        pos = self.model.point_position(first)
        t_r = float(np.asarray(rt).ravel()[first]) if rt is not None else t
        self.rupture = dict(step=n, time=t_r if math.isfinite(t_r) else t, interference=w,
                            position=pos[0], depth=pos[1])
        if self.on_rupture == "raise":
            raise RuptureError(n, w, self.rupture["time"], pos, rec["ruptured_points"])
        if self.on_rupture == "stop":
            self.stop_reason = (f"material ruptured at step {n} (interference {w:.6g} m): "
                                f"{rec['ruptured_points']} point(s), the first at "
                                f"r = {pos[0]:.6g} m, {pos[1]:.6g} m below the surface")
            return True
        return False
