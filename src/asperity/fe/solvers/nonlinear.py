"""The one Newton iteration of the finite element drivers (report 3.5).

Every driver solves its equilibrium R(x) = 0 at a load step by the same
loop (`newton`); what differs is passed in as a `Problem`:

* the residual R and the data the rest needs (`Problem.evaluate`), the
  force scale and the round-off floor of the convergence test
  ||R|| <= max(tolerance * scale, floor), and a check of the data
  (a constitutive update that did not converge at some point);
* the Newton direction, each problem with its own linear algebra: the
  dense Cholesky of the condensed stiffness (`newton`), the Schur
  complement on the active surface nodes (`adhesive.AdhesiveTangent`), SuperLU
  (`inelastic_model`), SuperLU reused as a GMRES preconditioner (`linear.ReusedLU`);
* the line search: backtracking on an energy (`EnergySearch`: Armijo,
  with a decrease of the residual accepted where energy differences drown
  in round-off, and trial points optionally projected, `Problem.project`)
  or on the residual norm (`ResidualSearch`, a few halvings);
* a hook at convergence (`Problem.settle`: the adhesive solver leaves a
  saddle along its lowest mode) and a monitor of the iterations.

A line search is called as ``search(problem, x, R, ||R||, d)`` and
returns the new iterate and, if it evaluated it, ``problem.evaluate`` of
it (else None).

A try that fails (non-finite values, a diverging or stalled residual, a
failed linear solve) raises `errors.StepFailed` with the iterations it
took; the drivers cut the step and retry, and raise
`errors.ConvergenceError` when the cuts run out.

Step control (report 3.5), the same rules in every driver:

* `StepCuts` counts the cuts of one requested step (a failed try, or a
  state the driver rejects) and makes the `ConvergenceError` that names
  the step once they run out.  The elastic and adhesive drivers bisect in
  the interference (the adhesive one turns to its fold path, not to the
  error, when its cuts run out: `StepCuts.restart` after a fold);
* the time-marching drivers (inelastic, 3-D) end each try on the next knot
  of their history (`next_time`), cut a rejected try, and size the next
  step from the accepted one by its Newton iterations and cuts (`Pace`)
  and by the largest inelastic strain increment (`strain_limited`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from asperity.fe.errors import ConvergenceError, StepFailed

#: Armijo's sufficient decrease: merit(x + d) <= merit(x) + ARMIJO R.d
ARMIJO = 1e-4


@dataclass(frozen=True)
class EnergySearch:
    """Backtracking on the problem's energy (`Problem.merit`, gradient R).

    A step is accepted if the energy decreases by Armijo's rule or, where
    energy differences drown in round-off near the solution, if the
    residual norm decreases by the same factor: anywhere (``roundoff``
    None, a convex energy) or only where the energy rose by at most
    ``roundoff`` |energy| (a non-convex one, where accepting real increases
    lets Newton cycle between kinks).  With ``projected``, a full step that
    fails Armijo is retried with the trial points passed through
    `Problem.project`.  After ``halvings`` failures the last trial is taken.
    """

    halvings: int
    projected: bool = False
    roundoff: float | None = None

    def __call__(self, problem, x, R, rn, d):
        e0 = problem.merit(x)
        slope = R @ d
        if self.projected:
            trial = x + d
            if problem.merit(trial) <= e0 + ARMIJO * slope:
                return trial, None
        alpha = 1.0
        for _ in range(self.halvings):
            trial = x + alpha * d
            if self.projected:
                trial = problem.project(trial, x)
                # the projection changes the step: its own directional derivative
                drop = ARMIJO * (R @ (trial - x))
            else:
                drop = ARMIJO * alpha * slope
            e1 = problem.merit(trial)
            if e1 <= e0 + drop:
                return trial, None
            if self.roundoff is None or e1 - e0 <= self.roundoff * abs(e0):
                evaluated = problem.evaluate(trial)
                if np.linalg.norm(evaluated[0]) <= (1 - ARMIJO * alpha) * rn:
                    return trial, evaluated
            alpha *= 0.5
        return trial, None


@dataclass(frozen=True)
class ResidualSearch:
    """Backtracking on the residual norm: the step is halved until ||R||
    decreases, at most ``halvings`` times; then the last trial is taken."""

    halvings: int

    def __call__(self, problem, x, R, rn, d):
        alpha = 1.0
        for _ in range(self.halvings):
            trial = x + alpha * d
            evaluated = problem.evaluate(trial)
            r1 = np.linalg.norm(evaluated[0])
            if np.isfinite(r1) and r1 < rn:
                break
            alpha *= 0.5
        return trial, evaluated


class Problem:
    """What `newton` asks of a problem; subclasses override the methods.

    ``data`` is whatever `evaluate` returns beside the residual (tractions,
    stresses, material states); `newton` only passes it on.
    """

    def evaluate(self, x):
        """(R, data): the residual whose norm converges, and its data."""
        raise NotImplementedError

    def scale(self, x, data) -> float:
        """Force scale of the convergence test ||R|| <= tolerance * scale."""
        raise NotImplementedError

    def floor(self, x, data) -> float:
        """Round-off level below which ||R|| counts as converged."""
        raise NotImplementedError

    def check(self, data, iteration: int) -> None:
        """Raise `StepFailed` if the data are not admissible."""

    def linearize(self, x, data):
        """Called once per iteration before the convergence test; what it
        returns (e.g. a tangent) goes to `direction` and `settle`."""
        return None

    def direction(self, x, R, data, tangent, iteration: int) -> np.ndarray:
        """The Newton correction d (J d = -R); raise `StepFailed` if there is none."""
        raise NotImplementedError

    def settle(self, x, data, tangent, iteration: int):
        """At convergence: None to accept x, or a new start to iterate from."""
        return None

    def monitor(self, iteration: int, rn: float, scale: float, data) -> None:
        """Sees every iteration's residual norm and scale (traces)."""

    def merit(self, x) -> float:
        """Energy whose gradient is R (for `EnergySearch`)."""
        raise NotImplementedError

    def project(self, trial, x):
        """Trial point of a projected `EnergySearch`."""
        return trial


