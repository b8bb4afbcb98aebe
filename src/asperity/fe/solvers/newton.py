"""Newton-Raphson on the condensed contact problem of an elastic body.

For an elastic body the only nonlinearity is the contact traction on the
top surface, so the equations (report 3.28) are solved for the surface
u_z alone:

    R(u) = K_S u + int t_N(a(u)) N W ds = 0,     J = K_S + int t_N'(a) N N^T W ds,

with K_S the condensed stiffness (`assembly.CondensedStiffness`), by the
Newton iteration of `nonlinear.newton` with a dense Cholesky of J.  R is
the gradient of the convex energy 1/2 u^T K_S u + int Phi(a) W ds, so each
Newton step is safeguarded by a backtracking line search on that energy
(or on the residual norm where energy differences drown in round-off).
Converged when ||R|| <= tolerance * ||f_contact|| or, for very stiff
penalties, when ||R|| reaches its round-off level (`ContactNewton.floor`).

The levels of a loading curve are reached one after another, with step
control, by the path-following driver (`asperity.fe.drivers.path`,
`asperity.fe.drivers.elastic.continuation`), each from the last converged
state with the tangent predictor u + dw du/dw (`LevelState.dudw`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from asperity.fe.solvers import nonlinear
from asperity.fe.contact.penalty import AugmentedPenalty, ContactZone
from asperity.fe.errors import StepFailed
from asperity.fe.solvers.nonlinear import EnergySearch, Problem


#: Newton stops once the residual is below this multiple of its round-off
#: level (`ContactNewton.floor`), which matters for very stiff penalties
ROUNDOFF_FACTOR = 10.0

#: the exact option's stiffness dF/dw holds the points in contact by springs
#: this much stiffer than the augmented Lagrangian's (relative error ~ 1 / scale)
EXACT_TANGENT_SCALE = 1e6


#: backtracking on the convex energy (Armijo) or, where energy differences
#: drown in round-off near the solution, on the residual
LINE_SEARCH = EnergySearch(halvings=40)


@dataclass
class LevelState:
    """A converged state at interference w."""

    w: float
    u: np.ndarray           # surface u_z (zone dofs)
    dudw: np.ndarray        # tangent du/dw
    traction: np.ndarray    # t_N at the facet quadrature points
    force: float            # total force [N] or [N/m]
    stiffness: float        # dF/dw from the consistent tangent
    iterations: int = 0
    cuts: int = 0
    wall_time: float = 0.0
    multipliers: np.ndarray | None = None  # the exact contact's, at the quadrature points


class ContactNewton:
    """Solves R(u) = 0 on a `ContactZone` with condensed stiffness `K`."""

    def __init__(self, K: np.ndarray, zone: ContactZone, tolerance: float = 1e-8,
                 max_iterations: int = 25, divergence: float = 1e8):
        self.K = K
        self.zone = zone
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        self.divergence = divergence

    def energy(self, law, u, w):
        """The convex energy 1/2 u^T K_S u + int Phi(a) W ds (module docstring)."""
        a = self.zone.penetration(u, w)
        return 0.5 * u @ self.K @ u + np.sum(law.potential(a) * self.zone.weights)

    def floor(self, u, w, dt) -> float:
        """Round-off level of the residual: below it no iteration can go.

        The penetration a = z + u + w is a difference of much larger
        numbers (relative error eps (|z| + |u| + w) / a), which the penalty
        stiffness t' amplifies; plus the rounding of K_S u.
        """
        eps = np.finfo(float).eps
        zone = self.zone
        up = np.einsum("jf,jg->fg", np.abs(u)[zone.facet_nodes], np.abs(zone.N))
        da = eps * (np.abs(zone.z0) + up + abs(w))
        return (np.linalg.norm(zone.nodal(dt * da))
                + eps * np.linalg.norm(np.abs(self.K) @ np.abs(u)))

    def residual(self, law, u, w):
        a = self.zone.penetration(u, w)
        t, dt = law.traction(a)
        f = self.zone.nodal(t)
        return self.K @ u + f, f, t, dt

    def solve(self, law, w: float, u0: np.ndarray):
        """Newton iterations from u0 (`nonlinear.newton`); returns (u, t, dt, iterations)."""
        u, (f, t, dt), its = nonlinear.newton(_Level(self, law, w), u0, self.tolerance,
                                              self.max_iterations, LINE_SEARCH, self.divergence)
        return u, t, dt, its

    def tangent(self, dt: np.ndarray) -> np.ndarray:
        """du/dw at a converged state: J du/dw = -int t' N W."""
        J = self.K + self.zone.matrix(dt)
        rhs = -self.zone.nodal(dt)
        if not np.any(rhs):
            return np.zeros(self.zone.ndofs)
        return sla.cho_solve(sla.cho_factor(J), rhs)

    def state(self, w, u, t, dt, iterations=0, cuts=0) -> LevelState:
        dudw = self.tangent(dt)
        zone = self.zone
        da = np.einsum("jf,jg->fg", dudw[zone.facet_nodes], zone.N) + 1.0
        return LevelState(w, u, dudw, t, zone.total(t), zone.total(dt * da),
                          iterations, cuts)


