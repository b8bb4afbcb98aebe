"""Hertz contact of an elastic sphere with a rigid flat (report 6.1)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from asperity.references.hertz import hertz_asperities, hertz_response

positive = st.floats(min_value=1e-3, max_value=1e3)
poisson = st.floats(min_value=-0.5, max_value=0.5)


def test_report_table_6_5():
    # Fig. 6.5, THEORY: E = 1000, nu = 0.3, R = 1; columns w, r, A, P, p_max as printed
    table = [
        (0.002, 0.04472, 0.006283, 1.3105e-01, 3.1286e01),
        (0.005, 0.07071, 0.015708, 5.1803e-01, 4.9468e01),
        (0.010, 0.10000, 0.031416, 1.4652e00, 6.9958e01),
        (0.020, 0.14142, 0.062832, 4.1442e00, 9.8936e01),
    ]
    w, r, a, p, p0 = map(np.array, zip(*table))
    out = hertz_response(w, 1.0, 1000.0, 0.3)
    # printed to 4-5 significant digits: half a unit of the last printed digit
    np.testing.assert_allclose(out["contact_radius"], r, atol=0.5e-5)
    np.testing.assert_allclose(out["contact_area"], a, atol=0.5e-6)
    np.testing.assert_allclose(out["force"], p, rtol=0.5e-4)
    np.testing.assert_allclose(out["max_pressure"], p0, rtol=0.5e-4)


def test_closed_forms_at_one_point():
    w, R, E, nu = 2e-7, 1.414e-4, 3.155e9, 0.3
    out = hertz_response(w, 1 / R, E, nu)
    es = E / (1 - nu**2)
    assert out["force"] == pytest.approx(4 / 3 * es * math.sqrt(R) * w**1.5, rel=1e-14)
    assert out["contact_radius"] == pytest.approx(math.sqrt(R * w), rel=1e-14)
    assert out["contact_area"] == pytest.approx(math.pi * R * w, rel=1e-14)
    assert out["stiffness"] == pytest.approx(2 * es * math.sqrt(R * w), rel=1e-14)


@settings(max_examples=80, deadline=None)
@given(w=positive, R=positive, E=positive, nu=poisson)
def test_stiffness_is_load_derivative_and_area_is_pi_r2(w, R, E, nu):
    out = hertz_response(w, 1 / R, E, nu)
    dw = 1e-4 * w
    fp = hertz_response(w + dw, 1 / R, E, nu)["force"]
    fm = hertz_response(w - dw, 1 / R, E, nu)["force"]
    # central difference: relative truncation error (dw/w)^2 / 8 ~ 1e-9
    assert (fp - fm) / (2 * dw) == pytest.approx(out["stiffness"], rel=1e-7)
    assert out["contact_area"] == pytest.approx(math.pi * out["contact_radius"] ** 2, rel=1e-13)
    # mean pressure P/A = 2/3 of the maximum
    assert out["force"] / out["contact_area"] == pytest.approx(2 / 3 * out["max_pressure"], rel=1e-13)


@settings(max_examples=80, deadline=None)
@given(w=positive, R=positive, E=positive, nu=poisson, lam=st.floats(1e-3, 1e3))
def test_scale_invariance(w, R, E, nu, lam):
    # scaling lengths by lam: P ~ lam^2, A ~ lam^2, r ~ lam, dP/dw ~ lam, p_max invariant
    a = hertz_response(w, 1 / R, E, nu)
    b = hertz_response(lam * w, 1 / (lam * R), E, nu)
    assert b["force"] == pytest.approx(lam**2 * a["force"], rel=1e-12)
    assert b["contact_area"] == pytest.approx(lam**2 * a["contact_area"], rel=1e-12)
    assert b["contact_radius"] == pytest.approx(lam * a["contact_radius"], rel=1e-12)
    assert b["stiffness"] == pytest.approx(lam * a["stiffness"], rel=1e-12)
    assert b["max_pressure"] == pytest.approx(a["max_pressure"], rel=1e-12)
    # and linear in the modulus
    c = hertz_response(w, 1 / R, lam * E, nu)
    assert c["force"] == pytest.approx(lam * a["force"], rel=1e-12)
    assert c["contact_area"] == pytest.approx(a["contact_area"], rel=1e-12)


def test_no_contact_and_broadcasting():
    w = np.array([-1e-6, 0.0, 1e-6])
    k = np.array([[1e3], [1e4]])
    out = hertz_response(w, k, 2e11, 0.3)
    for v in out.values():
        assert v.shape == (2, 3)
        assert np.all(v[:, :2] == 0.0)
        assert np.all(v[:, 2] > 0.0)
    # a flat (curvature 0) touching: infinite, not nan
    flat = hertz_response(1e-6, 0.0, 2e11, 0.3)
    assert np.isinf(flat["force"]) and np.isinf(flat["contact_area"])
    with pytest.raises(ValueError):
        hertz_response(1e-6, -1.0, 2e11, 0.3)
    with pytest.raises(ValueError):
        hertz_response(1e-6, 1.0, 2e11, 0.6)


def test_hertz_asperities_dataset():
    heights = np.array([-1e-6, 0.0, 2e-6])
    curv = np.array([1e3, 1e4])
    w = np.geomspace(1e-9, 1e-6, 7)
    ds = hertz_asperities(heights, curv, w, 2e11, 0.3)
    assert ds.force.dims == ("height", "curvature", "interference")
    assert ds.force.shape == (3, 2, 7)
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
    assert set(ds.data_vars) >= {"force", "contact_area", "contact_radius", "stiffness"}
    # shift invariant: identical along height, and equal to hertz_response
    np.testing.assert_array_equal(ds.force.values[0], ds.force.values[2])
    ref = hertz_response(w[None, :], curv[:, None], 2e11, 0.3)
    np.testing.assert_allclose(ds.stiffness.values[1], ref["stiffness"], rtol=1e-15)
    with pytest.raises(ValueError):
        hertz_asperities(heights, curv, w[::-1], 2e11, 0.3)
