"""The one path-following driver (`asperity.fe.drivers.path.follow`): its step
control on paths whose answers are known, and the elastic and adhesive drivers
through it.

The drivers' own recorded references (iterations, cuts, forces and areas of
the elastic path with and without cut steps, and of the adhesive path with
its jumps) are in tests/fe/test_nonlinear.py; the adhesive fold forced
through `follow` in tests/fe/test_adhesion_fold.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import pytest

from asperity.fe import LinearElastic, Paraboloid, solve_asperity
from asperity.fe.drivers import adhesive_trace, elastic
from asperity.fe.drivers.path import Steps, follow
from asperity.fe.errors import ConvergenceError, StepFailed


@dataclass
class Point:
    w: float
    x: float = 0.0


class Reach(Steps):
    """A path whose Newton converges (in one iteration) only on steps up to
    `longest`; every try is logged."""

    def __init__(self, longest, retry_once=False, smallest=0.0, limit=8):
        self.longest, self.retry_once, self.smallest, self.limit = (
            longest, retry_once, smallest, limit)
        self.tries = []

    def solve(self, state, goal, small):
        ok = abs(goal - state.w) <= self.longest + 1e-12
        self.tries.append((goal, ok))
        if not ok:
            raise StepFailed("too long", 1)
        return Point(goal), 1, None


def test_a_path_without_folds_retries_every_failed_position_after_each_advance():
    # 1 fails, 0.5 fails, 0.25; then 0.5 and 1 again: 1 fails from 0.5, 0.75, 1
    steps = Reach(0.3)
    state, jumps, iterations, cuts = follow(steps, Point(0.0), 1.0, step=4)
    assert [g for g, _ in steps.tries] == [1.0, 0.5, 0.25, 0.5, 1.0, 0.75, 1.0]
    assert state.w == 1.0 and jumps == []
    assert iterations == 7 and cuts == 3  # one iteration a try; every failure a cut


def test_a_path_with_folds_retries_once_then_bisects_down_to_the_smallest_step():
    # after 0.5 is reached on its one retry, 1 is not tried again until the
    # bracket to it is `smallest` long: 0.75, 0.875, 0.9375, then 1
    steps = Reach(0.3, retry_once=True, smallest=0.1)
    state, jumps, iterations, cuts = follow(steps, Point(0.0), 1.0)
    assert [g for g, _ in steps.tries] == [1.0, 0.5, 0.25, 0.5, 0.75, 0.875, 0.9375, 1.0]
    assert state.w == 1.0 and cuts == 2


def test_the_cuts_run_out_with_an_error_naming_the_step_and_the_last_position():
    steps = Reach(0.01, limit=3)
    with pytest.raises(ConvergenceError) as err:
        follow(steps, Point(0.0), 1.0, step=7)
    assert err.value.step == 7 and err.value.reached == 0.0
    assert "too long" in str(err.value) and "step 7" in str(err.value)


class Cubic(Steps):
    """Equilibria x^3 - 3 x = w (energy x^4/4 - 3 x^2/2 - w x): the branch
    x < -1 folds at w = 2 (x = -1), where the state jumps to the branch
    x = 2 (x^3 - 3 x = 2).  Newton from the tangent predictor, its move capped
    at 0.1 (dx/dw blows up at the fold); a state more than 0.5 off it is a jump."""

    retry_once = True
    smallest = 1e-4
    limit = 60

    def solve(self, state, goal, small):
        dxdw = 1.0 / (3 * state.x**2 - 3)
        pred = state.x + float(np.clip((goal - state.w) * dxdw, -0.1, 0.1))
        x = pred
        for k in range(1, 200):
            r = x**3 - 3 * x - goal
            if abs(r) < 1e-13:
                return Point(goal, x), k, pred
            x -= r / (3 * x**2 - 3)
            if not math.isfinite(x):
                break
        raise StepFailed("no convergence", 60)

    def continuity(self, state, new, predictor):
        return ("jump" if abs(new.x - predictor) > 0.5 else "continuous"), 0


def _root(w, x0):
    x = x0
    for _ in range(100):
        x -= (x**3 - 3 * x - w) / (3 * x**2 - 3)
    return x


def test_the_jump_at_a_fold_is_found_within_the_smallest_step_and_lands_on_the_other_branch():
    start = Point(-3.0, _root(-3.0, -2.0))
    state, jumps, _, _ = follow(Cubic(), start, 3.0)
    assert len(jumps) == 1
    before, after = jumps[0]
    # the fold is at w = 2: the last state of the lower branch within the smallest
    # step before it, the first of the upper branch within it after
    assert 2.0 - 2e-4 <= before.w < 2.0 < after.w <= before.w + 1e-4 + 1e-15
    assert before.x < -1.0 and after.x == pytest.approx(_root(after.w, 3.0), abs=1e-12)
    assert after.x > 1.9
    assert state.w == 3.0 and state.x == pytest.approx(_root(3.0, 3.0), abs=1e-12)


def test_the_elastic_and_adhesive_drivers_follow_their_paths_through_follow(monkeypatch):
    used = []

    def spy(steps, state, target, step=0):
        used.append(steps)
        return follow(steps, state, target, step)

    monkeypatch.setattr(elastic, "follow", spy)
    ds = solve_asperity(Paraboloid(1.0), LinearElastic(1000.0, 0.3), [0.001, 0.002],
                        accuracy="draft")
    # the adaptive loop solves its driving levels, then both levels on the final mesh
    assert {type(s) for s in used} == {elastic._Levels} and len(used) >= 2
    assert np.all(ds.force.values > 0)
    # the adhesive step: its steps handed to `follow` (jumps at min_step * d, retried once)
    monkeypatch.setattr(adhesive_trace, "follow", lambda steps, s, t, step=0: (steps, t, step))
    state = SimpleNamespace(model=SimpleNamespace(adhesion=SimpleNamespace(d=2e-9)), w=0.0)
    steps, target, step = adhesive_trace._advance(state, 1e-9, {"min_step": 1e-3}, 5)
    assert isinstance(steps, adhesive_trace._Steps) and (target, step) == (1e-9, 5)
    assert steps.smallest == pytest.approx(2e-12, rel=1e-15) and steps.retry_once
    assert steps.limit == adhesive_trace.MAX_HALVINGS and steps.fold is not None
