"""Elastic asperity with Lennard-Jones adhesion: approach, retract, jumps, pull-off.

The body and the contact are those of `asperity.fe.drivers.elastic` (P2 elements,
the stiffness condensed onto the candidate surface dofs, C1 penalty of
report 3.3.2 at the nodes); the adhesive traction of report 3.3.3 acts on
the free surface outside contact (`adhesion.LennardJones`, composite Gauss
rule per facet).  For an elastic body the equations (report 3.23 with the
boundary integrals of 3.4.1) are the stationarity conditions of

    Pi(u; w) = 1/2 u^T K_S u + int Phi_c(a) W ds + int Phi_a(a) W ds,

a = z + u_z + w the penetration, Phi_c the penalty potential and Phi_a the
adhesion potential (Phi_a' = t, `LennardJones.potential`).  Pi is not
convex: the adhesive tangent q'(s) is negative beyond s = 1.2 d, and an
elastic asperity can snap into contact and out of it.

Control and jumps
-----------------
The rigid flat's position w is prescribed (displacement control, as the
report's load-deflection curves and the pipeline's interference grid):
w < 0 is a gap before touching (the tip at separation d - w), w > 0 an
interference.  Every state is a *stable* equilibrium, a local minimum of
Pi: Newton's matrix is the consistent tangent (report 3.28 with the
adhesive term beta of 3.30 and the traction q of 3.32), shifted by
tau diag K_S on the active nodes where it is not positive definite, with
a backtracking line search on Pi that projects nodes pushed into the flat
back to it (so a contact zips up in a few iterations, not one node per
iteration); a converged saddle is left along its most negative
eigenvector.  The linear algebra works on the active surface nodes only
(`_Tangent`: Schur complement with the compliance K_S^-1).

Along the path, each step starts from the tangent predictor.  A step is
continuous if the energy balance Pi*(w1) - Pi*(w0) = (F0 + F1)/2
(w1 - w0) holds (Pi* has the derivative F along a branch; a jump releases
a finite energy) and the surface stayed near the predictor, or, where it
did not (a contact zipping or peeling over many elements), near the
secant through a state solved halfway (`AdhesiveModel.continuity`).
Otherwise, or if Newton fails, the step's end is marked bad and the
bracket up to it is bisected: a continuous branch is followed with steps
small enough to be smooth, and where the step stays discontinuous down
to ``min_step * d`` the old branch has ended (a fold of the equilibrium
curve: jump-in on approach, jump-off on retraction) and the minimum
reached is on the other branch.  The state before the fold and the state
after the jump are both recorded, ``min_step * d`` apart, the second
flagged ``jump``.  This is the physical path under displacement control;
the unstable branch that joins the two is not traced.

At a large Tabor parameter the branch before the jump-off fold is steep
over a long stretch (du/dw ~ (w - w_fold)^(-1/2) over many ring elements
peeling one by one) and the bisection in w can stall there: where it has
cut a requested step MAX_HALVINGS times (or a jump fails at the smallest
step), the branch is instead followed by its arc length in (u, w)
(pseudo-arc-length continuation, `_FoldPath`), which stays regular
through the fold, until dw/ds changes sign; the fold so bracketed is
located to ``min_step * d`` and the jump solved from the stable state
there to ``min_step * d`` beyond it (`_through_fold`).  A stretch that
turns out to have no fold is followed to the step's end.  Paths on which
the bisection does not stall do not take the fold path.  Where the
jump-off from the fold does not converge from the tangent predictor (the
contact peels over a band of many elements at once), it is solved again
from the branch out of contact that the asperity jumps off to
(`_Landing`): the states the approach passed before it jumped in, or the
undeformed body where the tip is beyond the cut-off.

Retracting, the flat first runs back over levels the approach reached
continuously; an elastic body's equilibria along a branch without a fold
depend on the flat's position only, so those levels are the approach's
states, not solved again (`_retrace`), down to the level the approach
jumped in at.  From there on, where the contact hangs on (the hysteresis
of report 7.3), every step is solved.

Sign convention: ``force`` is the total normal force of the flat on the
asperity, compressive positive as in `solve_asperity`; adhesion makes it
negative (attractive).  ``contact_force`` (>= 0, the penalty) and
``adhesive_force`` (<= 0) are its two parts.  ``pull_off_force`` is the
largest tensile force on retraction, a positive number (per unit length in
plane strain): the minimum of the force on the retract branch, located by
bisecting the path around the smallest recorded force (continuing the
branch from it) until the neighbouring states are d / 64 apart.

Mesh
----
The adhesion acts within a ring of the contact edge a few d wide in
separation: sqrt(2 R d) wide for a stiff sphere, the cohesive length
l = E* dgamma / q_max^2 (`LennardJones.process_zone`, 6 nm for aluminum
with dgamma = 1 J/m^2, d = 0.3 nm) for a compliant one.  The edge moves
over the whole band 0 <= r <= r_band during the path, so the initial ring
mesh (`mesh.AsperityMesh`) is refined until every element is smaller than
h_ring + grading * (its distance to the band), with

    h_ring = min(l / process_zone_elements, sqrt(2 R d) / ring_elements),

and r_band 1.1 times the larger of the radius where the undeformed gap at
the largest interference, less JKR's lift of the surface around the
contact (sqrt(2 pi a W / E*), an upper bound), is the cut-off, and the JKR
contact radius there plus 5 min(l, sqrt(2 R d)) (an adhesive contact is
never larger than JKR's).  The zone of candidate facets is the band; a
path whose adhesive ring reaches its last tenth is restarted with a wider
band.  The number of band facets grows like mu^2 (contact radius /
cohesive length), and the cost with it (the dense condensed stiffness is
m x m in the band's nodes, the active set of the tangent holds every node
in contact).

Meshes that follow the contact: a band of more than ``follow_above``
ring elements (a large Tabor parameter) is not refined as a whole.  Only
a window of it is (`AdhesiveModel.window_for`): the cohesive zone, from
the edge of the surface held in the well of q (separation below
(1 + TIP_SEPARATION) d, past the peak of q) or the contact edge to the
surface within FINE_SEPARATION d of the flat, plus a margin of
``follow_margin_elements`` ring elements on either side (preset; or
``follow_margin`` times the radius that reaches, if that is larger: the
contact inside and the surface outside are graded away from it as above);
the candidate zone is still the whole band.  The margin trades the size
of the Newton tangent's active set, whose dense factorization is most of
the cost, against how often the mesh moves: a narrow margin, 20 elements
in every preset, keeps the active set small at the price of more meshes
along the path (docs: changelog, 'Adhesion'); the pull-off moves by up
to 1e-4 of itself (`tests/fe/test_adhesion_follow.py`).  At a large
Tabor parameter the surface held in the well is a wide annulus around
the contact (the tension of JKR's contact), where the fields are smooth;
the contact edge inside it (where the penalty takes over from the
adhesion, the edge of the contact area) gets a band of its own, of
elements EDGE_COARSENING times longer.  Refining the whole annulus at
h_ring instead (preset key ``edge_band`` False) puts every node of the
annulus in the active set of the Newton tangent, whose factorization
costs the cube of its size (`_Tangent`), where the smooth fields need no
such refinement.  Each state the path reaches is
checked: if its edge or ring has come within a quarter of the margin of
the window's ends, the surface displacement is interpolated onto a mesh
with a new window and the equilibrium at the same flat position is
re-solved there (`_follow`), and the path goes on from that state (the
energy balance is checked between states of one mesh only).  A jump may
land far outside the window (jump-in): the landing state is moved, and
re-solved, until its window holds.  Each state keeps its mesh
(``AdhesiveState.model``): the bisection around the pull-off and the
outputs use it.  Only the current mesh keeps the sparse factors of its
body; the states recorded on a mesh the path has left are evaluated and
that mesh's factors dropped (`AdhesiveModel.release`), so the memory of a
path does not grow with its meshes at the rate of their factors.  The
measured costs of the adhesive jobs are in the docs (changelog,
'Adhesion').
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
import xarray as xr

from asperity.fe.solvers import nonlinear
from asperity.fe.contact.adhesion import LennardJones, adhesion_zone
from asperity.fe.discretization.assembly import CondensedStiffness, Discretization
from asperity.fe.contact.penalty import PENALTY_FACTOR, C1Penalty, ContactZone, contact_edge
from asperity.fe.errors import ContactZoneError, ConvergenceError, StepFailed
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.discretization.geometry import CosineHill, Paraboloid, Profile
from asperity.fe.materials.elastic import LinearElastic, equivalent_strain, von_mises
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec
from asperity.fe.solvers.newton import ROUNDOFF_FACTOR
from asperity.fe.solvers.nonlinear import EnergySearch, Problem
from asperity.fe.outputs import accuracy_attrs, dataset, describe
from asperity.fe.presets import PLANE_STRAIN_DOMAIN, resolve
from asperity.io.run_report import StepProgress
from asperity.references.adhesion import jkr_contact_radius

log = logging.getLogger(__name__)

#: Newton iterations of a step attempt are the preset's ``max_iterations``
#: (40): a continuous step converges well within them; one that does not is halved
#: (beyond a fold there is no nearby minimum, so failing fast localizes the
#: fold cheaply).  The solve of a jump, at the smallest step, may take
#: JUMP_ITERATION_FACTOR times more (the contact zips or peels).
MAX_ITERATIONS = 40
JUMP_ITERATION_FACTOR = 15
#: relative round-off of the energy Pi below which the line search accepts a
#: decrease of the residual instead (accepting real energy increases lets
#: Newton cycle between the kinks of the contact set)
ENERGY_ROUNDOFF = 1e-10
#: backtracking on Pi (Armijo), trial points projected if the full step fails
#: (`AdhesiveNewton.project`), the residual where Pi drowns in round-off
LINE_SEARCH = EnergySearch(halvings=50, projected=True, roundoff=ENERGY_ROUNDOFF)
#: halvings of one requested step (failed Newton or discontinuity) before the
#: branch is followed through its fold instead (`_through_fold`)
MAX_HALVINGS = 60
#: a mesh following the contact (`AdhesiveModel.window_for`): the fine band
#: spans the cohesive zone, from the edge of the surface held within
#: TIP_SEPARATION d of the well of q (or the contact edge) to the surface
#: within FINE_SEPARATION d of the flat, with the preset's margin on each
#: side (``follow_margin``, ``follow_margin_elements``); a contact edge
#: farther inside has a band of its own, of elements EDGE_COARSENING times
#: longer; a state whose edge or ring comes
#: within a quarter of the margin of its band's ends is moved to a new mesh,
#: at most MAX_REMESH times in a row
FINE_SEPARATION = 4.0
TIP_SEPARATION = 0.2
EDGE_COARSENING = 2.0
MAX_REMESH = 8
#: the fold path (`_FoldPath`): the first arc between FOLD_ARC d (root mean
#: square surface displacement); a corrector may move at most FOLD_MOVE d
#: from the predictor; at most FOLD_POINTS points to reach the fold and as
#: many to locate it
FOLD_ARC = (0.01, 0.5)
FOLD_MOVE = 0.5
FOLD_POINTS = 60


class _Overflow(Exception):
    """The adhesive ring reached the end of the refined band."""


def tip_radius(geometry: Profile) -> float:
    """Radius of curvature at the apex [m]."""
    if isinstance(geometry, CosineHill):
        return 1.0 / geometry.tip_curvature
    radius = getattr(geometry, "radius", None)
    if radius is not None:
        return float(radius)
    r = 1e-3 * geometry.extent
    return float(r**2 / (2.0 * abs(geometry.surface(r))))


# --- mesh ----------------------------------------------------------------------------
def band_mesh(geometry: Profile, windows, grading: float, spec: MeshSpec,
              max_rounds: int = 80) -> AsperityMesh:
    """The ring mesh refined until h <= h_w + grading * distance to band w, for
    some band w.

    Each band is the top surface r_lo <= r <= r_hi with its element size,
    ``windows = ((r_lo, r_hi, h_w), ...)`` (r_lo = 0: from the apex).
    Red-green-blue refinement of the elements too large for their
    distance, repeated.
    """
    mesh = AsperityMesh.initial(geometry, spec)
    for _ in range(max_rounds):
        m = mesh.vertices
        p = m.p[:, m.t]  # (2, 3, ne)
        edges = np.stack([np.hypot(*(p[:, i] - p[:, (i + 1) % 3])) for i in range(3)])
        size = edges.max(axis=0)
        c = p.mean(axis=1)
        depth = np.maximum(geometry.body_surface(c[0]) - c[1], 0.0)
        bound = np.full(size.shape, np.inf)
        for r_lo, r_hi, h in windows:
            off = np.maximum(np.maximum(c[0] - r_hi, r_lo - c[0]), 0.0)
            dist = np.maximum(np.hypot(off, depth) - 0.5 * size, 0.0)
            bound = np.minimum(bound, h + grading * dist)
        marked = np.nonzero(size > bound)[0]
        if marked.size == 0:
            return mesh
        mesh = mesh.refined(marked)
    raise RuntimeError("band refinement did not finish")


@dataclass
class _Scales:
    radius: float
    contact_modulus: float
    tabor: float
    process_zone: float
    ring: float
    h_ring: float
    r_band: float
    capped: bool


def _scales(geometry, material, adhesion: LennardJones, w_top: float, pre: dict,
            band_factor: float = 1.0) -> _Scales:
    R = tip_radius(geometry)
    Es = material.contact_modulus
    mu = adhesion.tabor_parameter(R, Es)
    lpz = adhesion.process_zone(Es)
    ring = math.sqrt(2.0 * R * adhesion.d)
    h = min(lpz / pre["process_zone_elements"], ring / pre["ring_elements"])
    W = adhesion.work_of_adhesion
    if geometry.axisymmetric:
        a_jkr = jkr_contact_radius(R, Es, W, max(w_top, 0.0))
        lift = math.sqrt(2.0 * math.pi * a_jkr * W / Es)  # JKR: the neck lifts the surface
    else:
        a_jkr = math.sqrt(2.0 * R * max(w_top, adhesion.d))
        lift = 0.0
    reach = max(w_top, 0.0) + adhesion.range - adhesion.d + lift
    if reach >= geometry.height:
        raise ValueError("the largest interference plus the adhesion range reaches the foot of the hill")
    r_geo = float(geometry.intersection_radius(np.array([reach]))[0])
    r_band = band_factor * 1.1 * max(r_geo, a_jkr + 5.0 * min(lpz, ring))
    r_band = min(r_band, 0.9 * geometry.extent)
    capped = r_band / h > pre["max_band_facets"]
    if capped:
        h = r_band / pre["max_band_facets"]
    return _Scales(R, Es, mu, lpz, ring, h, r_band, capped)


# --- the non-convex Newton ----------------------------------------------------------
@dataclass
class AdhesiveState:
    """A converged stable state at flat position w."""

    w: float
    u: np.ndarray
    dudw: np.ndarray
    contact_force: float
    adhesive_force: float
    stiffness: float
    energy: float = 0.0
    iterations: int = 0
    cuts: int = 0
    wall_time: float = 0.0
    #: the `AdhesiveModel` (mesh) the state is an equilibrium of
    model: "AdhesiveModel | None" = None
    #: its outputs on that mesh (`AdhesiveModel.evaluate`), once evaluated
    fields: dict | None = None

    @property
    def force(self) -> float:
        return self.contact_force + self.adhesive_force


class _Tangent:
    """The tangent J = K_S + E D E^T, D the surface terms on the active nodes A.

    K_S is dense but constant; D lives on the nodes of facets with a
    nonzero traction slope (contact and adhesive ring).  With the
    compliance C = K_S^-1 (computed once), J x = b is solved on A alone:
    x_A = S^-1 C_AA^-1 (C b)_A and x = C b - C_:A D x_A, with
    S = C_AA^-1 + D (the Schur complement of J onto A).  J is positive
    definite exactly when S is (K_S is), so the stability test and the
    shift that makes a non-convex tangent positive definite (tau diag K_AA
    on A) act on S too.  Costs |A|^3 instead of m^3 per iteration.
    """

    def __init__(self, C: np.ndarray, kdiag: np.ndarray, nodes: np.ndarray, D: np.ndarray,
                 reuse: "_Tangent | None" = None):
        self.C, self.nodes, self.D = C, nodes, D
        self.kdiag = kdiag[nodes]
        if reuse is not None and np.array_equal(reuse.nodes, nodes):
            # same active nodes as the last tangent: C_AA^-1 is the same
            if nodes.size:
                self.cC, self.G, self.CA = reuse.cC, reuse.G, reuse.CA
        elif nodes.size:
            self.cC = sla.cho_factor(C[np.ix_(nodes, nodes)], check_finite=False)
            self.G = sla.cho_solve(self.cC, np.eye(nodes.size), check_finite=False)
            self.CA = C[:, nodes]
        self.shift = 0.0
        self.cS = None
        self.luS = None

    def factor(self, shift: float = 0.0, definite: bool = True) -> bool:
        """Cholesky of S + shift diag K_AA; False if not positive definite.
        With ``definite`` False an indefinite S is factored by LU instead
        (the unstable branch beyond a fold, `_FoldPath`) and the result
        says only whether it is positive definite."""
        self.shift = shift
        self.luS = None
        if not self.nodes.size:
            return True
        S = self.G + self.D
        if shift:
            S = S + np.diag(shift * self.kdiag)
        try:
            self.cS = sla.cho_factor(S, check_finite=False)
            return True
        except np.linalg.LinAlgError:
            self.cS = None
            if not definite:
                self.luS = sla.lu_factor(S, check_finite=False)
            return False

    def solve(self, b: np.ndarray) -> np.ndarray:
        y = self.C @ b
        if not self.nodes.size:
            return y
        yA = sla.cho_solve(self.cC, y[self.nodes], check_finite=False)
        xA = (sla.lu_solve(self.luS, yA, check_finite=False) if self.luS is not None
              else sla.cho_solve(self.cS, yA, check_finite=False))
        Dp = self.D + np.diag(self.shift * self.kdiag) if self.shift else self.D
        return y - self.CA @ (Dp @ xA)

    def lowest_mode(self) -> np.ndarray:
        """Direction of the most negative curvature of J (harmonic extension off A)."""
        lam, vec = sla.eigh(self.G + self.D, subset_by_index=[0, 0])
        return self.CA @ (self.G @ vec[:, 0])


class AdhesiveNewton:
    """Minimizes Pi(u; w) over the zone's surface u_z (see module docstring)."""

    def __init__(self, K: np.ndarray, zone: ContactZone, law: C1Penalty, azone: ContactZone,
                 adhesion: LennardJones, tolerance: float, max_iterations: int = MAX_ITERATIONS):
        self.K = K
        self.kdiag = np.abs(np.diag(K)).copy()
        self.krow = np.abs(K).sum(axis=1)  # row sums of |K|, for the round-off floor
        c = sla.cho_factor(K)
        C = sla.cho_solve(c, np.eye(K.shape[0]))
        self.C = 0.5 * (C + C.T)
        self.zone = zone
        self.law = law
        self.azone = azone
        self.adhesion = adhesion
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        # nodal penalty stiffness, for the projected line search
        kappa = np.zeros(zone.ndofs)
        np.maximum.at(kappa, zone.facet_nodes,
                      np.broadcast_to(law.kappa, zone.facet_nodes.shape))
        self.node_kappa = kappa

    def parts(self, u, w):
        tp, dtp = self.law.traction(self.zone.penetration(u, w))
        ta, dta = self.adhesion.traction(self.azone.penetration(u, w))
        return tp, dtp, ta, dta

    def residual(self, u, w):
        tp, dtp, ta, dta = self.parts(u, w)
        R = self.K @ u + self.zone.nodal(tp) + self.azone.nodal(ta)
        scale = (np.linalg.norm(self.zone.nodal(np.abs(tp)))
                 + np.linalg.norm(self.azone.nodal(np.abs(ta))))
        return R, scale, (tp, dtp, ta, dta)

    def energy(self, u, w) -> float:
        ap = self.zone.penetration(u, w)
        aa = self.azone.penetration(u, w)
        return float(0.5 * u @ self.K @ u
                     + np.sum(self.law.potential(ap) * self.zone.weights)
                     + np.sum(self.adhesion.potential(aa) * self.azone.weights))

    def tangent(self, dtp, dta, u=None, w=None) -> _Tangent:
        """J = K + int t' N N^T W ds of both rules (report 3.30, 3.32, 3.4.1).

        The active nodes A must hold every node with a nonzero traction
        slope; extra nodes only add zero rows to D.  So that A (and with it
        C_AA^-1) changes rarely, it is taken with a margin: the nodes of
        the facets within 3 d of the adhesive range, kept while they still
        cover what is needed and are not 30 % too many.
        """
        needed_f = np.any(dtp != 0, axis=1) | np.any(dta != 0, axis=1)
        needed = np.unique(self.zone.facet_nodes[:, needed_f])
        last = getattr(self, "_last", None)
        if last is not None and np.isin(needed, last.nodes).all() \
                and last.nodes.size <= 1.3 * needed.size + 20:
            nodes = last.nodes
        elif u is not None:
            a = self.azone.penetration(u, w)
            reach = -(self.adhesion.range - self.adhesion.d) - 3.0 * self.adhesion.d
            near = needed_f | np.any(a > reach, axis=1)
            nodes = np.unique(self.zone.facet_nodes[:, near])
        else:
            nodes = needed
        active = np.any(np.isin(self.zone.facet_nodes, nodes), axis=0) & needed_f
        pos = np.full(self.zone.ndofs, -1)
        pos[nodes] = np.arange(nodes.size)
        D = np.zeros((nodes.size, nodes.size))
        for zone, dt in ((self.zone, dtp), (self.azone, dta)):
            vals = np.einsum("fg,ig,jg->ijf", (dt * zone.weights)[active], zone.N, zone.N)
            fn = pos[zone.facet_nodes[:, active]]
            ii = np.broadcast_to(fn[:, None, :], vals.shape)
            jj = np.broadcast_to(fn[None, :, :], vals.shape)
            np.add.at(D, (ii.ravel(), jj.ravel()), vals.ravel())
        self._last = _Tangent(self.C, self.kdiag, nodes, D, last)
        return self._last

    def floor(self, u, w, dtp, dta) -> float:
        """Round-off level of the residual (as `newton.ContactNewton.floor`)."""
        eps = np.finfo(float).eps
        out = eps * np.linalg.norm(self.krow) * np.max(np.abs(u), initial=0.0)  # >= eps ||K| |u||
        for zone, dt in ((self.zone, dtp), (self.azone, dta)):
            up = np.einsum("jf,jg->fg", np.abs(u)[zone.facet_nodes], np.abs(zone.N))
            da = eps * (np.abs(zone.z0) + up + abs(w))
            out += np.linalg.norm(zone.nodal(np.abs(dt) * da))
        return out

    def direction(self, T: _Tangent, R, iteration: int = 0):
        """Newton direction; J shifted by tau diag K on A until positive definite."""
        if T.factor():
            return T.solve(-R)
        tau = getattr(self, "_tau", 1e-6)
        for _ in range(60):
            if T.factor(tau):
                self._tau = max(tau / 4.0, 1e-8)
                return T.solve(-R)
            tau *= 4.0
        raise StepFailed("no positive definite shift of the tangent", iteration)

    def solve(self, w: float, u0: np.ndarray, max_iterations: int | None = None):
        """A stable minimum near u0 (`nonlinear.newton` with `LINE_SEARCH`):
        returns (u, parts, tangent, iterations)."""
        limit = self.max_iterations if max_iterations is None else max_iterations
        level = _Level(self, w)
        u, (scale, parts), its = nonlinear.newton(level, u0, self.tolerance, limit, LINE_SEARCH)
        return u, parts, level.tangent, its

    def project(self, trial, u, w):
        """The trial point with no node deeper in the flat than now or than
        the penetration q_max / kappa at which the penalty balances the peak
        adhesive pressure.

        A Newton step computed with the current contact set would push the
        nodes it does not hold deep into the flat, and plain backtracking
        then lets the contact grow by about one node per iteration (the
        zipping of a jump-in); projected, it grows at once.
        """
        zone = self.zone
        cap = np.maximum(zone.node_penetration(u, w), self.adhesion.peak_pressure / self.node_kappa)
        return trial - np.maximum(zone.node_penetration(trial, w) - cap, 0.0)

    def state(self, w, u, parts, T: _Tangent, iterations=0, cuts=0) -> AdhesiveState:
        """The converged state with du/dw (J du/dw = -int t' N W) and dF/dw."""
        tp, dtp, ta, dta = parts
        rhs = -(self.zone.nodal(dtp) + self.azone.nodal(dta))
        dudw = T.solve(rhs) if np.any(rhs) else np.zeros_like(u)
        k = 0.0
        for zone, dt in ((self.zone, dtp), (self.azone, dta)):
            da = np.einsum("jf,jg->fg", dudw[zone.facet_nodes], zone.N) + 1.0
            k += zone.total(dt * da)
        return AdhesiveState(w, u, dudw, self.zone.total(tp), self.azone.total(ta), k,
                             self.energy(u, w), iterations, cuts)


