"""Hard cases: very flat and steep hills, scale, a very stiff penalty."""

import numpy as np
import pytest

from asperity.fe import ConvergenceError, CosineHill, LinearElastic, hertz, solve_asperity
from asperity.fe.contact.penalty import PENALTY_FACTOR

MAT = LinearElastic(1.0, 0.3)


def _curve(ratio, n=40, accuracy="standard", height=1.0, material=MAT):
    hill = CosineHill.from_aspect(ratio, height)
    w = np.linspace(0.3 / n, 0.3, n) * hill.height  # up to 30 % of the height
    return hill, solve_asperity(hill, material, w, accuracy=accuracy)


@pytest.mark.parametrize("ratio", [100.0, 2.0], ids=["flat", "steep"])
def test_flat_and_steep_hills_to_30_percent_of_height(ratio):
    hill, ds = _curve(ratio)
    F, a = ds.force.values, ds.contact_radius.values
    w = ds.interference.values
    assert np.all(np.isfinite(F)) and np.all(np.isfinite(a))
    assert np.all(np.diff(F) > 0) and np.all(np.diff(a) > 0)
    assert np.all(ds.normal_stiffness.values > 0)
    # the elastic surface sinks: contact inside the geometric intersection
    assert np.all(a < hill.intersection_radius(w))
    assert np.all(ds.estimated_error.values < 0.01)
    assert ds.step_cuts.values.sum() == 0
    # first touch behaves as Hertz with the tip radius 1 / (C k^2)
    ref = hertz(1 / hill.tip_curvature, MAT, w[0])
    tol = 0.01 if ratio > 10 else 0.08  # steep hill: a / R is not small
    assert F[0] / ref["force"] == pytest.approx(1.0, abs=tol)
    # stiffness from the tangent agrees with the force curve
    fd = np.gradient(F, w)[2:-2]
    np.testing.assert_allclose(ds.normal_stiffness.values[2:-2], fd, rtol=0.05)


def test_flat_hill_has_small_strains_steep_hill_large():
    _, flat = _curve(100.0, n=6, accuracy="draft")
    _, steep = _curve(2.0, n=6, accuracy="draft")
    assert flat.max_equivalent_strain.max() < 0.02
    assert steep.max_equivalent_strain.max() > 0.1


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [100.0, 2.0], ids=["flat", "steep"])
def test_standard_agrees_with_fine(ratio):
    _, std = _curve(ratio, n=8)
    _, fine = _curve(ratio, n=8, accuracy="fine")
    np.testing.assert_allclose(std.force.values, fine.force.values, rtol=0.005)
    np.testing.assert_allclose(std.contact_radius.values, fine.contact_radius.values, rtol=0.02)


def test_same_dimensionless_answer_at_nanometre_and_millimetre_scale():
    out = []
    for height, E in [(1e-9, 200e9), (1e-3, 200e9), (1e-3, 3e6)]:
        hill = CosineHill.from_aspect(13.4, height)
        w = np.array([0.02, 0.1, 0.3]) * height
        ds = solve_asperity(hill, LinearElastic(E, 0.3), w, accuracy="draft")
        out.append((ds.force.values / (E * height**2), ds.contact_radius.values / height,
                    ds.normal_stiffness.values / (E * height), ds.max_equivalent_strain.values))
    for other in out[1:]:
        for x, y in zip(out[0], other):
            np.testing.assert_allclose(x, y, rtol=1e-6)


def test_very_stiff_penalty_converges_or_names_the_step():
    hill = CosineHill.from_aspect(13.4, 1.0)
    w = [0.01, 0.05, 0.1, 0.2]
    base = solve_asperity(hill, MAT, w, accuracy="draft")
    try:
        stiff = solve_asperity(hill, MAT, w, accuracy="draft", penalty_factor=1e4 * PENALTY_FACTOR)
    except ConvergenceError as err:  # allowed, but it must say where
        assert 0 <= err.step < len(w) and err.interference in w
        return
    for name in ("force", "contact_radius", "normal_stiffness"):
        assert np.all(np.isfinite(stiff[name].values))
    # the penalty error of the default is small: same answer within 1e-3
    np.testing.assert_allclose(stiff.force.values, base.force.values, rtol=1e-3)
    np.testing.assert_allclose(stiff.contact_radius.values, base.contact_radius.values, rtol=5e-3)


def test_plane_strain_ridge_runs():
    ridge = CosineHill.from_aspect(13.4, 1.0, axisymmetric=False)
    ds = solve_asperity(ridge, MAT, [0.01, 0.1, 0.3], accuracy="draft")
    assert np.all(np.diff(ds.force.values) > 0)
    assert ds.force.attrs["units"] == "N/m"
