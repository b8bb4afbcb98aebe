"""An axisymmetric body of any profile on a rigid flat (asperity.references.sneddon), the
profiles of a map's summits (asperity.surface.summits.summit_profiles), and Hertz's
elliptic contact (asperity.references.hertz.elliptic_hertz): against closed forms and
the boundary elements."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.references.boundary_element import solve_map
from asperity.references.hertz import elliptic_hertz, hertz_response
from asperity.references.sneddon import profile_law, profile_tables
from asperity.surface.summits import summit_profiles

E_STAR = 1e11


def test_a_paraboloid_is_hertz_and_a_cone_is_sneddons_cone():
    """f' = r / R: w = a^2 / R, F = 4 E* a^3 / (3 R); f' = tan(alpha): w = (pi/2) a tan(alpha),
    F = (pi/2) E* a^2 tan(alpha) (Johnson 5.6); f' linear on the grid, so to quadrature
    round-off (1e-12)."""
    radii = np.linspace(0.0, 2e-6, 201)
    R, slope = 1e-5, 0.1
    w, force, a = profile_tables(radii, np.vstack([radii / R, np.full_like(radii, slope)]), E_STAR)
    np.testing.assert_allclose(w[0], a**2 / R, rtol=1e-12, atol=1e-30)
    np.testing.assert_allclose(force[0], 4 * E_STAR * a**3 / (3 * R), rtol=1e-12, atol=1e-30)
    np.testing.assert_allclose(w[1], np.pi / 2 * a * slope, rtol=1e-12, atol=1e-30)
    np.testing.assert_allclose(force[1], np.pi / 2 * E_STAR * a**2 * slope, rtol=1e-12, atol=1e-30)


def test_the_law_is_hertz_for_a_paraboloid_and_smooth_where_it_starts():
    """The law of a tabulated paraboloid against Hertz (to the table's resolution, 2e-3
    at 200 radii: a(w) is linear between radii where it goes as w^1/2), its dF/dw against its own central differences (1e-6), a force that
    starts as w^3/2 (no kink at w = 0), and a flat punch past the table."""
    radii = np.linspace(0.0, 2e-6, 201)
    R = 1e-5
    law = profile_law(radii, (radii / R)[None, :], E_STAR)
    w = np.array([5e-12, 3e-10, 4e-11 * 37, 1.1e-7, 2.5e-7, 3.9e-7])
    index = np.zeros(w.size, dtype=int)
    force, area, dforce, darea = law(w, index)
    hertz = hertz_response(w, 1 / R, E_STAR, 0.0)
    np.testing.assert_allclose(force[w > 4e-10], hertz["force"][w > 4e-10], rtol=2e-3)
    np.testing.assert_allclose(area[w > 4e-10], hertz["contact_area"][w > 4e-10], rtol=2e-3)
    step = 1e-4 * w
    numeric = (law(w + step, index)[0] - law(w - step, index)[0]) / (2 * step)
    np.testing.assert_allclose(dforce, numeric, rtol=1e-6)
    # within the first radius dF/dw goes as w^1/2, to 0 at w = 0
    assert law(np.array([1e-14]), np.array([0]))[2][0] == pytest.approx(dforce[0] * (1e-14 / 5e-12) ** 0.5,
                                                                     rel=1e-9)
    # past the table (a = 2 um at w = a^2 / R = 4e-7): dF/dw = 2 E* a_max
    beyond = law(np.array([5e-7, 6e-7]), np.array([0, 0]))
    assert beyond[0][1] - beyond[0][0] == pytest.approx(2 * E_STAR * 2e-6 * 1e-7, rel=1e-9)


def _bump(shape: str):
    n, dx, height = 128, 1e-6, 0.5e-6
    y, x = np.mgrid[0:n, 0:n] * dx
    c = 64.3 * dx
    s = 6 * dx
    if shape == "round":
        return height * np.exp(-((x - c) ** 2 + (y - c) ** 2) / (2 * s * s)), dx, height, s
    return height * np.exp(-(x - c) ** 2 / (2 * (2 * s) ** 2) - (y - c) ** 2 / (2 * (s / 2) ** 2)), dx, height, s


def test_a_gaussian_bump_by_its_own_profile_against_the_boundary_elements():
    """A Gaussian bump exp(-r^2 / 2 s^2), pressed to half and 0.8 of its height: the profile
    from its map (bearing area of its basin) through Sneddon within 5 % of the boundary
    elements (free boundary, a radius of 10-20 grid steps); Hertz at its tip curvature is
    10 % off at 0.8, where the bump is wider than its paraboloid."""
    z, dx, height, s = _bump("round")
    i, j = np.unravel_index(np.argmax(z), z.shape)
    kappa = height / s**2
    radii, slopes = summit_profiles(z, dx, dx, [i], [j], [kappa])
    law = profile_law(radii, slopes, E_STAR)
    for fraction, hertz_off in ((0.5, False), (0.8, True)):
        w = fraction * height
        bem = solve_map(z, dx, dx, [z.max() - w - z.mean()], E_STAR, boundary="free")
        exact = float(bem["nominal_pressure"][0]) * z.size * dx * dx
        assert law(np.array([w]), np.array([0]))[0][0] == pytest.approx(exact, rel=0.05)
        hertz = hertz_response(w, kappa, E_STAR, 0.0)["force"]
        assert (abs(hertz / exact - 1) > 0.08) == hertz_off


def test_elliptic_hertz_is_circular_hertz_for_equal_curvatures_and_satisfies_its_conditions():
    """Equal curvatures: Hertz (1e-12). Unequal: the pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2)
    displaces the surface by L - M x^2 - N y^2 (Johnson 4.35-4.37), which must equal
    w - A x^2 - B y^2: checked with the complete elliptic integrals (1e-10)."""
    from scipy.special import ellipe, ellipk

    w = np.array([1e-8, 5e-8, 2e-7])
    circle = elliptic_hertz(w, 2e4, 2e4, E_STAR)
    hertz = hertz_response(w, 2e4, E_STAR, 0.0)
    for key in ("force", "contact_area", "stiffness"):
        np.testing.assert_allclose(circle[key], hertz[key], rtol=1e-12)
    k_small, k_large = 1e4, 6e4
    out = elliptic_hertz(w, k_large, k_small, E_STAR)
    a, b = out["semi_axis_a"], out["semi_axis_b"]
    m = 1 - (b / a) ** 2
    K, E = ellipk(m), ellipe(m)
    p0 = 3 * out["force"] / (2 * np.pi * a * b)
    np.testing.assert_allclose(p0 * b * K / E_STAR, w, rtol=1e-10)  # L = w
    np.testing.assert_allclose(p0 * b / (E_STAR * m * a * a) * (K - E), k_small / 2, rtol=1e-10)  # M = A
    np.testing.assert_allclose(p0 * b / (E_STAR * m * a * a) * (E / (1 - m) - K), k_large / 2,
                               rtol=1e-10)  # N = B


def test_elliptic_hertz_against_the_boundary_elements():
    """An elliptic paraboloid with curvatures 1 : 4 on a grid that resolves its contact
    ellipse (semi-axes about 20 and 8 steps): the force within 1.5 % (the grid's own error,
    0.15 (dx/b)^2, and the counted area within 5 %)."""
    n, dx = 160, 1e-7
    y, x = (np.mgrid[0:n, 0:n] - 80.3) * dx
    k1, k2 = 2.5e4, 1e5
    z = -(k1 * x**2 + k2 * y**2) / 2
    w = 2e-8
    out = elliptic_hertz(np.array([w]), k1, k2, E_STAR)
    bem = solve_map(z, dx, dx, [z.max() - w - z.mean()], E_STAR, boundary="free", tolerance=1e-9)
    force = float(bem["nominal_pressure"][0]) * z.size * dx * dx
    area = float(bem["contact_area_ratio"][0]) * z.size * dx * dx
    assert out["force"][0] == pytest.approx(force, rel=0.015)
    assert out["contact_area"][0] == pytest.approx(area, rel=0.05)