class _Level(Problem):
    """Pi(u; w) stationary at flat position w, a stable minimum (module docstring)."""

    def __init__(self, solver: AdhesiveNewton, w: float):
        self.solver, self.w = solver, w
        self.escapes = 0
        self.tangent = None

    def evaluate(self, u):
        R, scale, parts = self.solver.residual(u, self.w)
        return R, (scale, parts)

    def scale(self, u, data):
        return data[0]

    def floor(self, u, data):
        tp, dtp, ta, dta = data[1]
        return ROUNDOFF_FACTOR * self.solver.floor(u, self.w, dtp, dta)

    def linearize(self, u, data):
        tp, dtp, ta, dta = data[1]
        self.tangent = self.solver.tangent(dtp, dta, u, self.w)
        return self.tangent

    def direction(self, u, R, data, tangent, iteration):
        return self.solver.direction(tangent, R, iteration)

    def settle(self, u, data, tangent, iteration):
        """A saddle is left along the most negative curvature of the tangent."""
        if tangent.factor():
            return None
        self.escapes += 1
        if self.escapes > 3:
            raise StepFailed("converged to an unstable equilibrium", iteration)
        v = tangent.lowest_mode()
        v *= 0.1 * self.solver.adhesion.d / max(np.max(np.abs(v)), np.finfo(float).tiny)
        return u + v if self.merit(u + v) <= self.merit(u - v) else u - v

    def merit(self, u):
        return self.solver.energy(u, self.w)

    def project(self, trial, u):
        return self.solver.project(trial, u, self.w)


