"""The one time-marching driver (`asperity.fe.drivers.march`): its loop on a
problem whose answer is known, and every marching driver of the package on it.

The three marching cases of the package (axisymmetric J2, plane-strain
Bodner-Partom, 3-D sliding) reproduce through `march` the steps, iterations,
cuts and results recorded from their own loops before it
(tests/fe/test_nonlinear.py: ``j2``, ``j2_cuts``, ``bodner_partom``,
``bodner_partom_plane_strain``, ``sliding``, ``sliding_cuts``).
"""

import ast
from pathlib import Path

import numpy as np
import pytest

import asperity.fe as fe
from asperity.fe.drivers.march import Accepted, Marching, Trial, march
from asperity.fe.errors import ConvergenceError

FE = Path(fe.__file__).parent


class Decay(Marching):
    """y' = -y from y(0) = 1 by backward Euler on [0, 1] with a knot at 0.3:
    a try longer than ``longest`` is rejected (a cut); the next step is twice
    the last.  ``again_at`` asks once for another try (not a cut) in that step;
    ``redo_at`` solves that step once more; ``stop_at`` ends the run there."""

    def __init__(self, longest=0.25, again_at=None, redo_at=None, stop_at=None, max_cuts=5):
        self.t, self.end, self.max_cuts = 0.0, 1.0, max_cuts
        self.y, self.longest = 1.0, longest
        self.again_at, self.redo_at, self.stop_at = again_at, redo_at, stop_at
        self.steps, self.cut_to, self.begun = [], [], []

    def begin(self, n, dt):
        self.begun.append(n)
        return 0.2, (0.3 if self.t < 0.3 else self.end)

    def attempt(self, n, t_new, cuts):
        h = t_new - self.t
        if n == self.again_at:
            self.again_at = None
            return Trial(t_new, again=True, dt=0.5 * h)
        if h > self.longest:
            return Trial(t_new, f"step {h:g} too long", shrink=0.5)
        return Trial(t_new, data=self.y / (1 + h))

    def failure(self, cuts, trial):
        return cuts.error(trial.t_new, self.t, trial.reason)

    def cut(self, n, dt, trial):
        self.cut_to.append(dt)

    def accept(self, n, trial, cuts):
        h = trial.t_new - self.t
        if n == self.redo_at:
            self.redo_at = None
            return Accepted(h, redo=True)
        self.t, self.y = trial.t_new, trial.data
        self.steps.append((n, self.t, cuts.count))
        return Accepted(2 * h, stop=n == self.stop_at)


def test_steps_end_on_the_knots_and_the_end_and_integrate_backward_euler():
    p = Decay(longest=1.0)
    n = march(p, 0.05, 100)
    times = [t for _, t, _ in p.steps]
    # 0.05, 0.15 (doubled), 0.3 (the knot, not crossed), then the cap of 0.2
    np.testing.assert_allclose(times, [0.05, 0.15, 0.3, 0.5, 0.7, 0.9, 1.0], rtol=0, atol=1e-15)
    assert n == len(times) == 7
    hs = np.diff([0.0, *times])
    assert p.y == pytest.approx(np.prod(1 / (1 + hs)), rel=1e-14)
    assert p.t == 1.0


def test_a_rejected_try_is_a_cut_and_shrinks_the_step():
    p = Decay(longest=0.12)
    march(p, 0.2, 100)
    # the first step tries 0.2 (cap), is cut to 0.1, accepted after one cut
    assert p.steps[0] == (1, pytest.approx(0.1), 1)
    assert p.cut_to[0] == pytest.approx(0.1)
    assert all(t2 - t1 <= 0.12 + 1e-15 for (_, t1, _), (_, t2, _) in zip(
        [(0, 0.0, 0)] + p.steps[:-1], p.steps))
    assert p.t == 1.0


def test_another_try_is_not_a_cut():
    p = Decay(longest=1.0, again_at=2)
    march(p, 0.05, 100)
    n, t, cuts = p.steps[1]
    assert (n, cuts) == (2, 0)
    assert t == pytest.approx(0.05 + 0.05)  # the step tried 0.1, then again with half


def test_a_redone_step_keeps_its_number():
    p = Decay(longest=1.0, redo_at=2)
    march(p, 0.05, 100)
    assert [n for n, _, _ in p.steps] == list(range(1, len(p.steps) + 1))
    assert p.begun[:3] == [1, 2, 2]


def test_the_run_stops_when_told_and_after_max_steps():
    p = Decay(longest=1.0, stop_at=3)
    assert march(p, 0.05, 100) == 3 and p.t == pytest.approx(0.3)
    q = Decay(longest=1.0)
    assert march(q, 0.05, 2) == 2 and len(q.steps) == 2


def test_exhausted_cuts_name_the_step():
    p = Decay(longest=1e-9, max_cuts=3)
    with pytest.raises(ConvergenceError) as err:
        march(p, 0.1, 100)
    # three cuts halve the step (0.1 to 0.0125); the fourth rejection raises
    assert err.value.step == 1 and err.value.cuts == 3
    np.testing.assert_allclose(p.cut_to, [0.05, 0.025, 0.0125], rtol=1e-15)


def test_every_marching_driver_runs_march():
    """The time-marching drivers call `march` and have no step loop of their own:
    they neither cut steps (``StepCuts``) nor place them (``next_time``)."""
    for stem in ("inelastic", "solid3d"):
        tree = ast.parse((FE / "drivers" / f"{stem}.py").read_text())
        names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)} | {
            n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
        assert "march" in names, stem
        assert not names & {"StepCuts", "next_time"}, stem
