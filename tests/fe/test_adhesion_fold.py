"""The adhesive path through a fold (`asperity.fe.solvers.arclength`;
`asperity.fe.drivers.adhesive_trace`, "Control and jumps"): where the bisection in w
stalls, the branch is followed by its arc length to the fold and the jump solved from
there.

Checked by forcing it (the bisection allowed 2 halvings instead of MAX_HALVINGS) on a
case the bisection alone passes, against that run. The asperity that needed it, R = 150 um
at d = 0.3 nm (report 7.3, Tabor parameter 10), costs 400 s of CPU at draft, too much for
the suite: it is `make bench CASE=adhesion`'s (benchmarks/adhesion_cost.py --only-large),
against JKR.
"""

import math

import numpy as np
import pytest

from asperity.fe import LennardJones, LinearElastic, Paraboloid, solve_asperity_adhesive
from asperity.fe.drivers import adhesive_model, adhesive_trace
from asperity.fe.solvers import arclength
from asperity.fe.solvers.adhesive import AdhesiveNewton, predictor
from asperity.references.adhesion import jkr_jump_off

D = 0.3e-9


def _landing(ds, which):
    """(before, after) indices of the largest jump of a branch."""
    jump = ds.jump.values.astype(bool) & (ds.branch.values.astype(str) == which)
    k = np.nonzero(jump)[0]
    k = k[np.argmax(np.abs(ds.force.values[k] - ds.force.values[k - 1]))]
    return k - 1, k


#: mu = 5 on a 15 um asperity (as tests/fe/test_adhesion_hard_cases.py)
R, MU = 15e-6, 5.0


def run():
    E_star = math.sqrt(R / D**3) / MU**1.5
    return solve_asperity_adhesive(Paraboloid(R), LinearElastic(E_star * 0.91, 0.3),
                                   LennardJones(1.0, D), w_max=2 * D, accuracy="draft")


@pytest.fixture(scope="module")
def plain():
    """The path by the bisection alone: it finds the jump-in and the jump-off."""
    return run()


def test_forced_fold_path_finds_the_bisections_jumps(monkeypatch, plain):
    """With the bisection cut short, both jumps are passed by the fold path and
    must be the same jumps as the bisection's (draft)."""
    mu = MU
    passes = []
    through = arclength.through_fold

    def counted(*args):
        out = through(*args)
        passes.append(out)
        return out

    monkeypatch.setattr(adhesive_trace, "MAX_HALVINGS", 2)
    monkeypatch.setattr(adhesive_trace, "through_fold", counted)
    forced = run()
    # the fold path took over, and jumped at least twice (in and off)
    assert sum(bool(p[2]) for p in passes) >= 2
    assert forced.attrs["jumps"] == plain.attrs["jumps"] == 2
    # the pull-off is on the branch before the jump-off fold: the same state
    # (measured 5e-13 apart)
    P = plain.attrs["pull_off_force"]
    assert forced.attrs["pull_off_force"] == pytest.approx(P, rel=1e-6)
    # both locate the folds to min_step d = 0.002 d, on a branch whose edge peels
    # node by node in snaps of a few thousandths of d (measured: jump-in 3e-4 d,
    # jump-off 5e-4 d apart)
    for attr in ("jump_in_interference", "jump_off_interference"):
        assert abs(forced.attrs[attr] - plain.attrs[attr]) <= 0.02 * D, attr
    # and land on the same branch: the force after each jump
    for which in ("approach", "retract"):
        _, kp = _landing(plain, which)
        _, kf = _landing(forced, which)
        assert abs(forced.force.values[kf] - plain.force.values[kp]) <= 2e-3 * P, which
    _, kf = _landing(forced, "retract")
    assert forced.contact_radius.values[kf] == 0  # let go
    # the jump-off near JKR's fold (measured -8.17 d, JKR -8.04 d at mu = 5)
    assert forced.attrs["jump_off_interference"] == pytest.approx(jkr_jump_off(mu, D), rel=0.03)