# --- the model -----------------------------------------------------------------------
class AdhesiveModel:
    """Mesh graded to the adhesive band, condensed stiffness, both surface rules.

    The fine bands are ``window`` ((r_lo, r_hi, h), ...); the candidate zone
    is always 0 <= r <= r_band.  A model `follows` the contact if the band has more
    than ``follow_above`` ring elements: its fine band is then a window
    around the contact edge, by default the preset's
    ``follow_margin_elements`` ring elements at the apex, moved along the
    path (`window_for`, `remeshed`; module docstring, "Mesh"); else it is
    the whole band (0, r_band).
    """

    def __init__(self, geometry: Profile, material, adhesion: LennardJones, scales: _Scales,
                 preset: dict, penalty_factor: float = PENALTY_FACTOR,
                 window: tuple | None = None):
        if not getattr(material, "is_linear", False):
            raise NotImplementedError("adhesion is implemented for elastic materials only")
        t0 = time.perf_counter()
        self.geometry, self.material, self.adhesion = geometry, material, adhesion
        self.scales, self.preset, self.penalty_factor = scales, preset, penalty_factor
        self.follows = scales.r_band > preset["follow_above"] * scales.h_ring
        if window is None:
            h = scales.h_ring
            window = ((0.0, preset["follow_margin_elements"] * h if self.follows
                       else scales.r_band, h),)
        self.window = window
        if geometry.axisymmetric:
            L = preset["domain_factor"] * geometry.length_scale
        else:
            L = PLANE_STRAIN_DOMAIN * geometry.length_scale
        spec = MeshSpec(L, min(4.0 * scales.h_ring, 0.1 * scales.r_band), preset["growth"],
                        preset["n_theta"])
        self.mesh = band_mesh(geometry, self.window, preset["grading"], spec)
        self.disc = Discretization(self.mesh)
        top = self.disc.top
        outer = top.coords[0, 2::2]
        nf = int(np.searchsorted(outer, scales.r_band)) + 1
        nf = max(2, min(nf, top.nfacets - 1))
        self.zone = ContactZone(top, nf, geometry)
        self.azone = adhesion_zone(top, nf, geometry, preset["gauss_points"],
                                   preset["subdivisions"])
        self.cond = self._condensed()
        self.law = C1Penalty.for_zone(self.zone, material.contact_modulus, penalty_factor)
        self.newton = AdhesiveNewton(self.cond.stiffness, self.zone, self.law, self.azone,
                                     adhesion, preset["tolerance"], preset["max_iterations"])
        R = scales.radius
        #: force scale of the adhesion: 2 pi R dgamma, or sqrt(R / d) dgamma per length
        self.force_reference = (2 * np.pi * R * adhesion.dgamma if geometry.axisymmetric
                                else 2 * math.sqrt(R / adhesion.d) * adhesion.dgamma)
        # the last tenth of the band's facets must stay out of the adhesive range
        # (of its radius where the facets outside the fine band are graded)
        if self.follows:
            ends = top.coords[0, 2:2 * nf + 1:2]
            self.edge_facets = ends > 0.9 * ends[-1]
        else:
            self.edge_facets = np.arange(nf) >= int(0.9 * nf)
        self.setup_time = time.perf_counter() - t0

    @property
    def dofs(self) -> int:
        return len(self.disc.free)

    def _condensed(self) -> CondensedStiffness:
        _, D = self.material.response(np.zeros((4, 1)))
        return CondensedStiffness(self.disc, self.disc.stiffness(np.asarray(D)), self.zone.dofs)

    def release(self) -> None:
        """Drop the sparse factors of the body, the bulk of a model's memory.

        The path needs only the condensed stiffness (`AdhesiveNewton`); the
        factors serve `evaluate` (the fields inside the body), which factors
        the body again if they were dropped.  A path whose mesh follows the
        contact keeps every mesh a recorded state lies on; `_trace` evaluates
        those states and drops the factors when the path moves to another
        mesh, so only the current mesh holds them.
        """
        self.cond.lu = None

    def continuity(self, old: AdhesiveState, new: AdhesiveState, pred: np.ndarray,
                   pre: dict) -> tuple[str, int]:
        """Whether `new` continues the branch of `old` (module docstring):
        ("continuous", "steep" or "jump", the Newton iterations spent on
        the test).

        Along a branch the minimum energy Pi*(w) has the derivative F
        (/ 2 pi, or / 2 in plane strain), so the trapezoidal rule
        Pi*(w1) - Pi*(w0) = (F0 + F1) / 2 (w1 - w0) holds to O(dw^2) even
        across the kinks where nodes enter or leave contact; a jump
        releases a finite energy that does not vanish with the step
        (`balanced`).  A step whose energy balances is continuous if the
        surface moved within d / 2 + 2 |dw| of the tangent predictor `pred`
        (the allowance covers the kinks where nodes enter or leave
        contact; the predictor's own move is capped at d + 2 |dw|, since
        du/dw blows up near a fold).  A jump of the surface that releases
        too little energy to show in the balance still moves it far from
        the predictor (a jump-in at a small Tabor parameter releases about
        as little energy as a continuous step's balance error, but moves the
        surface farther off the predictor than any continuous step; so both
        tests are needed), while the last continuous steps before a fold stay
        close to the predictor at min_step.

        Where a contact zips and peels over many ring elements (a large
        Tabor parameter) the predictor is no guide: the nodes that enter or
        leave contact within a step move several |dw| off it while the
        energy balances. Such a step is tested against the secant instead
        (`midpoint`): the state halfway, solved from `old`, must balance its
        energy with both ends and lie within d / 2 + |dw| of the mean of
        their surfaces. A jump J moves the secant's midpoint by J / 2
        whichever half it lies in, so the secant test misses the same jumps
        as the predictor test (J below d + 2 |dw|, the predictor's allowance
        and d / 2 more). A step whose energy balances but that fails the
        secant test too (or whose midpoint does not converge) is "steep":
        `_advance` retries it once from the first midpoint it reaches before
        bisecting on. At the smallest steps (min_step * d), where a
        continuous branch cannot move far from its tangent, only the
        predictor counts: a jump is a move of more than jump_tolerance * d
        (0.25 d) away from it. Jumps smaller than these allowances are
        recorded as a steep continuous stretch.
        """
        d = self.adhesion.d
        dw = new.w - old.w
        off = np.max(np.abs(new.u - pred), initial=0.0)
        if abs(dw) <= pre["min_step"] * d:
            return ("continuous" if off <= pre["jump_tolerance"] * d else "jump"), 0
        if not self.balanced(old, new, pre):
            return "jump", 0
        if off <= 0.5 * d + 2.0 * abs(dw):
            return "continuous", 0
        verdict, iterations, _ = self.midpoint(old, new, pre)
        return verdict, iterations

    def balanced(self, old: AdhesiveState, new: AdhesiveState, pre: dict) -> bool:
        """The energy balance of the step from `old` to `new` (`continuity`):
        |Pi*(w1) - Pi*(w0) - (F0 + F1) / 2 (w1 - w0)| within
        energy_tolerance * d * max(|F|, F_ref / 20) plus, between two states
        both touching or both not, the rule's own truncation error, estimated
        as dw^2 |k1 - k0| / 6 (twice the trapezoidal error dw^3 F'' / 12, with
        F'' ~ (k1 - k0) / dw from the stiffnesses k at both ends).  Without
        the truncation term the geometric steps beyond 4 d (tens of d each)
        fail the balance through the trapezoidal rule's own error and are
        halved for nothing; it is not allowed across touching, where a
        jump-in moves the stiffness by the contact's own and could hide the
        energy it releases."""
        d = self.adhesion.d
        ff = self.zone.force_factor
        dw = new.w - old.w
        f0, f1 = old.force / ff, new.force / ff
        scale = max(abs(f0), abs(f1), 0.05 * self.force_reference / ff)
        balance = new.energy - old.energy - 0.5 * (f0 + f1) * dw
        same_side = (old.contact_force > 0) == (new.contact_force > 0)
        truncation = dw * dw * abs(new.stiffness - old.stiffness) / (6.0 * ff) if same_side else 0.0
        return abs(balance) <= pre["energy_tolerance"] * d * scale + truncation

    def midpoint(self, old: AdhesiveState, new: AdhesiveState,
                 pre: dict) -> tuple[str, int, float]:
        """The secant test of a step that left its predictor (`continuity`):
        the state at the middle of the step, solved from `old`'s predictor,
        balances its energy with both ends and its surface is within
        d / 2 + |dw| of theirs averaged ("continuous"); else "jump" if a
        half does not balance, "steep" if only the secant or the solve
        fails.  Returns (verdict, iterations, the largest departure from the
        secant [m]; NaN if the solve failed)."""
        d = self.adhesion.d
        wm = 0.5 * (old.w + new.w)
        try:
            u, parts, T, its = self.newton.solve(wm, _predictor(old, wm))
        except StepFailed as exc:
            return "steep", exc.iterations, math.nan
        mid = self.newton.state(wm, u, parts, T)
        secant = np.max(np.abs(u - 0.5 * (old.u + new.u)), initial=0.0)
        if not (self.balanced(old, mid, pre) and self.balanced(mid, new, pre)):
            return "jump", its, secant
        verdict = "continuous" if secant <= 0.5 * d + abs(new.w - old.w) else "steep"
        return verdict, its, secant

    def window_for(self, state: AdhesiveState) -> tuple | None:
        """The fine bands `state` needs if this mesh's will not do, else None.

        The ring is the cohesive zone: the surface from the edge of the
        adhered region (the outermost node closer than (1 +
        TIP_SEPARATION) d to the flat, past the peak of q; the contact
        edge if beyond it; the apex if neither) to the outermost node
        within FINE_SEPARATION d of the flat (q there is 4 % of its peak).
        Its band must reach a quarter of the margin beyond it on either
        side (or the apex, or r_band); a new band extends a full margin
        beyond it, from the apex if that leaves less than a margin inside,
        at the ring's element size h_ring.  At a large Tabor parameter the
        surface inside the ring is held in the well of q (d < s < 1.2 d)
        over a wide annulus around the contact (the tension of JKR's
        contact), where the fields are smooth: only the contact edge
        (where the penalty takes over from the adhesion) needs a band of
        its own there, with the same margins and elements EDGE_COARSENING
        times longer (preset key ``edge_band``; without it the band reaches
        from the contact edge, or the apex, to the ring).  Returns the bands
        ((r_lo, r_hi, h), ...).
        """
        if not self.follows:
            return None
        d = self.adhesion.d
        r = self.zone.coords[0]
        pen = self.zone.node_penetration(state.u, state.w)
        touching = pen >= 0
        edge = contact_edge(r, -pen, touching) if touching.any() else 0.0
        near = pen > -(FINE_SEPARATION - 1.0) * d
        outer = max(float(r[near].max()) if near.any() else 0.0, edge)
        held = pen > -TIP_SEPARATION * d
        tip = max(float(r[held].max()) if held.any() else 0.0, edge)
        h = self.scales.h_ring
        margin = max(self.preset["follow_margin"] * outer,
                     self.preset["follow_margin_elements"] * h)
        r_band = self.scales.r_band

        def covers(lo, hi, size):  # a band of elements no longer than size spans lo..hi
            return any(a <= max(lo, 0.0) and b >= min(hi, r_band) and h_w <= size
                       for a, b, h_w in self.window)

        if self.preset["edge_band"]:
            apart = 0.0 < edge < tip - 2.0 * margin  # the contact edge needs a band of its own
            inner = tip if apart or edge == 0.0 else edge
        else:  # one band from the contact edge (or the apex)
            apart, inner = False, edge
        if covers(inner - 0.25 * margin, outer + 0.25 * margin, h) and (
                not apart or covers(edge - 0.25 * margin, edge + 0.25 * margin,
                                    EDGE_COARSENING * h)):
            return None
        lo = inner - margin if inner > 2.0 * margin else 0.0
        bands = [(lo, min(outer + margin, r_band), h)]
        if apart:
            lo = edge - margin if edge > 2.0 * margin else 0.0
            bands.append((lo, edge + margin, EDGE_COARSENING * h))
        return tuple(bands)

    def remeshed(self, window: tuple) -> "AdhesiveModel":
        """The model on a mesh with the fine bands `window` ((r_lo, r_hi, h), ...)."""
        return AdhesiveModel(self.geometry, self.material, self.adhesion, self.scales,
                             self.preset, self.penalty_factor, window)

    def overflow(self, state: AdhesiveState) -> bool:
        a = self.azone.penetration(state.u, state.w)
        near = a > -(self.adhesion.range - self.adhesion.d)
        return bool(np.any(near[self.edge_facets]))

    def evaluate(self, states) -> dict:
        """Contact radius and the field maxima of the states."""
        if self.cond.lu is None:  # released (`release`)
            self.cond = self._condensed()
        zone, disc, mat = self.zone, self.disc, self.material
        k = len(states)
        radius = np.zeros(k)
        gap_tip = np.zeros(k)
        for j, s in enumerate(states):  # one scalar search per state
            pen = zone.node_penetration(s.u, s.w)
            gap_tip[j] = self.adhesion.d - pen[0]
            if np.any(pen >= 0):
                radius[j] = contact_edge(zone.coords[0], -pen, pen >= 0)
        strain_max, mises_max = np.zeros(k), np.zeros(k)
        for lo in range(0, k, 8):
            sub = states[lo:lo + 8]
            f = np.array([-(zone.nodal(self.newton.parts(s.u, s.w)[0])
                            + self.azone.nodal(self.newton.parts(s.u, s.w)[2])) for s in sub]).T
            U = self.cond.full_displacement(f.reshape(zone.ndofs, len(sub)))
            strain = disc.strain(U)
            stress, _ = mat.response(strain)
            strain_max[lo:lo + len(sub)] = equivalent_strain(strain).reshape(-1, len(sub)).max(axis=0)
            mises_max[lo:lo + len(sub)] = von_mises(stress).reshape(-1, len(sub)).max(axis=0)
        return dict(contact_radius=radius, tip_separation=gap_tip,
                    max_equivalent_strain=strain_max, max_von_mises=mises_max)


