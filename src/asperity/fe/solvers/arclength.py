"""The adhesive asperity's branch followed through its fold by arc length, and the
jump from the fold (report 7.3).

Under displacement control a branch of stable equilibria of the adhesive
asperity (`asperity.fe.solvers.adhesive`) ends at a fold of the equilibrium
curve: jump-in on approach, jump-off on retraction.  Near the fold du/dw
blows up, du/dw ~ (w - w_fold)^(-1/2); at a large Tabor parameter the branch
before the jump-off fold is steep over a long stretch (many ring elements
peeling one by one), and a step control that bisects in w (the driver's,
`asperity.fe.drivers.adhesive_trace`) can stall there.

`FoldPath` parametrizes the branch by its arc length s in (u, w) instead,
with the inner product

    <x, y> = x_u . y_u / m + x_w y_w

(m surface dofs: the root mean square of the surface displacement), which
stays regular through the fold (pseudo-arc-length continuation: H. B.
Keller, Numerical solution of bifurcation and nonlinear eigenvalue problems,
in P. H. Rabinowitz (ed.), Applications of Bifurcation Theory, Academic
Press, 1977).  From a point (u0, w0) with unit tangent t = +-(du/dw, 1) /
|(du/dw, 1)| the next point an arc h along solves the bordered system

    R(u, w) = 0,    <t, (u - u0, w - w0)> = h,

by Newton's method from the tangent predictor (u0, w0) + h t, each
iteration by block elimination: J a = -R, J b = -R_w (b = du/dw),
dw = -(g + <t, (a, 0)>) / <t, (b, 1)> with g the arc condition's residual,
du = a + dw b (`FoldPath.corrector`; J may be indefinite beyond the fold).
Steps in s go on until dw/ds changes sign; the fold so bracketed is
located by bisection in s, its position estimated by the quadratic w(s)
with the slopes s0, s1 of dw/ds at the ends of the bracket, an arc h apart,

    w_fold = w_lo - s0^2 h / (2 (s1 - s0)),

until the stable side is within ``min_step * d`` of it.  The jump is then
solved from the stable state at the fold to ``min_step * d`` beyond it
(`through_fold`); where it does not converge from the tangent predictor
(the contact peels over a band of many elements at once), from the branch
out of contact that the asperity jumps off to (`Landing`: the states the
approach passed before it jumped in, or the undeformed body where the tip
is beyond the cut-off), kept only if it lies lower in energy (a snap
releases energy).
"""

from __future__ import annotations

import math

import numpy as np

from asperity.fe.contact.adhesion import LennardJones
from asperity.fe.errors import StepFailed
from asperity.fe.solvers.adhesive import (JUMP_ITERATION_FACTOR, AdhesiveState, on_nodes,
                                          predictor)
from asperity.fe.solvers.newton import ROUNDOFF_FACTOR

#: the fold path (`FoldPath`): the first arc between FOLD_ARC d (root mean
#: square surface displacement); a corrector may move at most FOLD_MOVE d
#: from the predictor; at most FOLD_POINTS points to reach the fold and as
#: many to locate it
FOLD_ARC = (0.01, 0.5)
FOLD_MOVE = 0.5
FOLD_POINTS = 60


class FoldPath:
    """The branch of a state followed through its fold (module docstring).

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
        branch): it is factored by LU there (`AdhesiveTangent.factor`).  No line
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
                u, parts, T, its = self.newton.solve(goal, predictor(new, goal))
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


def through_fold(state: AdhesiveState, target: float, pre: dict,
                  landing: "Landing | None" = None):
    """The jump from the fold of `state`'s branch towards `target` (`FoldPath`).

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
    path = FoldPath(state, target, pre)
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
    pred = predictor(before, goal)
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


class Landing:
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
        u_hi = on_nodes(hi, model)
        if hi.w == w:
            return u_hi
        if k:
            lo = self.states[k - 1]
            w_lo, u_lo = lo.w, on_nodes(lo, model)
        else:
            w_lo, u_lo = self.free, np.zeros(model.zone.ndofs)
        t = (w - w_lo) / (hi.w - w_lo)
        return (1.0 - t) * u_lo + t * u_hi