class ContactScale:
    """The force scale of a step's convergence test (`Problem.scale`).

    The contact force norm of the current iterate or, if larger, the
    largest of the step's iterates so far, but not more than twice
    ``reference``, that of the last accepted step.  An overshooting
    iterate (points pushed deep into the stiff penalty) would otherwise
    loosen the test for the rest of the step.
    """

    def __init__(self, reference: float):
        self.reference = float(reference)
        self.top = 0.0

    def __call__(self, force: float) -> float:
        self.top = max(self.top, force)
        return max(force, min(self.top, 2.0 * self.reference))


def check_local_update(state, iteration: int) -> None:
    """`StepFailed` if the constitutive update of a material state did not
    converge at some point (its ``converged`` flags, if it has them)."""
    conv = getattr(state, "converged", None)
    if conv is not None and not np.all(conv):
        raise StepFailed("local constitutive update did not converge", iteration)


def newton(problem: Problem, x0, tolerance: float, max_iterations: int, search,
           divergence: float | None = None):
    """Newton iterations from x0; returns (x, data, iterations).

    Converged when ||R|| <= max(tolerance * scale, floor) (and `settle`
    accepts).  Raises `StepFailed` (with the iterations done) on a
    non-finite residual or correction, a residual grown beyond
    ``divergence`` times the first, a failed direction, or no convergence
    in `max_iterations`.
    """
    x = np.array(x0, dtype=float)
    R, data = problem.evaluate(x)
    r0 = np.linalg.norm(R)
    for it in range(max_iterations + 1):
        rn = np.linalg.norm(R)
        if not np.isfinite(rn):
            raise StepFailed("non-finite residual", it)
        problem.check(data, it)
        tangent = problem.linearize(x, data)
        scale = problem.scale(x, data)
        problem.monitor(it, rn, scale, data)
        if rn <= max(tolerance * scale, problem.floor(x, data)):
            moved = problem.settle(x, data, tangent, it)
            if moved is None:
                return x, data, it
            x = moved
            R, data = problem.evaluate(x)
            continue
        if divergence is not None and rn > divergence * max(r0, np.finfo(float).tiny):
            raise StepFailed("diverging residual", it)
        if it == max_iterations:
            break
        d = problem.direction(x, R, data, tangent, it)
        if not np.all(np.isfinite(d)):
            raise StepFailed("non-finite Newton correction", it)
        x, evaluated = search(problem, x, R, rn, d)
        R, data = problem.evaluate(x) if evaluated is None else evaluated
    raise StepFailed(f"no convergence in {max_iterations} iterations", max_iterations)


# ----------------------------------------------------------------------------- step control
class StepCuts:
    """The cuts of one requested step.

    `cut` counts one (a try that failed or was rejected); `exhausted` says
    when more than ``limit`` were made since the start or the last
    `restart`; `error` is then the `ConvergenceError` naming ``step``, the
    position tried and the last one reached, with the cuts made in all
    but the last.  ``count`` is the cuts made in all (``step_cuts`` of the
    drivers' output).
    """

    def __init__(self, step: int, limit: int):
        self.step, self.limit = step, limit
        self.count = 0
        self._window = 0

    def cut(self) -> None:
        self.count += 1
        self._window += 1

    def restart(self) -> None:
        """A fresh allowance of ``limit`` cuts (the adhesive path after a fold)."""
        self._window = 0

    @property
    def exhausted(self) -> bool:
        return self._window > self.limit

    def error(self, tried: float, reached: float, detail: str) -> ConvergenceError:
        return ConvergenceError(self.step, tried, reached, self.count - 1, detail)


def next_time(t: float, dt: float, knot: float) -> float:
    """The end of a try of time step ``dt`` from ``t``: not beyond the next
    knot of the history, and snapped onto it when closer than 1e-9 of the
    way (no sliver step before a knot)."""
    t_new = min(t + dt, knot)
    if knot - t_new < 1e-9 * (knot - t):
        t_new = knot
    return t_new


@dataclass(frozen=True)
class Pace:
    """The next time step after an accepted one of length h, from how hard
    Newton worked: ``factor`` x h.

    The factor is ``growth`` (or the ``proposed`` one of a time-error
    controller), at most 1 after a step that was cut or took more than
    ``fast`` iterations, and at most ``shrink`` after one that took
    ``slow`` or more.
    """

    fast: int
    growth: float
    slow: int | None = None
    shrink: float = 1.0

    def factor(self, iterations: int, cuts: int, proposed: float | None = None) -> float:
        fac = self.growth if proposed is None else proposed
        if cuts:
            fac = min(fac, 1.0)
        if self.slow is not None and iterations >= self.slow:
            fac = min(fac, self.shrink)
        elif iterations > self.fast:
            fac = min(fac, 1.0)
        return fac


def strain_limited(dt: float, h: float, step_strain: float, largest: float) -> float:
    """``dt`` limited so that the next step's largest inelastic strain
    increment is about 0.8 ``largest`` if it scales with the step (the last
    step of length ``h`` made ``step_strain``), and never below h / 2."""
    if step_strain > 0:
        dt = min(dt, h * max(0.5, 0.8 * largest / step_strain))
    return dt