def adhesive_model(geometry: Profile, material, adhesion: LennardJones, w_max: float,
                   accuracy="standard", penalty_factor: float | None = None,
                   band_factor: float = 1.0) -> AdhesiveModel:
    """The mesh and operators for a path up to the interference w_max."""
    pre = resolve("adhesive", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    scales = _scales(geometry, material, adhesion, float(w_max), pre, band_factor)
    return AdhesiveModel(geometry, material, adhesion, scales, pre, factor)


# --- the path ------------------------------------------------------------------------
def adhesive_path(adhesion: LennardJones, w_max: float, w_min: float | None = None,
                  steps_per_d: float = 6.0, far_steps: int = 16) -> np.ndarray:
    """Flat positions: approach from the cut-off to w_max, retract to w_min.

    Steps of d / steps_per_d within 4 d of first touch, growing as 15 % of
    |w| before it (the far tail of the attraction) and geometrically in
    `far_steps` steps beyond it up to w_max.  The approach starts where the
    tip is at the cut-off separation (no force); the retraction runs back
    over the same levels and on to `w_min` (default the start), below
    which the flat would have to go for a contact that hangs on (JKR-like)
    to let go.  w = 0 (first touch) is always a level.
    """
    d = adhesion.d
    h = d / steps_per_d
    start = -(adhesion.range - d)
    near = 4.0 * d

    def below(lo):  # levels from lo (< 0) up to 0
        out, w = [0.0], 0.0
        while w > lo:
            w -= max(h, 0.15 * min(-w, -lo) if -w > near else h)
            out.append(max(w, lo))
        return np.array(out[::-1])

    up = [below(start)]
    if w_max > 0:
        top = min(w_max, near)
        n = max(int(math.ceil(top / h)), 1)
        up.append(np.linspace(0, top, n + 1)[1:])
        if w_max > near:
            up.append(np.geomspace(near, w_max, far_steps + 1)[1:])
    approach = np.concatenate(up)
    approach = approach[approach <= w_max + 1e-12 * d] if w_max < 0 else approach
    retract = approach[::-1][1:]
    lo = start if w_min is None else min(w_min, start)
    if lo < start:
        retract = np.concatenate((retract[:-1], below(lo)[::-1][len(below(start)) - 1:]))
    return np.concatenate((approach, retract))


def _branches(path: np.ndarray) -> list[str]:
    out = ["approach"]
    for a, b in zip(path[:-1], path[1:]):
        out.append("approach" if b > a else ("retract" if b < a else out[-1]))
    return out


@dataclass
class _Record:
    state: AdhesiveState
    branch: str
    jump: bool
    requested: bool
    step: int


def _on_nodes(state: AdhesiveState, model: "AdhesiveModel") -> np.ndarray:
    """The surface displacement of `state` interpolated onto the surface nodes of
    `model` (linearly in r)."""
    return np.interp(model.zone.coords[0], state.model.zone.coords[0], state.u)


def _follow(state: AdhesiveState, step: int = 0) -> tuple[AdhesiveState, int]:
    """`state` moved onto a mesh whose fine band covers its contact edge.

    While the state's mesh will not do (`AdhesiveModel.window_for`), the
    surface displacement is interpolated onto the nodes of a mesh with the
    band it needs and the equilibrium at the same flat position re-solved
    from there (a jump may land far outside the band: the landing state
    then moves the band, and is re-solved, again).  Returns the state and
    the Newton iterations spent.
    """
    iterations = 0
    for _ in range(MAX_REMESH):
        old = state.model
        window = old.window_for(state)
        if window is None:
            return state, iterations
        model = old.remeshed(window)
        u0 = _on_nodes(state, model)
        newton = model.newton
        try:
            u, parts, T, its = newton.solve(state.w, u0,
                                            JUMP_ITERATION_FACTOR * newton.max_iterations)
        except StepFailed as exc:
            raise ConvergenceError(step, state.w, state.w, 0,
                                   f"{exc} (re-solving on a new mesh at w = {state.w:.6g} m)"
                                   ) from None
        iterations += its
        state = newton.state(state.w, u, parts, T)
        state.model = model
    raise ConvergenceError(step, state.w, state.w, 0,
                           f"the fine band does not settle on the contact (at w = {state.w:.6g} m)")


class _FoldPath:
    """The branch of a state followed through its fold (module docstring,
    "Control and jumps").

    Near a fold du/dw blows up and the step control in w can only bisect
    towards it.  Here the branch is parametrized by its arc length s in
    (u, w) instead, with the inner product <x, y> = x_u . y_u / m + x_w y_w
    (m surface dofs: the root mean square of the surface displacement), a
    parametrization that stays regular through a fold (pseudo-arc-length
    continuation, `corrector`).  The unit tangent t is +-(du/dw, 1)
    normalized, oriented at the start towards the target and then along
    the previous one.  Steps in s (tangent predictor; an arc is halved if
    the corrector fails, moves farther than FOLD_MOVE d from the predictor
    or turns the tangent by more than 60 degrees, and grows by half after a
    success) go on until dw/ds changes sign: w turned back, the fold is
    between the last two points.  The bracket is bisected in s until the
    stable side is within ``min_step * d`` in w of the fold's position
    estimated by the quadratic w(s) with the slopes dw/ds at both ends.
    """

    def __init__(self, state: AdhesiveState, target: float, pre: dict):
        self.newton = state.model.newton
        self.pre = pre
        self.d = state.model.adhesion.d
        self.sign = math.copysign(1.0, target - state.w)
        self.m = state.u.size
        self.iterations = 0

    def inner(self, x, y) -> float:
        """<x, y> of two (u, w) pairs (class docstring)."""
        return float(x[0] @ y[0] / self.m + x[1] * y[1])

    def tangent(self, s: AdhesiveState, along=None) -> tuple:
        """Unit tangent at s, oriented along `along` (a tangent) or, without
        it, towards the target."""
        t = (s.dudw, 1.0)
        norm = math.sqrt(self.inner(t, t))
        t = (s.dudw / norm, 1.0 / norm)
        flip = self.inner(t, along) < 0 if along is not None else t[1] * self.sign < 0
        return (-t[0], -t[1]) if flip else t

    def corrector(self, u: np.ndarray, w: float, t: tuple, origin: AdhesiveState, arc: float):
        """The equilibrium an arc `arc` along `t` from `origin`, from (u, w).

        Newton on the bordered system of pseudo-arc-length continuation,
        R(u, w) = 0 and <t, (u, w) - (u0, w0)> = arc, by block elimination:
        J a = -R, J b = -R_w (b is du/dw), dw from the linearized arc
        condition, du = a + dw b.  J may be indefinite (the unstable
        branch): it is factored by LU there (`_Tangent.factor`).  No line
        search: the start is the tangent predictor a small arc away.
        Returns (u, w, parts, tangent J, iterations, whether J is positive
        definite); raises `StepFailed`.
        """
        newton = self.newton
        limit = newton.max_iterations
        for it in range(limit + 1):
            R, scale, parts = newton.residual(u, w)
            tp, dtp, ta, dta = parts
            rn = np.linalg.norm(R)
            if not np.isfinite(rn):
                raise StepFailed("non-finite residual on the fold path", it)
            T = newton.tangent(dtp, dta, u, w)
            definite = T.factor(definite=False)
            if it and rn <= max(newton.tolerance * scale,
                                ROUNDOFF_FACTOR * newton.floor(u, w, dtp, dta)):
                return u, w, parts, T, it, definite
            if it == limit:
                break
            a = T.solve(-R)
            b = T.solve(-(newton.zone.nodal(dtp) + newton.azone.nodal(dta)))
            g = self.inner(t, (u - origin.u, w - origin.w)) - arc
            dw = -(g + self.inner(t, (a, 0.0))) / self.inner(t, (b, 1.0))
            step = a + dw * b
            if not (np.all(np.isfinite(step)) and np.isfinite(dw)):
                raise StepFailed("non-finite correction on the fold path", it)
            u, w = u + step, w + dw
        raise StepFailed(f"no convergence in {limit} iterations on the fold path", limit)

    def point(self, s: AdhesiveState, t: tuple, arc: float):
        """The branch an arc `arc` from s along t, its tangent and whether it
        is stable (J positive definite); `StepFailed` if the corrector fails
        or the point is not a continuation (see the class docstring)."""
        newton = self.newton
        u0, w0 = s.u + arc * t[0], s.w + arc * t[1]
        try:
            u, w, parts, T, its, stable = self.corrector(u0, w0, t, s, arc)
        except StepFailed as exc:
            self.iterations += exc.iterations
            raise
        self.iterations += its
        if np.max(np.abs(u - u0), initial=0.0) > FOLD_MOVE * self.d:
            raise StepFailed("the corrector left the predictor", its)
        new = newton.state(w, u, parts, T)
        new.model = s.model
        t1 = self.tangent(new, t)
        if self.inner(t1, t) < 0.5:
            raise StepFailed("the tangent turned", its)
        return new, t1, stable

    def fold(self, state: AdhesiveState, goal: float):
        """(stable state at the fold, estimated fold position), or (the state
        at `goal`, None) if the branch reaches it without turning."""
        d, sign = self.d, self.sign
        lo, t_lo = state, self.tangent(state)
        # the first arc: the tangent's move to the goal, within FOLD_ARC
        h = min(max(abs(goal - lo.w) / abs(t_lo[1]), FOLD_ARC[0] * d), FOLD_ARC[1] * d)
        for _ in range(FOLD_POINTS):
            try:
                new, t_new, stable = self.point(lo, t_lo, h)
            except StepFailed:
                h *= 0.5
                if h < 1e-3 * FOLD_ARC[0] * d:
                    raise
                continue
            if t_new[1] * t_lo[1] < 0:
                hi = new
                break
            if (new.w - goal) * sign >= 0:  # no fold before the goal: solve there
                u, parts, T, its = self.newton.solve(goal, _predictor(new, goal))
                self.iterations += its
                out = self.newton.state(goal, u, parts, T)
                out.model = new.model
                return out, None
            if not stable:
                raise StepFailed("the branch lost stability without a fold", 0)
            lo, t_lo, h = new, t_new, 1.5 * h
        else:
            raise StepFailed("the fold path did not turn", 0)
        smallest = self.pre["min_step"] * d
        for _ in range(FOLD_POINTS):
            x = (hi.u - lo.u, hi.w - lo.w)
            arc = self.inner(t_lo, x)
            s0 = t_lo[1]
            s1 = self.tangent(hi, t_lo)[1]
            w_fold = lo.w - 0.5 * s0 * s0 * arc / (s1 - s0)
            if abs(lo.w - w_fold) <= smallest:
                return lo, w_fold
            mid, t_mid, stable = self.point(lo, t_lo, 0.5 * arc)
            if t_mid[1] * s0 > 0 and stable:
                lo, t_lo = mid, t_mid
            else:
                hi = mid
        raise StepFailed("the fold was not located", 0)


def _advance(state: AdhesiveState, target: float, pre: dict, step: int = 0,
             landing: _Landing | None = None):
    """From a converged state to the flat position `target`, with step control.

    A step that fails to converge, or is discontinuous
    (`AdhesiveModel.continuity`), marks its end as bad; the bracket from
    the state to the nearest bad position is then bisected (a good
    midpoint advances the state, a bad one shrinks the bracket) until it is
    min_step * d long, where a discontinuous step is a jump.  A position
    where Newton failed, or bad only by the predictor and secant tests
    ("steep"), is retried once, from the first midpoint reached, before
    the bisection goes on (such a stretch then costs two half steps
    instead of a bisection down to min_step).  A bad
    position reached continuously after all (a steep stretch) is dropped
    and the bracket reopens to the next one, never to the target.  Each
    state reached (after a jump too) is moved onto a mesh that follows its
    contact edge (`_follow`) before the next step.  Where the bisection
    stalls (more than MAX_HALVINGS halvings since the start or the last
    fold, or a failed solve at the smallest step) the branch is followed
    through its fold instead (`_through_fold`, with `landing` for the jump
    from the fold).  Returns (final state,
    [(state before, state after) of each jump], iterations, halvings);
    raises `ConvergenceError` (naming `step` and the last position reached)
    when that fails too.
    """
    d = state.model.adhesion.d
    smallest = pre["min_step"] * d
    target = float(target)
    goals = [target]
    iterations = 0
    cuts = nonlinear.StepCuts(step, MAX_HALVINGS)  # halvings; restarted after a fold
    jumps = []
    bads = []  # positions known to fail or to be discontinuous, nearest last
    steep = None  # a bad position to retry once after the next advance
    retry = False  # the last attempt advanced the state
    while goals:
        goal = goals[-1]
        while bads and (bads[-1] - state.w) * (target - state.w) <= 0:  # reached after all
            bads.pop()
        if bads and (goal - bads[-1]) * (target - state.w) >= 0:  # the goal is at or beyond it
            bad = bads[-1]
            if (retry and bad == steep) or abs(bad - state.w) <= smallest:
                nxt = bad
            else:
                nxt = 0.5 * (state.w + bad)
            if nxt != goal:
                goals.append(nxt)
                continue
        model = state.model
        newton = model.newton
        small = abs(goal - state.w) <= smallest
        pred = _predictor(state, goal)
        failure = None
        try:
            u, parts, T, its = newton.solve(
                goal, pred, JUMP_ITERATION_FACTOR * newton.max_iterations if small else None)
            iterations += its
        except StepFailed as exc:
            iterations += exc.iterations
            retried = retry and goal == steep
            if not retried:  # a failed retry halves nothing
                cuts.cut()
            if small or cuts.exhausted:
                failure = f"{exc} (at w = {goal:.6g} m)"
            else:
                bads.append(goal)
                goals = [target]
                steep = None if retried else goal  # retried once, as a steep position
                retry = False
                continue
        if failure is None:
            new = newton.state(goal, u, parts, T)
            new.model = model
            verdict, its = model.continuity(state, new, pred, pre)
            iterations += its
            jumped = verdict != "continuous"
            if jumped and not small:
                retried = retry and goal == steep
                if not retried:  # a failed retry halves nothing
                    cuts.cut()
                if cuts.exhausted:
                    failure = "the path stays discontinuous"
                else:
                    # a steep position is retried once: not when this was its retry
                    steep = goal if verdict == "steep" and not retried else None
                    bads.append(goal)
                    goals = [target]
                    retry = False
                    continue
        if failure is not None:  # the bisection stalled: follow the branch through its fold
            try:
                state, new, jumped, its = _through_fold(state, target, pre, landing)
            except StepFailed as exc:
                raise cuts.error(target, state.w, f"{failure}; then {exc}") from None
            iterations += its
            cuts.restart()
        new, its = _follow(new, step)
        iterations += its
        if jumped:
            jumps.append((state, new))
            bads = []
        if new.model.overflow(new):
            raise _Overflow()
        state = new
        retry = True
        if failure is None:
            goals.pop()
        else:  # the pass landed at a position of its own
            goals = [target]
    return state, jumps, iterations, cuts.count


def _predictor(state: AdhesiveState, goal: float) -> np.ndarray:
    """The tangent predictor from `state` to the flat position `goal`, its move
    capped at d + 2 |dw| (du/dw blows up near a fold;
    `AdhesiveModel.continuity` allows d / 2 + 2 |dw| off it)."""
    dw = goal - state.w
    step_u = dw * state.dudw
    big = np.max(np.abs(step_u), initial=0.0)
    cap = state.model.adhesion.d + 2.0 * abs(dw)
    return state.u + (step_u if big <= cap else step_u * (cap / big))


def _through_fold(state: AdhesiveState, target: float, pre: dict,
                  landing: "_Landing | None" = None):
    """The jump from the fold of `state`'s branch towards `target` (`_FoldPath`).

    The branch is followed to its fold, and the equilibrium ``min_step * d``
    beyond the fold solved from the stable state there (the tangent
    predictor, JUMP_ITERATION_FACTOR times the iterations); if that fails
    and a `landing` is given, from its guess instead, kept only if its
    energy is below the predictor's (a snap releases energy).  Returns (the state
    at the fold, the state after, whether it jumped (moved more than
    jump_tolerance * d off the predictor), Newton iterations); if the
    branch reaches `target` without a fold, (`state`, the state at the
    target, False, iterations).  Raises `StepFailed` saying what failed.
    """
    if not np.any(state.dudw):  # the surface does not move with w: no branch to follow
        raise StepFailed("the surface does not move with w: no branch to follow")
    path = _FoldPath(state, target, pre)
    try:
        before, w_fold = path.fold(state, target)
    except StepFailed as exc:
        raise StepFailed(f"following the branch by its arc length: {exc}",
                         path.iterations) from None
    if w_fold is None:  # no fold: the branch followed to the target
        return state, before, False, path.iterations
    d = state.model.adhesion.d
    goal = w_fold + path.sign * pre["min_step"] * d
    newton = before.model.newton
    pred = _predictor(before, goal)
    limit = JUMP_ITERATION_FACTOR * newton.max_iterations
    try:
        u, parts, T, its = newton.solve(goal, pred, limit)
    except StepFailed as exc:
        its = exc.iterations
        guess = None if landing is None else landing.guess(goal, before.model)
        if guess is None:
            raise StepFailed(f"the jump from the fold at w = {w_fold:.6g} m: {exc}",
                             path.iterations + its) from None
        try:
            u, parts, T, more = newton.solve(goal, guess, limit)
        except StepFailed as exc2:
            raise StepFailed(f"the jump from the fold at w = {w_fold:.6g} m: {exc}; from the "
                             f"approach's state out of contact: {exc2}",
                             path.iterations + its + exc2.iterations) from None
        its += more
        if newton.energy(u, goal) >= newton.energy(pred, goal):  # a snap only goes down
            raise StepFailed(f"the jump from the fold at w = {w_fold:.6g} m: {exc}; the "
                             "approach's state out of contact is not below the fold in "
                             "energy", path.iterations + its)
    after = newton.state(goal, u, parts, T)
    after.model = before.model
    jumped = np.max(np.abs(u - pred), initial=0.0) > pre["jump_tolerance"] * d
    return before, after, jumped, path.iterations + its


class _Landing:
    """Where a jump-off lands: the branch out of contact the approach passed.

    Retracting, the asperity jumps off at a flat position w_off below the
    jump-in w_in of its approach (the hysteresis of 7.3), where the
    approach was still on the branch out of contact; below the start of
    the approach, -(s_c - d), the undeformed tip is beyond the cut-off and
    that branch is u = 0 exactly.  `guess` gives the branch at w, on the
    surface nodes of `model`: u = 0 below the cut-off, else interpolated
    linearly in w between the two of those states that bracket w (each
    interpolated onto the nodes); None above the last state out of
    contact (the branch is not known there).
    """

    def __init__(self, states, adhesion: LennardJones):
        self.states = sorted((s for s in states if s.contact_force <= 0.0), key=lambda s: s.w)
        self.free = -(adhesion.range - adhesion.d)

    def guess(self, w: float, model) -> np.ndarray | None:
        if w <= self.free:
            return np.zeros(model.zone.ndofs)
        if not self.states or w > self.states[-1].w:
            return None
        k = next(i for i, s in enumerate(self.states) if s.w >= w)
        hi = self.states[k]
        u_hi = _on_nodes(hi, model)
        if hi.w == w:
            return u_hi
        if k:
            lo = self.states[k - 1]
            w_lo, u_lo = lo.w, _on_nodes(lo, model)
        else:
            w_lo, u_lo = self.free, np.zeros(model.zone.ndofs)
        t = (w - w_lo) / (hi.w - w_lo)
        return (1.0 - t) * u_lo + t * u_hi


def _trace(model: AdhesiveModel, path, pre: dict, label: str = "",
           progress=None) -> list[_Record]:
    """States along the path with step control and jumps (module docstring),
    from `model`'s mesh (moved along with the contact if it follows it);
    `progress(line)`, if given, hears of every level reached."""
    newton = model.newton
    branches = _branches(path)
    # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
    ticker = StepProgress(log, f"adhesive path{' of ' + label if label else ''}: ",
                          total=len(path) - 1)
    t0 = time.perf_counter()
    try:
        u, parts, T, its = newton.solve(float(path[0]), np.zeros(model.zone.ndofs))
    except StepFailed as exc:
        raise ConvergenceError(0, float(path[0]), math.nan, 0, str(exc), label) from None
    state = newton.state(float(path[0]), u, parts, T, its)
    state.model = model
    try:
        state, more = _follow(state)
    except ConvergenceError as exc:
        exc.sample = label
        raise
    state.iterations = its + more
    state.wall_time = time.perf_counter() - t0
    records = [_Record(state, branches[0], False, True, 0)]
    landing = None  # of a retraction: built from the approach's records when it starts
    # the approach's levels (state, whether the level into it jumped) while the path
    # has only gone up; `mirror` indexes the one the retraction is at, if any (`_retrace`)
    ups, mirror = [(state, False)], None
    for n in range(1, len(path)):
        target, branch = float(path[n]), branches[n]
        t0 = time.perf_counter()
        if branch != "retract":
            landing = None
        elif landing is None:
            landing = _Landing((r.state for r in records if r.branch == "approach"),
                               model.adhesion)
        if branch == "retract" and ups is not None:
            mirror = len(ups) - 1 if mirror is None else mirror
            back = _retrace(ups, mirror, target)
            ups = None if back is None else ups
        else:
            back = None
        if back is not None:
            state, mirror = back
            state.wall_time = time.perf_counter() - t0
            records.append(_Record(state, branch, False, True, n))
            ticker.update(n, n / (len(path) - 1), f"flat at w = {target:.4g} m ({branch}), "
                          f"force {state.force:.4g} N", 0)
            if progress is not None:
                progress(f"level {n} of {len(path) - 1} ({branch}): w = {target:.6g} m, force "
                         f"{state.force:.6g} N, retraced (the approach's state)")
            _release_behind(records, state)
            continue
        try:
            state, jumps, iterations, halvings = _advance(state, target, pre, n, landing)
        except ConvergenceError as exc:
            exc.sample = label
            raise
        if ups is not None and branch == "approach":
            ups.append((state, bool(jumps)))
        else:
            ups = None  # retraced no further once solved, nor after a second approach
        for before, after in jumps:
            if records[-1].state is not before:
                records.append(_Record(before, branch, False, False, n))
            records.append(_Record(after, branch, True, after is state, n))
        state.iterations, state.cuts = iterations, halvings
        state.wall_time = time.perf_counter() - t0
        if records[-1].state is not state:
            records.append(_Record(state, branch, False, True, n))
        ticker.update(n, n / (len(path) - 1), f"flat at w = {target:.4g} m ({branch}), "
                      f"force {state.force:.4g} N", iterations)
        if progress is not None:
            progress(f"level {n} of {len(path) - 1} ({branch}): w = {target:.6g} m, force "
                     f"{state.force:.6g} N, {iterations} Newton iterations, {halvings} cuts, "
                     f"{len(jumps)} jumps, {state.wall_time:.3g} s")
        _release_behind(records, state)
    return records


def _evaluate(states) -> None:
    """The outputs (`AdhesiveState.fields`) of those `states` that lack them,
    each state on its own mesh."""
    todo = [s for s in states if s.fields is None]
    for model in {id(s.model): s.model for s in todo}.values():
        mine = [s for s in todo if s.model is model]
        ev = model.evaluate(mine)
        for j, s in enumerate(mine):
            s.fields = {name: values[j] for name, values in ev.items()}


def _release_behind(records: list, state: AdhesiveState) -> None:
    """Evaluate the recorded states on meshes other than `state`'s, and drop
    those meshes' factors (`AdhesiveModel.release`)."""
    behind = [r.state for r in records
              if r.state.model is not state.model and r.state.model.cond.lu is not None]
    _evaluate(behind)
    for s in behind:
        s.model.release()


def _retrace(ups: list, mirror: int, target: float):
    """The retraction's state at `target` when it runs back over a continuous
    stretch of the approach: (that state, its index in `ups`) or None.

    An elastic body with a conservative adhesion has no memory: its states
    are the local minima of Pi(u; w), and along a branch without a fold
    (Pi's Hessian positive definite) they are a function u(w) of the flat's
    position alone (implicit function theorem), whichever way the flat
    moves.  So while the retraction stands on the state the approach
    reached at level k, `ups[mirror]` (at the turn: the same state; `_trace`
    keeps `ups` only while every level of the retraction was retraced), and the
    approach came to it from level k - 1 at `target` without a jump
    (`_advance`'s continuity test, `AdhesiveModel.continuity`, passed on
    every step in between), the retraction's equilibrium at `target` is the
    approach's state there, on the same mesh; solving it again would
    retrace the same branch, with the same tests, to the solver's
    tolerance.  A step the approach crossed with a jump (the jump-in) is
    solved: retracting, the contact hangs on past it (report 7.3's
    hysteresis).  The state returned is a copy with no Newton iterations or
    cuts of its own.  A jump smaller than the continuity test's allowance
    (recorded on approach as a steep continuous stretch) is retraced as the
    approach passed it.
    """
    if mirror < 1 or ups[mirror][1]:
        return None
    before = ups[mirror - 1][0]
    if before.w != target:
        return None
    return replace(before, iterations=0, cuts=0, wall_time=0.0), mirror - 1


# --- outputs -------------------------------------------------------------------------
def retract_indices(branch: np.ndarray) -> np.ndarray:
    """Records of the retraction, with the turning point (the deepest state) first."""
    idx = np.nonzero(branch == "retract")[0]
    if idx.size and idx[0] > 0:
        idx = np.concatenate(([idx[0] - 1], idx))
    return idx


def _refine_pull_off(records: list, pre: dict, resolution: float) -> None:
    """Bisect the path around the largest tensile force on retraction.

    States at the midpoints between the minimum of the force and its
    neighbours on the same continuous branch (continued from the minimum,
    rejected if discontinuous from it) are inserted, until the neighbours
    are `resolution` apart.  Inserted records are not `requested`.
    """
    for _ in range(40):
        idx = list(retract_indices(np.array([r.branch for r in records])))
        if not idx:
            return
        i = min(idx, key=lambda k: records[k].state.force)
        src = records[i].state
        if src.force >= 0:
            return
        inserts = []
        for j in (i + 1, i - 1):  # the later index first: inserting keeps the other valid
            if j not in idx:
                continue
            b = max(i, j)  # records[b].jump: a discontinuity between b - 1 and b
            if records[b].jump or abs(records[j].state.w - src.w) <= resolution:
                continue
            mid = 0.5 * (records[j].state.w + src.w)
            try:
                new, jumps, its, cuts = _advance(src, mid, pre)
            except (ConvergenceError, _Overflow):
                continue
            if jumps:  # not on the branch of the minimum
                continue
            new.iterations, new.cuts = its, cuts
            inserts.append((b, _Record(new, records[b].branch, False, False, records[b].step)))
        if not inserts:
            return
        for b, rec in inserts:  # descending b
            records.insert(b, rec)


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
    approach's state (module docstring, "Control and jumps") has none.
    Raises `ConvergenceError` naming the step (and `label`).
    """
    t_start = time.perf_counter()
    pre = resolve("adhesive", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    R = tip_radius(geometry)
    Es = material.contact_modulus
    mu = adhesion.tabor_parameter(R, Es)
    if interferences is None:
        if w_max is None:
            d0 = (math.pi**2 * adhesion.dgamma**2 * R / Es**2) ** (1 / 3)  # JKR zero-load scale
            w_max = max(4.0 * adhesion.d, 2.0 * d0)
        if w_min is None:
            w_min = -max(adhesion.range - adhesion.d, (2.0 * mu + 4.0) * adhesion.d)
        path = adhesive_path(adhesion, w_max, w_min, pre["steps_per_d"], pre["far_steps"])
    else:
        path = np.atleast_1d(np.asarray(interferences, dtype=float))
        if path.ndim != 1 or path.size == 0 or not np.all(np.isfinite(path)):
            raise ValueError("interferences must be a non-empty finite 1-D sequence")
    band = 1.0
    for _ in range(4):
        model = adhesive_model(geometry, material, adhesion, float(path.max()), pre, factor, band)
        try:
            records = _trace(model, path, pre, label, progress)
            break
        except _Overflow:
            if model.scales.r_band >= 0.9 * geometry.extent:
                raise ContactZoneError("the adhesive ring reached the edge of the hill") from None
            band *= 1.5
            if progress is not None:
                progress("the adhesive ring outgrew the refined band: the path again, on a "
                         "band 1.5 times wider")
    else:
        raise ContactZoneError("the adhesive ring outgrew the refined band")
    _refine_pull_off(records, pre, adhesion.d / 64.0)
    states = [r.state for r in records]
    models = list({id(s.model): s.model for s in states}.values())
    _evaluate(states)
    ev = {name: np.array([s.fields[name] for s in states]) for name in states[0].fields}
    axi = geometry.axisymmetric
    a = ev["contact_radius"]
    w = np.array([s.w for s in states])
    F = np.array([s.force for s in states])
    branch = np.array([r.branch for r in records])
    jump = np.array([r.jump for r in records])
    total = time.perf_counter() - t_start
    own = np.array([s.wall_time for s in states])
    rec = dict(
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
    )
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


# --- Fig. 7.6 ----------------------------------------------------------------------------
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


def smooth_aluminum_curves(radii=(15.4e-6, 30e-6, 60e-6), d: float = 0.3e-9,
                           dgamma: float = 1.0, E: float | None = None, nu: float | None = None,
                           w_max: float = 10e-9, accuracy="draft",
                           cutoff: float | None = None) -> xr.Dataset:
    """Load-deflection curves of elastic aluminum asperities with adhesion (Fig. 7.6).

    Report 7.3: very smooth 6061-T4 aluminum (E and nu of
    `BodnerPartom.aluminum_6061_t4`, 6.3.1, unless given), asperity tip radii 15 to 300 um, dgamma =
    1 J/m^2 (DESIGN errata), d = 0.3-0.5 nm, elastic.  Each radius is a
    shallow paraboloid (`Paraboloid`: the half space with a paraboloidal
    gap; the contact radius stays below 3 % of R here, where sphere and
    paraboloid differ by well under 1 %), approached from the cut-off to
    `w_max` and retracted until it lets go.  Returns a Dataset on dims
    (radius, step) (`stack_runs`) with, per radius, the pull-off force,
    the Tabor parameter and the jump interferences, and the DMT and JKR
    pull-off forces 2 pi R W_c and 3/2 pi R W_c for comparison.

    Cost grows with the Tabor parameter (R^(1/3) / d): with d = 0.3 nm,
    mu = 4.7, 5.9, 7.5 at 15.4, 30, 60 um, and 10, 13 at 150 and 300 um
    (the flat end of 7.3's range), whose mesh follows the contact edge
    (module docstring, "Mesh").  The report's Fig. 7.6 shows R = 15.4 um
    only; the default adds two flatter radii (their measured costs: docs,
    changelog, 'Adhesion').  With d = 0.5 nm, mu is 0.6 times smaller.
    """
    alloy = BodnerPartom.aluminum_6061_t4()
    mat = LinearElastic(alloy.E if E is None else E, alloy.nu if nu is None else nu)
    law = LennardJones(dgamma, d) if cutoff is None else LennardJones(dgamma, d, cutoff)
    radii = np.asarray(radii, dtype=float)
    runs = [solve_asperity_adhesive(Paraboloid(float(R)), mat, law, w_max=w_max,
                                    accuracy=accuracy, label=f"R = {R * 1e6:.4g} um")
            for R in radii]
    ds = stack_runs(runs, "radius", radii, dict(units="m", long_name="asperity tip radius"))
    W = law.work_of_adhesion
    ds["pull_off_force_dmt"] = ("radius", 2 * np.pi * radii * W,
                                dict(units="N", long_name="DMT pull-off 2 pi R W_c(d)"))
    ds["pull_off_force_jkr"] = ("radius", 1.5 * np.pi * radii * W,
                                dict(units="N", long_name="JKR pull-off 3/2 pi R W_c(d)"))
    ds.attrs.update(material=describe(mat), adhesion=describe(law), report="7.3, Fig. 7.6",
                    geometry="Paraboloid (shallow: half space with a paraboloidal gap)",
                    **accuracy_attrs(accuracy),
                    w_max=float(w_max),
                    sign_convention="force compressive positive; adhesion (attraction) negative")
    return ds
