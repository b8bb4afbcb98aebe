"""Asperity profiles: shape, curvature, intersection radius, validation."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from asperity.fe import CosineHill, Cylinder, Paraboloid, Sphere, TruncatedV


def test_cosine_hill_apex_valley_and_tip_curvature():
    hill = CosineHill(amplitude=2.0, wavenumber=3.0)
    assert hill.surface(0.0) == 0.0
    assert hill.extent == pytest.approx(math.pi / 3)
    assert hill.height == pytest.approx(4.0)  # peak to valley 2C
    assert hill.surface(hill.extent) == pytest.approx(-4.0)
    assert hill.surface(10 * hill.extent) == pytest.approx(-4.0)  # flat block top
    # kappa = C k^2 from the second difference at the apex
    h = 1e-4
    curv = -(hill.surface(h) - 2 * hill.surface(0.0) + hill.surface(-h)) / h**2
    assert curv == pytest.approx(hill.tip_curvature, rel=1e-6)
    assert hill.tip_curvature == pytest.approx(2.0 * 9.0)


@settings(max_examples=40, deadline=None)
@given(ratio=st.floats(1.0, 500.0), height=st.floats(1e-9, 1e3))
def test_cosine_hill_from_aspect_round_trip(ratio, height):
    hill = CosineHill.from_aspect(ratio, height)
    assert hill.width_to_height == pytest.approx(ratio, rel=1e-12)
    assert hill.height == pytest.approx(height, rel=1e-12)
    # width (valley to valley) / height
    assert 2 * hill.extent / hill.height == pytest.approx(ratio, rel=1e-12)
    tip = CosineHill.from_tip(hill.tip_curvature, height)
    assert tip.wavenumber == pytest.approx(hill.wavenumber, rel=1e-12)


@pytest.mark.parametrize("geometry", [
    CosineHill(1.0, 1.0), Sphere(2.0), Paraboloid(2.0), Paraboloid(2.0, shallow=False),
    Cylinder(2.0), TruncatedV(0.1, 1.0),
])
def test_profiles_are_non_increasing_and_start_at_the_apex(geometry):
    r = np.linspace(0, 2 * geometry.extent, 2001)
    z = geometry.surface(r)
    assert z[0] == 0.0
    assert np.all(np.diff(z) <= 1e-15)
    assert np.all(z >= -geometry.height - 1e-12)
    # slope is the derivative of the profile (away from kinks)
    rm = 0.5 * (r[1:] + r[:-1])
    ok = np.all(np.abs(rm[:, None] - np.array(geometry.kinks or [np.inf])[None, :]) > 2e-3 * geometry.extent, axis=1)
    fd = np.diff(z) / np.diff(r)
    np.testing.assert_allclose(fd[ok], geometry.slope(rm[ok]), atol=2e-3 * max(1, np.max(np.abs(fd))))


@pytest.mark.parametrize("geometry", [CosineHill(0.5, 2.0), Sphere(1.0), Paraboloid(1.0)])
def test_intersection_radius_solves_the_profile(geometry):
    w = np.array([1e-6, 1e-3, 0.1]) * geometry.height
    r = geometry.intersection_radius(w)
    np.testing.assert_allclose(geometry.surface(r), -w, rtol=1e-9)
    assert geometry.intersection_radius(0.0) == 0.0


def test_sphere_and_paraboloid_agree_near_the_apex():
    r = np.array([1e-3, 1e-2])
    np.testing.assert_allclose(Sphere(1.0).surface(r), Paraboloid(1.0).surface(r), rtol=1e-4)


def test_shallow_paraboloid_keeps_the_body_flat():
    shallow, body = Paraboloid(1.0), Paraboloid(1.0, shallow=False)
    r = np.linspace(0, 0.4, 5)
    np.testing.assert_array_equal(shallow.body_surface(r), 0.0)
    np.testing.assert_allclose(shallow.gap_offset(r), -0.5 * r**2)
    np.testing.assert_allclose(body.body_surface(r), -0.5 * r**2)
    np.testing.assert_array_equal(body.gap_offset(r), 0.0)


def test_truncated_v_report_grooves():
    v = TruncatedV(top_half_width=0.01, ridge_height=0.125)
    assert not v.axisymmetric
    # 45 deg included angle: flanks at 22.5 deg from the vertical
    assert v.flank_slope == pytest.approx(1 / math.tan(math.radians(22.5)))
    assert v.kinks == (0.01, v.extent)
    assert v.surface(0.005) == 0.0
    # the flat touches the whole top at once
    assert v.intersection_radius(1e-9) == pytest.approx(0.01)


def test_plane_strain_flags():
    assert not Cylinder(1.0).axisymmetric
    assert CosineHill(1.0, 1.0, axisymmetric=False).axisymmetric is False
    assert Sphere(1.0).axisymmetric


@pytest.mark.parametrize("bad", [
    lambda: CosineHill(-1.0, 1.0), lambda: CosineHill(1.0, 0.0), lambda: Sphere(0.0),
    lambda: Sphere(1.0, cap_angle_deg=95), lambda: Paraboloid(float("nan")),
    lambda: TruncatedV(0.1, -1.0), lambda: TruncatedV(0.1, 1.0, included_angle_deg=0),
])
def test_invalid_geometries_are_rejected(bad):
    with pytest.raises(ValueError):
        bad()


def test_interference_beyond_the_hill_is_rejected():
    hill = CosineHill(1.0, 1.0)
    with pytest.raises(ValueError, match="foot of the hill"):
        hill.intersection_radius(2.5)


def test_profiles_are_hashable_and_frozen():
    a, b = CosineHill(1.0, 2.0), CosineHill(1.0, 2.0)
    assert a == b and hash(a) == hash(b)
    with pytest.raises(Exception):
        a.amplitude = 3.0