def test_a_jump_off_the_predictor_misses_lands_from_the_approach(monkeypatch, plain):
    """The jump from the jump-off fold solved from the approach's state out of
    contact (`arclength.Landing`) where it fails from the tangent predictor: forced
    by failing the jump solves from the predictor at every fold the fold path finds
    beyond -7 d (JKR's jump-off is at -8.04 d; the approach jumps in at -3 d), with
    the fold path forced as above. It must land where the predictor lands: the same
    jump-off, pull-off and force after the jump as the bisection's path."""
    from asperity.fe.errors import StepFailed

    folds, predicted, guesses = [], [], []
    fold, guess, solve = arclength.FoldPath.fold, arclength.Landing.guess, AdhesiveNewton.solve

    def found(self, state, goal):
        out = fold(self, state, goal)
        if out[1] is not None and out[1] < -7 * D:
            folds.append(out[0])
        return out

    def marked(state, goal):
        out = predictor(state, goal)
        if any(state is f for f in folds):
            predicted.append(out)
        return out

    def landing(self, *args):
        out = guess(self, *args)
        guesses.append(out is not None)
        return out

    def missing(self, w, u0, max_iterations=None):
        if any(u0 is p for p in predicted):
            raise StepFailed("forced: the predictor misses", 1)
        return solve(self, w, u0, max_iterations)

    monkeypatch.setattr(adhesive_trace, "MAX_HALVINGS", 2)
    monkeypatch.setattr(arclength.FoldPath, "fold", found)
    for caller in (arclength, adhesive_model, adhesive_trace):  # every module using the predictor
        monkeypatch.setattr(caller, "predictor", marked)
    monkeypatch.setattr(arclength.Landing, "guess", landing)
    monkeypatch.setattr(AdhesiveNewton, "solve", missing)
    landed = run()
    assert predicted and guesses and all(guesses)  # forced, and the landing had a state
    assert landed.attrs["jumps"] == plain.attrs["jumps"] == 2
    P = plain.attrs["pull_off_force"]
    assert landed.attrs["pull_off_force"] == pytest.approx(P, rel=1e-6)
    assert abs(landed.attrs["jump_off_interference"]
               - plain.attrs["jump_off_interference"]) <= 0.02 * D
    _, kp = _landing(plain, "retract")
    _, kl = _landing(landed, "retract")
    assert abs(landed.force.values[kl] - plain.force.values[kp]) <= 2e-3 * P
    assert landed.contact_radius.values[kl] == 0  # let go


def test_the_landing_guess_is_the_branch_out_of_contact():
    """`Landing.guess` on made-up states (two meshes): u = 0 where the undeformed
    tip is beyond the cut-off, an approach state's own u at its w (interpolated onto
    the nodes asked for), linear in w between two, and None above the last state
    out of contact; states in contact are not used."""
    from types import SimpleNamespace as NS

    law = LennardJones(1.0, D)  # cut-off 16 d: the approach starts at -15 d
    coarse = NS(zone=NS(coords=np.array([[0.0, 1.0, 2.0]]), ndofs=3))
    fine = NS(zone=NS(coords=np.array([[0.0, 0.5, 1.0, 1.5, 2.0]]), ndofs=5))
    a = NS(w=-10 * D, u=np.array([2.0, 1.0, 0.0]), contact_force=0.0, model=coarse)
    b = NS(w=-6 * D, u=np.array([4.0, 3.0, 2.0, 1.0, 0.0]), contact_force=0.0, model=fine)
    touching = NS(w=-2 * D, u=np.zeros(5), contact_force=1e-6, model=fine)
    land = arclength.Landing([b, touching, a], law)
    np.testing.assert_array_equal(land.guess(-20 * D, fine), np.zeros(5))
    np.testing.assert_array_equal(land.guess(-15 * D, fine), np.zeros(5))
    np.testing.assert_allclose(land.guess(-10 * D, fine), [2.0, 1.5, 1.0, 0.5, 0.0], rtol=1e-15)
    np.testing.assert_allclose(land.guess(-8 * D, fine), [3.0, 2.25, 1.5, 0.75, 0.0], rtol=1e-14)
    np.testing.assert_allclose(land.guess(-12.5 * D, coarse), [1.0, 0.5, 0.0], rtol=1e-13)
    assert land.guess(-5 * D, fine) is None  # above the last state out of contact
