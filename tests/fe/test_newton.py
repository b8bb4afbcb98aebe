"""Newton-Raphson with step cutting and the ConvergenceError."""

import numpy as np
import pytest

from asperity.fe import ConvergenceError, CosineHill, LinearElastic, solve_asperity

HILL = CosineHill.from_aspect(10.0, 1.0)
MAT = LinearElastic(1.0, 0.3)
W = [0.01, 0.05, 0.1, 0.2]


def test_convergence_error_names_the_step_and_interference():
    with pytest.raises(ConvergenceError) as info:
        solve_asperity(HILL, MAT, W, accuracy=dict(base="draft", max_iterations=0, max_cuts=3))
    err = info.value
    assert err.step == 0
    assert err.interference == pytest.approx(0.01)
    assert err.cuts == 3
    assert "step 0" in str(err) and "0.01" in str(err)


def test_step_cutting_recovers_and_is_recorded():
    ref = solve_asperity(HILL, MAT, W, accuracy="draft")
    cut = solve_asperity(HILL, MAT, W, accuracy=dict(base="draft", max_iterations=2))
    assert cut.step_cuts.values.sum() > 0
    assert np.all(cut.newton_iterations.values >= ref.newton_iterations.values)
    np.testing.assert_allclose(cut.force.values, ref.force.values, rtol=1e-5)


def test_converged_residual_is_small():
    from asperity.fe.contact.penalty import C1Penalty
    from asperity.fe.drivers.elastic import continuation
    from asperity.fe.solvers.newton import ContactNewton
    from asperity.fe.presets import resolve
    from asperity.fe.drivers.elastic import adapted_model

    model, _ = adapted_model(HILL, MAT, W, resolve("elastic", "draft"))
    law = C1Penalty.for_zone(model.zone, MAT.contact_modulus)
    newton = ContactNewton(model.cond.stiffness, model.zone, 1e-10)
    states = continuation(newton, law, W)
    for s in states:
        R, f, _, _ = newton.residual(law, s.u, s.w)
        assert np.linalg.norm(R) <= 1e-10 * np.linalg.norm(f)
        assert s.force > 0


def test_convergence_error_names_the_callers_step_in_adaptivity():
    # the failing level is the third requested one, reached while adapting
    with pytest.raises(ConvergenceError) as info:
        solve_asperity(HILL, MAT, [0.2, 0.1, 0.01], accuracy=dict(base="draft", max_iterations=0,
                                                                  max_cuts=1))
    assert info.value.step == 2 and info.value.interference == pytest.approx(0.01)
    with pytest.raises(ConvergenceError) as info:
        solve_asperity(HILL, MAT, [0.0, 0.05], adapt="per_level",
                       accuracy=dict(base="draft", max_iterations=0, max_cuts=1))
    assert info.value.step == 1
