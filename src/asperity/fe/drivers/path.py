"""The one path-following driver: from a converged state to a prescribed flat
position, with step control, for the elastic and the adhesive paths.

Under displacement control (the flat's position w prescribed, report 3.5
and 7.3) a path is a sequence of equilibria.  `follow` takes one requested
step from a converged state to a `target`:

- each try at a position `goal` starts from the path's predictor and is
  solved by the path (`Steps.solve`, Newton in `asperity.fe.solvers`);
- a try whose Newton fails, or whose end is not on the branch of the
  state (`Steps.continuity`: a jump), marks that position *bad*; the
  bracket from the state to the nearest bad position is bisected, a good
  midpoint advancing the state and a bad one shrinking the bracket;
- a position where Newton failed is tried again from the next state
  reached: every time on a path without folds (`Steps.retry_once` false,
  the elastic path: Newton failed because the step was long), once on a
  path with folds (the adhesive path: a second failure means a fold is
  near, which the bisection then locates);
- a bracket ``Steps.smallest`` long is crossed as it comes: a
  discontinuous step that short is a jump (the fold of the equilibrium
  curve; report 7.3), recorded with the states on both sides;
- each failed try is a cut (`nonlinear.StepCuts`), except a failed retry
  of a path that retries once; after ``Steps.limit`` cuts, or a failure at
  the smallest step, the path follows its branch through the fold
  (`Steps.fold`, arc-length continuation) or, having none, raises
  `ConvergenceError` naming the step and the last position reached.

Each state reached is handed to `Steps.settle` (the adhesive path moves it
to a mesh that follows its contact edge) and `Steps.check`.  `follow`
returns the final state, the jumps as (state before, state after), the
Newton iterations spent and the cuts.
"""

from __future__ import annotations

from asperity.fe.errors import StepFailed
from asperity.fe.solvers import nonlinear


class Steps:
    """What `follow` asks of a path; the defaults are a path without folds,
    jumps or remeshing (the elastic path)."""

    #: a step this short is taken as it comes (a jump where discontinuous)
    smallest: float = 0.0
    #: cuts of one requested step before the path gives up or folds
    limit: int = 8
    #: a failed position is retried once (a path with folds), not every time
    retry_once: bool = False

    def solve(self, state, goal: float, small: bool):
        """(the state at `goal`, Newton iterations, the predictor it started
        from); raises `StepFailed`."""
        raise NotImplementedError

    def continuity(self, state, new, predictor) -> tuple[str, int]:
        """("continuous", "steep" or "jump"; Newton iterations spent)."""
        return "continuous", 0

    #: `fold(state, target)` -> (state, new, jumped, iterations), or None
    fold = None

    def settle(self, new, step: int):
        """(the state to go on from, Newton iterations spent)."""
        return new, 0

    def check(self, new) -> None:
        """Raise if the path cannot go on from `new`."""


def follow(steps: Steps, state, target: float, step: int = 0):
    """From the converged `state` to the flat position `target` (module
    docstring); `step` is the caller's index of the requested step, named by
    `ConvergenceError`.  Returns (state, jumps, iterations, cuts)."""
    smallest = steps.smallest
    target = float(target)
    goals = [target]
    iterations = 0
    cuts = nonlinear.StepCuts(step, steps.limit)  # restarted after a fold
    jumps = []
    bads = []  # positions known to fail or to be discontinuous, nearest last
    again = set()  # failed positions to try again from the next state reached
    retry = False  # the last attempt advanced the state
    while goals:
        goal = goals[-1]
        while bads and (bads[-1] - state.w) * (target - state.w) <= 0:  # reached after all
            bads.pop()
        if bads and (goal - bads[-1]) * (target - state.w) >= 0:  # the goal is at or beyond it
            bad = bads[-1]
            if (retry and bad in again) or abs(bad - state.w) <= smallest:
                nxt = bad
            else:
                nxt = 0.5 * (state.w + bad)
            if nxt != goal:
                goals.append(nxt)
                continue
        small = abs(goal - state.w) <= smallest
        retried = retry and goal in again
        once = retried and steps.retry_once  # its one retry
        failure = None
        try:
            new, its, pred = steps.solve(state, goal, small)
            iterations += its
        except StepFailed as exc:
            iterations += exc.iterations
            if not once:  # a failed retry of a path with folds halves nothing
                cuts.cut()
            if small or cuts.exhausted:
                failure = f"{exc} (at w = {goal:.6g} m)"
            else:
                bads.append(goal)
                goals = [target]
                _mark(again, goal, not once, steps.retry_once)
                retry = False
                continue
        if failure is None:
            verdict, its = steps.continuity(state, new, pred)
            iterations += its
            jumped = verdict != "continuous"
            if jumped and not small:
                if not once:
                    cuts.cut()
                if cuts.exhausted:
                    failure = "the path stays discontinuous"
                else:
                    # a steep position is retried: not when this was its retry
                    _mark(again, goal, verdict == "steep" and not retried, steps.retry_once)
                    bads.append(goal)
                    goals = [target]
                    retry = False
                    continue
        if failure is not None:  # the bisection stalled: through the fold, if any
            if steps.fold is None:
                raise cuts.error(target, state.w, failure)
            try:
                state, new, jumped, its = steps.fold(state, target)
            except StepFailed as exc:
                raise cuts.error(target, state.w, f"{failure}; then {exc}") from None
            iterations += its
            cuts.restart()
        new, its = steps.settle(new, step)
        iterations += its
        if jumped:
            jumps.append((state, new))
            bads = []
        steps.check(new)
        state = new
        retry = True
        if failure is None:
            goals.pop()
        else:  # the pass landed at a position of its own
            goals = [target]
    return state, jumps, iterations, cuts.count


def _mark(again: set, goal: float, retryable: bool, once: bool) -> None:
    """Whether the bad position `goal` is tried again from the next state
    reached; a path that retries once keeps only its latest such position."""
    if once:
        again.clear()
    if retryable:
        again.add(goal)
    else:
        again.discard(goal)