class _Level(Problem):
    """R(u) = 0 at interference w with penalty law `law` (module docstring)."""

    def __init__(self, solver: ContactNewton, law, w: float):
        self.solver, self.law, self.w = solver, law, w

    def evaluate(self, u):
        R, f, t, dt = self.solver.residual(self.law, u, self.w)
        return R, (f, t, dt)

    def scale(self, u, data):
        return np.linalg.norm(data[0])

    def floor(self, u, data):
        return ROUNDOFF_FACTOR * self.solver.floor(u, self.w, data[2])

    def direction(self, u, R, data, tangent, iteration):
        J = self.solver.K + self.solver.zone.matrix(data[2])
        try:
            return sla.cho_solve(sla.cho_factor(J, check_finite=True), -R)
        except (np.linalg.LinAlgError, ValueError) as exc:
            raise StepFailed(f"tangent not positive definite: {exc}", iteration) from None

    def merit(self, u):
        return self.solver.energy(self.law, u, self.w)


def untouched(zone: ContactZone, w: float = 0.0) -> LevelState:
    n = zone.ndofs
    shape = zone.weights.shape
    return LevelState(w, np.zeros(n), np.zeros(n), np.zeros(shape), 0.0, 0.0)


def solve_uzawa(newton: ContactNewton, kappa: np.ndarray, w: float, u0: np.ndarray,
                multipliers: np.ndarray, tolerance: float, max_updates: int = 50):
    """Augmented Lagrangian: Newton on t = max(0, lambda + kappa a), then lambda <- t.

    Stops when the largest penetration at the quadrature points is below
    `tolerance` * w and the force changed by less than `tolerance` relative.
    Returns (u, t, dt, iterations, multipliers).
    """
    u = u0
    lam = multipliers
    total = 0
    force_old = None
    for _ in range(max_updates):
        law = AugmentedPenalty(kappa, lam)
        try:
            u, t, dt, its = newton.solve(law, w, u)
        except StepFailed as exc:
            raise StepFailed(str(exc), total + exc.iterations) from None
        total += its
        a = newton.zone.penetration(u, w)
        force = newton.zone.total(t)
        # points of zero measure (the apex of a body of revolution) carry
        # no force and no constraint
        pen = float(np.max(np.where((t > 0) & (newton.zone.weights > 0), a, 0.0), initial=0.0))
        lam = t
        if pen <= tolerance * w and force_old is not None and \
                abs(force - force_old) <= tolerance * abs(force):
            return u, t, dt, total, lam
        force_old = force
    raise StepFailed(f"Uzawa updates did not reach the tolerance in {max_updates}", total)
