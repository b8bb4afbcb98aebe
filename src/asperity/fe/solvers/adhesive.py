"""The adhesive Newton problem: a stable equilibrium of an elastic asperity with
Lennard-Jones adhesion at a prescribed position of the flat (report 3.3.3, 7.3).

The body and the contact are those of `asperity.fe.drivers.elastic` (P2 elements,
the stiffness condensed onto the candidate surface dofs, K_S, C1 penalty of
report 3.3.2 at the nodes); the adhesive traction of report 3.3.3 acts on
the free surface outside contact (`adhesion.LennardJones`, composite Gauss
rule per facet).  For an elastic body the equations (report 3.23 with the
boundary integrals of 3.4.1) are the stationarity conditions of

    Pi(u; w) = 1/2 u^T K_S u + int Phi_c(a) W ds + int Phi_a(a) W ds,

a = z + u_z + w the penetration, Phi_c the penalty potential and Phi_a the
adhesion potential (Phi_a' = t, `LennardJones.potential`).  Pi is not
convex: the adhesive tangent q'(s) is negative beyond s = 1.2 d, and an
elastic asperity can snap into contact and out of it.

Every state is a *stable* equilibrium, a local minimum of Pi
(`AdhesiveNewton.solve`, on the shared `nonlinear.newton`): Newton's matrix
is the consistent tangent

    J = K_S + int t'(a) N N^T W ds

of both rules (report 3.28 with the adhesive term beta of 3.30 and the
traction q of 3.32), shifted by tau diag K_S on the active nodes where it is
not positive definite, with a backtracking line search on Pi (Armijo) that
projects nodes pushed into the flat back to it (so a contact zips up in a
few iterations, not one node per iteration); a converged saddle is left
along its most negative eigenvector.  The linear algebra works on the
active surface nodes A only (`AdhesiveTangent`: with the compliance
C = K_S^-1, J x = b is solved through the Schur complement
S = C_AA^-1 + D of J onto A, at |A|^3 instead of m^3 per iteration).

A converged state (`AdhesiveState`) carries du/dw, from J du/dw =
-int t' N W, and the normal stiffness dF/dw; a step from it to another
flat position starts from the tangent predictor u + dw du/dw, its move
capped at d + 2 |dw| (`predictor`: du/dw blows up near a fold).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from asperity.fe.contact.adhesion import LennardJones
from asperity.fe.contact.penalty import C1Penalty, ContactZone
from asperity.fe.errors import StepFailed
from asperity.fe.solvers import nonlinear
from asperity.fe.solvers.newton import ROUNDOFF_FACTOR
from asperity.fe.solvers.nonlinear import EnergySearch, Problem

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
    #: the model (mesh) the state is an equilibrium of: an `AdhesiveModel`
    #: (`asperity.fe.drivers.adhesive_model`), with the ``newton``, ``zone`` and
    #: ``adhesion`` that the solvers here use
    model: object | None = None
    #: its outputs on that mesh (`AdhesiveModel.evaluate`), once evaluated
    fields: dict | None = None

    @property
    def force(self) -> float:
        return self.contact_force + self.adhesive_force


def on_nodes(state: AdhesiveState, model) -> np.ndarray:
    """The surface displacement of `state` interpolated onto the surface nodes of
    `model` (linearly in r)."""
    return np.interp(model.zone.coords[0], state.model.zone.coords[0], state.u)


def predictor(state: AdhesiveState, goal: float) -> np.ndarray:
    """The tangent predictor from `state` to the flat position `goal`, its move
    capped at d + 2 |dw| (du/dw blows up near a fold;
    `AdhesiveModel.continuity` allows d / 2 + 2 |dw| off it)."""
    dw = goal - state.w
    step_u = dw * state.dudw
    big = np.max(np.abs(step_u), initial=0.0)
    cap = state.model.adhesion.d + 2.0 * abs(dw)
    return state.u + (step_u if big <= cap else step_u * (cap / big))


class AdhesiveTangent:
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
                 reuse: "AdhesiveTangent | None" = None):
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
        (the unstable branch beyond a fold, `FoldPath`) and the result
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
    """Minimizes Pi(u; w) over the zone's surface u_z (module docstring)."""

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

    def tangent(self, dtp, dta, u=None, w=None) -> AdhesiveTangent:
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
        self._last = AdhesiveTangent(self.C, self.kdiag, nodes, D, last)
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

    def direction(self, T: AdhesiveTangent, R, iteration: int = 0):
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

    def state(self, w, u, parts, T: AdhesiveTangent, iterations=0, cuts=0) -> AdhesiveState:
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
