"""The one time-marching driver of the finite element package.

An incremental solution (report 3.6: the rate form of 3.22, solved step by
step in time; 6.3 for the asperity) advances a body along a prescribed
history in accepted steps.  Every marching problem of the package (the
axisymmetric and plane-strain inelastic asperity, `inelastic`; the 3-D
asperity pressed and slid, `solid3d`) runs the same loop:

1. a step n starts at the time t reached; the problem names its largest time
   step (a cap) and the next time the step may not cross (a knot of the
   history, or of the grid its outputs are reported on);
2. a try ends at ``next_time(t, min(dt, cap), knot)``; the problem solves it
   (Newton, `asperity.fe.solvers.nonlinear`) and either accepts it, rejects it
   with a reason and a factor to shrink the time step by (Newton failed, the
   step moved too far, its time error is too large), or asks to try again
   without counting a cut (a larger contact zone, an event to locate);
3. a rejected try is a cut (`StepCuts`): after ``max_cuts`` of them in one
   step the problem's `ConvergenceError` names the step and where it failed;
4. the accepted step is committed by the problem, which returns the next time
   step (from Newton's pace, the time-error controller and the strain limit)
   and whether the step is to be solved again (after a new mesh) or the run
   stops (an event, rupture, a stall).

The loop itself holds no physics: what a step is, how it is solved, what is
recorded and when to stop belong to the problem (`Marching`).  It ends at the
end of the history or after ``max_steps`` accepted steps.
"""

from __future__ import annotations

from dataclasses import dataclass

from asperity.fe.errors import ConvergenceError
from asperity.fe.solvers.nonlinear import StepCuts, next_time


@dataclass
class Trial:
    """The outcome of one try of a step ending at ``t_new``.

    ``reason`` is None for an accepted try, else why it was rejected (a cut);
    the next try's time step is then ``shrink`` times this one's.  ``again``
    asks for another try that is not a cut, with the time step ``dt`` (None:
    the same one).  ``data`` carries what the problem needs to commit it.
    """

    t_new: float
    reason: str | None = None
    shrink: float = 0.5
    again: bool = False
    dt: float | None = None
    data: object = None


@dataclass
class Accepted:
    """What a problem says after committing a step: the next time step ``dt``;
    ``redo``: the step was not committed and is solved again (same step
    number, e.g. on a new mesh); ``stop``: the run ends here."""

    dt: float
    redo: bool = False
    stop: bool = False


class Marching:
    """A problem marched in time by `march`.

    Attributes ``t`` (the time reached), ``end`` (the end of the history) and
    ``max_cuts`` (rejected tries allowed per step); the methods below.
    """

    t: float
    end: float
    max_cuts: int

    def begin(self, n: int, dt: float) -> tuple[float, float]:
        """Start step ``n`` with the proposed time step ``dt``: its cap and the
        knot it may not cross."""
        raise NotImplementedError

    def attempt(self, n: int, t_new: float, cuts: StepCuts) -> Trial:
        """Solve one try of step ``n`` from ``t`` to ``t_new``."""
        raise NotImplementedError

    def failure(self, cuts: StepCuts, trial: Trial) -> ConvergenceError:
        """The error once the step's cuts are exhausted at ``trial``."""
        raise NotImplementedError

    def cut(self, n: int, dt: float, trial: Trial) -> None:
        """Told of a cut of step ``n`` to the time step ``dt`` (logging)."""

    def accept(self, n: int, trial: Trial, cuts: StepCuts) -> Accepted:
        """Commit the accepted try of step ``n``."""
        raise NotImplementedError


def march(problem: Marching, dt: float, max_steps: int) -> int:
    """March `problem` from its time ``t`` to its ``end`` with the first time
    step ``dt``, at most ``max_steps`` accepted steps; returns the number of
    the last step accepted.

    Raises the problem's `ConvergenceError` when a step is cut more than
    ``max_cuts`` times.
    """
    n = 0
    while problem.t < problem.end * (1 - 1e-12) and n < max_steps:
        n += 1
        cuts = StepCuts(n, problem.max_cuts)
        cap, knot = problem.begin(n, dt)
        while True:
            trial = problem.attempt(n, next_time(problem.t, min(dt, cap), knot), cuts)
            if trial.again:
                dt = dt if trial.dt is None else trial.dt
                continue
            if trial.reason is None:
                break
            cuts.cut()
            if cuts.exhausted:
                raise problem.failure(cuts, trial)
            dt = trial.shrink * (trial.t_new - problem.t)
            problem.cut(n, dt, trial)
        step = problem.accept(n, trial, cuts)
        dt = step.dt
        if step.redo:
            n -= 1
            continue
        if step.stop:
            break
    return n
