"""Interacting, coalescing asperities through the periodic elastic half-space."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, fsolve
from scipy.special import zeta

from asperity.homogenize.asperity_laws import hertz_law
from asperity.homogenize.interacting import (InteractingAsperities, PeriodicKernel, _phi, hertz_displacement,
                                             interacting_interface, merge_spots)
from asperity.surface.maps import map_peaks
from asperity.surface.synthetic import gaussian_map

E_STAR = 70e9 / (1 - 0.33**2)
# 4 zeta(1/2) beta(1/2): the zero-mean lattice sum of 1/r on the unit square lattice (Epstein zeta,
# Glasser and Zucker 1980); beta(1/2) = 2/sqrt(pi) int_0^inf exp(-u^2)/(1 + exp(-2u^2)) du
BETA_HALF = 2 / math.sqrt(math.pi) * quad(lambda u: math.exp(-u * u) / (1 + math.exp(-2 * u * u)),
                                          0, 12, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
LATTICE = 4 * zeta(0.5) * BETA_HALF  # -3.9002649200...


def hertz(w, R):
    w = np.maximum(w, 0.0)
    return 4 / 3 * E_STAR * np.sqrt(R) * w**1.5, np.pi * R * w


def johnson(r, a, inside="hertz"):
    """Displacement per unit force of a Hertz pressure of radius a (Johnson 3.41a, b), directly."""
    if r >= a:
        return 3 * ((2 * a * a - r * r) * math.asin(a / r) + a * math.sqrt(r * r - a * a)) \
            / (4 * math.pi * a**3 * E_STAR)
    if inside == "hertz":
        return 3 * (2 * a * a - r * r) / (8 * a**3 * E_STAR)
    return 3 / (8 * a * E_STAR)


# --- the periodic kernel -------------------------------------------------------------------------

@pytest.mark.parametrize("period", [1.0, 2.5e-4])
def test_kernel_self_term_is_the_lattice_sum(period):
    # pi E* L c(0) = 4 zeta(1/2) beta(1/2) for a square cell; Ewald table vs closed form, 1e-9
    k = PeriodicKernel(period, E_STAR)
    assert math.pi * E_STAR * period * k.correction(0.0, 0.0) == pytest.approx(LATTICE, rel=1e-9)
    assert LATTICE == pytest.approx(-3.9002649200, rel=1e-9)


@pytest.mark.parametrize("period", [(1.0, 1.0), (2.0, 1.0)])
def test_kernel_has_zero_mean_and_boussinesq_near_field(period):
    lx, ly = period
    k = PeriodicKernel(period, E_STAR)
    # mean over the cell: c by Gauss-Legendre on the quadrant (smooth), 1/(pi E* r) in closed form,
    # int over [-a, a] x [-b, b] of 1/r = 4 (a asinh(b/a) + b asinh(a/b))
    xg, wg = np.polynomial.legendre.leggauss(60)
    xs, wx = lx / 4 * (xg + 1), lx / 4 * wg
    ys, wy = ly / 4 * (xg + 1), ly / 4 * wg
    X, Y = np.meshgrid(xs, ys)
    total = 4 * np.sum(wy[:, None] * wx[None, :] * k.correction(X, Y))
    a, b = lx / 2, ly / 2
    total += 4 * (a * math.asinh(b / a) + b * math.asinh(a / b)) / (math.pi * E_STAR)
    scale = 1 / (math.pi * E_STAR * min(lx, ly))  # the kernel at r = L
    assert abs(total / (lx * ly)) < 1e-6 * scale
    # r << L: G_per pi E* r = 1 + pi E* c(0) r + O(r^3), |pi E* L c(0)| < 4
    for r in (1e-4, 1e-3, 1e-2):
        g = k(r * min(lx, ly) / math.sqrt(2), r * min(lx, ly) / math.sqrt(2)) * math.pi * E_STAR * r * min(lx, ly)
        assert abs(g - 1) < 4 * r


def test_kernel_against_contactmechanics_grid():
    # ContactMechanics' periodic FFT half-space (q = 0 stiffness zero), unit force on one pixel of a
    # 256^2 grid: its band-limited pixel kernel tends to G_per as (dx/r)^2 (measured 0.038 at 32 px,
    # 0.011 at 64 px in units of 1/(pi E* L)); bounds 0.05 and 0.015
    from ContactMechanics import PeriodicFFTElasticHalfSpace

    n, L = 256, 1e-3
    hs = PeriodicFFTElasticHalfSpace((n, n), E_STAR, (L, L), stiffness_q0=0.0, fft="serial")
    f = np.zeros((n, n))
    f[0, 0] = 1.0
    u = -hs.evaluate_disp(f)  # ContactMechanics: displacement positive away from the body
    assert abs(u.mean()) < 1e-12 * abs(u).max()
    k = PeriodicKernel(L, E_STAR)
    X, Y = np.meshgrid(np.arange(n) * L / n, np.arange(n) * L / n, indexing="ij")
    G = k(X, Y)
    r = np.hypot(*k.minimum_image(X, Y)) / (L / n)
    err = np.abs(u - G) * math.pi * E_STAR * L
    assert err[r >= 32].max() < 0.05
    assert err[r >= 64].max() < 0.015


def test_hertz_field_branches():
    a = 2e-6
    # series (a/r < 0.1) and closed form meet; inside and outside meet at r = a
    for r in (a / 0.1 * (1 - 1e-12), a / 0.1 * (1 + 1e-12)):
        assert hertz_displacement(r, a, E_STAR)[0] == pytest.approx(johnson(a / 0.1, a), rel=1e-12)
    for r in (0.3 * a, a, 1.7 * a, 30 * a):
        assert hertz_displacement(r, a, E_STAR)[0] == pytest.approx(johnson(r, a), rel=1e-13)
    # derivative in a against a central difference (step 1e-5 a: truncation ~1e-10), of Johnson's
    # closed form where it does not cancel, of the series far out (a/r = 0.02)
    for r in (0.5 * a, 2 * a, 4 * a):
        da = 1e-5 * a
        fd = (johnson(r, a + da) - johnson(r, a - da)) / (2 * da)
        assert hertz_displacement(r, a, E_STAR)[1] == pytest.approx(fd, rel=1e-6)
    r, da = 50 * a, 1e-4 * a
    fd = (hertz_displacement(r, a + da, E_STAR)[0] - hertz_displacement(r, a - da, E_STAR)[0]) / (2 * da)
    assert hertz_displacement(r, a, E_STAR)[1] == pytest.approx(fd, rel=1e-6)
    # the edge-held inside branch: phi = pi E* r g = 3 pi/8 (r/a), continuous at r = a
    x = np.array([1.0, 2.0, 5.0])
    np.testing.assert_allclose(_phi(x, "edge")[0], 3 * np.pi / 8 / x, rtol=1e-14)


# --- one and two asperities ----------------------------------------------------------------------

def test_single_asperity_is_hertz():
    R, z = 1e-4, 1e-6
    h = np.array([-1e-6, 0.0, 0.5e-6, 2e-6])
    L = 1e6  # a / L ~ 1e-11: the self term c(0) F is below 1e-9 of w
    ds = interacting_interface([0.0], [0.0], [z], [1 / R], h, E_STAR, L)
    F, A = hertz(z - h, R)
    np.testing.assert_allclose(ds.nominal_pressure * L * L, F, rtol=1e-9, atol=0)
    np.testing.assert_allclose(ds.contact_area_ratio * L * L, A, rtol=1e-9, atol=0)
    stiff = 2 * E_STAR * np.sqrt(R * np.maximum(z - h, 0))
    np.testing.assert_allclose(ds.normal_stiffness * L * L, stiff, rtol=1e-9, atol=0)
    np.testing.assert_array_equal(ds.mean_gap, h)


def test_single_asperity_with_self_term():
    # moderate period: w + c(0) F(w) = z - h with pi E* L c(0) = LATTICE (closed form), by brentq
    R, z, h, L = 1e-4, 1e-6, 0.0, 1e-4
    c0 = LATTICE / (math.pi * E_STAR * L)
    w = brentq(lambda w: w + c0 * hertz(w, R)[0] - (z - h), 0.0, 10 * (z - h), xtol=1e-22, rtol=1e-15)
    assert w > (z - h) * (1 + 1e-3)  # the mean plane held: the asperity is pressed further in
    ds = interacting_interface([3e-5], [7e-5], [z], [1 / R], [h], E_STAR, L)
    assert float(ds.nominal_pressure[0]) * L * L == pytest.approx(hertz(w, R)[0], rel=1e-9)
    assert float(ds.contact_area_ratio[0]) * L * L == pytest.approx(hertz(w, R)[1], rel=1e-9)


@pytest.mark.parametrize("near_field", ["hertz", "edge"])
@pytest.mark.parametrize("d, R1, R2, z1, z2", [
    (5e-5, 1e-4, 2e-4, 1.2e-6, 0.9e-6),   # a/r ~ 0.2-0.3: closed form
    (3e-4, 1e-4, 1e-4, 1.0e-6, 1.1e-6),   # a/r < 0.1: series
    (1.2e-5, 1e-3, 1e-5, 1.0e-6, 1.0e-6),  # summit 2 inside spot 1 (a1 ~ 3e-5 > d > a2)
])
def test_two_asperities_against_fsolve(d, R1, R2, z1, z2, near_field):
    # the two scalar equations w_i = z_i - h - c0 F_i - (g(d, a_j) + c0) F_j solved by fsolve, with
    # Johnson's field written out; L = 1e4 d makes c(d) = c(0) up to (d/L)^2 (~1e-8 of c(0) F)
    h, L = 0.0, 1e4 * d
    c0 = LATTICE / (math.pi * E_STAR * L)

    def equations(w):
        (F1, A1), (F2, A2) = hertz(w[0], R1), hertz(w[1], R2)
        a1, a2 = math.sqrt(A1 / math.pi), math.sqrt(A2 / math.pi)
        u1 = c0 * F1 + (johnson(d, a2, near_field) + c0) * F2
        u2 = c0 * F2 + (johnson(d, a1, near_field) + c0) * F1
        return [(w[0] - z1 + h + u1) / z1, (w[1] - z2 + h + u2) / z1]

    w = fsolve(equations, [z1 - h, z2 - h], xtol=1e-13)
    assert max(abs(v) for v in equations(w)) < 1e-13
    model = InteractingAsperities([0.0, d], [0.0, 0.0], [z1, z2], [1 / R1, 1 / R2], E_STAR, L,
                                  near_field=near_field)
    state = model.solve(h)
    F = [hertz(w[0], R1)[0], hertz(w[1], R2)[0]]
    np.testing.assert_allclose(state.interference, w, rtol=1e-8)
    np.testing.assert_allclose(state.force, F, rtol=1e-8)


# --- coalescence ---------------------------------------------------------------------------------

def test_merge_spots_is_transitive_and_periodic():
    L = 10.0
    # chain 0-1-2 overlapping pairwise (0 and 2 do not), 3 alone, 4 across the edge from 0
    x = np.array([1.0, 2.5, 4.0, 7.0, 9.5])
    y = np.array([5.0, 5.0, 5.0, 5.0, 5.0])
    a = np.array([0.8, 0.8, 0.8, 0.5, 0.8])
    labels = merge_spots(x, y, a, L)
    assert labels[0] == labels[1] == labels[2] == labels[4]
    assert labels[3] != labels[0]
    assert len(set(labels)) == 2


def test_two_spots_merge_when_they_overlap():
    # two equal peaks 20 um apart: a = (R w)^1/2 = 10 um at w = 1 um; separate at h = 0.5 um
    # (a ~ 7 um), merged at h = -0.8 um (a ~ 12 um)
    R, d, L = 1e-4, 2e-5, 1e-3
    h = np.array([-0.8e-6, 0.5e-6])
    ds = interacting_interface([0.0, d], [0.0, 0.0], [1e-6, 1e-6], [1 / R, 1 / R], h, E_STAR, L)
    model = InteractingAsperities([0.0, d], [0.0, 0.0], [1e-6, 1e-6], [1 / R, 1 / R], E_STAR, L)
    merged, apart = model.solve(h[0]), model.solve(h[1])
    assert 2 * np.sqrt(merged.area[0] / np.pi) > d > 2 * np.sqrt(apart.area[0] / np.pi)
    np.testing.assert_allclose(ds.contact_count * L * L, [1, 2], rtol=1e-12)
    np.testing.assert_allclose(ds.asperities_in_contact * L * L, [2, 2], rtol=1e-12)
    np.testing.assert_array_equal(ds.merged_load_fraction, [1.0, 0.0])
    # the merged spot keeps the sum of the two areas and forces
    assert float(ds.contact_area_ratio[0]) * L * L == pytest.approx(merged.area.sum(), rel=1e-12)
    assert float(ds.nominal_pressure[0]) * L * L == pytest.approx(merged.force.sum(), rel=1e-12)
    assert np.ptp(merged.force) < 1e-12 * merged.force.max()  # symmetric pair


# --- many peaks ----------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def peaks():
    dx, n, sigma = 1.25e-6, 256, 1e-6
    z = gaussian_map(n, dx, sigma, 6e-6, seed=3)
    pk = map_peaks(z, dx, dx)
    return pk, n * dx, sigma


def test_many_peaks_finite_monotone_and_converged(peaks):
    pk, L, sigma = peaks
    assert pk.sizes["peak"] > 100
    h = np.linspace(0.5, 3.0, 6) * sigma
    ds = interacting_interface(pk.x, pk.y, pk.height, pk.curvature, h, E_STAR, L)
    for name in ("nominal_pressure", "contact_area_ratio", "normal_stiffness", "contact_count"):
        assert np.all(np.isfinite(ds[name]))
    assert np.all(np.diff(ds.nominal_pressure) < 0)
    assert np.all(np.diff(ds.contact_area_ratio) < 0)
    assert np.all(ds.contact_count <= ds.asperities_in_contact)
    model = InteractingAsperities(pk.x, pk.y, pk.height, pk.curvature, E_STAR, L)
    w = None
    for hk in h[::-1]:
        state = model.solve(hk, w, tolerance=1e-10)
        w = state.interference
        residual = model.evaluate(w, hk, jacobian=False)  # all asperities, in contact or not
        assert np.abs(residual).max() <= 1e-10 * (pk.height.max().item() - hk)
        assert np.all(state.force[w <= 0] == 0)
    for var in list(ds.data_vars) + ["separation"]:
        assert {"units", "long_name"} <= set(ds[var].attrs)


def test_stiffness_is_the_derivative_of_pressure(peaks):
    pk, L, sigma = peaks
    model = InteractingAsperities(pk.x, pk.y, pk.height, pk.curvature, E_STAR, L)
    for h in (0.8 * sigma, 1.7 * sigma):
        state = model.solve(h, tolerance=1e-13)
        dh = 1e-4 * sigma
        # central difference: truncation (dh/w)^2 ~ 1e-8 of the smallest contacting w ~ 0.01 sigma
        pp = model.solve(h + dh, state.interference, tolerance=1e-13).force.sum() / L**2
        pm = model.solve(h - dh, state.interference, tolerance=1e-13).force.sum() / L**2
        assert state.stiffness == pytest.approx(-(pp - pm) / (2 * dh), rel=1e-4)


def test_law_without_area_derivative(peaks):
    # a law returning (F, A, dF/dw) only: dA/dw by a central difference of the law; the solution is
    # the same (1e-9) and so is the stiffness (1e-6)
    pk, L, sigma = peaks
    law4 = hertz_law(E_STAR, pk.curvature)

    def law3(w, index):
        return law4(w, index)[:3]

    h = [sigma, 2 * sigma]
    a = interacting_interface(pk.x, pk.y, pk.height, pk.curvature, h, E_STAR, L)
    b = interacting_interface(pk.x, pk.y, pk.height, pk.curvature, h, E_STAR, L, law=law3)
    np.testing.assert_allclose(b.nominal_pressure, a.nominal_pressure, rtol=1e-9)
    np.testing.assert_allclose(b.normal_stiffness, a.normal_stiffness, rtol=1e-6)


def test_a_tabulated_law_of_hertz_asperities_is_hertz(peaks):
    """Hertz responses tabulated on an interference grid (as finite element asperities come):
    the law is Hertz at the grid's points (1e-12), between them within the linear
    interpolation's error (1e-2 on this grid), its slopes those of its own segments (1e-6),
    and the coupled interface within 1 % of Hertz's law."""
    from asperity.homogenize.asperity_laws import tabulated_law

    pk, L, sigma = peaks
    grid = np.concatenate([[0.0], np.geomspace(1e-4, 5.0, 240) * sigma])
    exact = hertz_law(E_STAR, pk.curvature)
    index = np.arange(pk.curvature.size)
    force, area = (np.array([exact(np.full(index.size, w), index)[i] for w in grid]).T for i in (0, 1))
    law = tabulated_law(grid, force, area)
    at_nodes = law(np.full(index.size, grid[100]), index)
    np.testing.assert_allclose(at_nodes[0], force[:, 100], rtol=1e-12)
    w = np.full(index.size, 0.7 * sigma)
    np.testing.assert_allclose(law(w, index)[0], exact(w, index)[0], rtol=1e-2)
    step = 1e-7 * sigma
    numeric = (law(w + step, index)[0] - law(w - step, index)[0]) / (2 * step)
    np.testing.assert_allclose(law(w, index)[2], numeric, rtol=1e-6)
    h = [sigma, 2 * sigma]
    a = interacting_interface(pk.x, pk.y, pk.height, pk.curvature, h, E_STAR, L)
    b = interacting_interface(pk.x, pk.y, pk.height, pk.curvature, h, E_STAR, L, law=law, accept=1e-2)
    np.testing.assert_allclose(b.nominal_pressure, a.nominal_pressure, rtol=1e-2)


def test_a_shape_with_a_spheres_departure_from_hertz(peaks):
    """`departure_law`: a model equal to its sphere leaves the base law as it is (1e-12); a
    sphere whose model carries half of Hertz's force and twice its area halves the base's
    force and doubles its area; the slopes are the derivatives of the forces and areas
    (central differences, 1e-6); past the reach the two ratios keep their values there."""
    from asperity.homogenize.asperity_laws import departure_law

    pk, _, sigma = peaks
    index = np.arange(pk.curvature.size)
    base = hertz_law(E_STAR, 0.5 * pk.curvature)  # a blunter summit than its tip sphere
    sphere = hertz_law(E_STAR, pk.curvature)
    reach = np.full(index.size, 2.0 * sigma)
    w = np.full(index.size, 0.7 * sigma)
    same = departure_law(base, sphere, sphere, reach)(w, index)
    for got, want in zip(same, base(w, index)):
        np.testing.assert_allclose(got, want, rtol=1e-12)

    def model(w, index):  # a softer sphere whose force falls from Hertz's as w grows
        f, a, df, da = sphere(w, index)
        s = 1.0 / (1.0 + w / sigma)
        return f * s, a * (2.0 - s), df * s - f * s * s / sigma, da * (2.0 - s) + a * s * s / sigma

    law = departure_law(base, model, sphere, reach)
    f, a, df, da = law(w, index)
    fb, ab = base(w, index)[:2]
    s = 1.0 / 1.7
    np.testing.assert_allclose(f, fb * s, rtol=1e-12)
    np.testing.assert_allclose(a, ab * (2.0 - s), rtol=1e-12)
    step = 1e-7 * sigma
    for value, slope in ((0, df), (1, da)):
        numeric = (law(w + step, index)[value] - law(w - step, index)[value]) / (2 * step)
        np.testing.assert_allclose(slope, numeric, rtol=1e-6)
    far = np.full(index.size, 3.0 * sigma)
    held = 1.0 / 3.0  # the force ratio at the reach, 2 sigma
    np.testing.assert_allclose(law(far, index)[0], base(far, index)[0] * held, rtol=1e-12)
    np.testing.assert_allclose(law(far, index)[2], base(far, index)[2] * held, rtol=1e-12)


def test_a_separation_newton_cannot_reach_is_approached_in_half_steps(peaks):
    """Where Newton from the last state does not converge (it can cycle between contact
    sets at the kinks of the semismooth equations: the elliptic law on an anisotropic
    map, scene anisotropic_reference), the flat approaches in halved steps of
    separation; the state reached is the equilibrium a converging solve gives, to the
    tolerance.  Here Newton is made to refuse any step longer than 0.2 sigma."""
    from asperity.homogenize.interacting import _approach

    pk, L, sigma = peaks
    model = InteractingAsperities(pk.x, pk.y, pk.height, pk.curvature, E_STAR, L)
    top = float(pk.height.max())
    tried = []

    class Short(InteractingAsperities):
        def solve(self, separation, start=None, **kw):
            reached = top if start is None else self._reached
            tried.append(separation)
            if reached - separation > 0.2 * sigma:
                raise RuntimeError("too long a step")
            state = super().solve(separation, start, **kw)
            self._reached = separation
            return state

    short = Short(pk.x, pk.y, pk.height, pk.curvature, E_STAR, L)
    solve = dict(tolerance=1e-10, max_iterations=100, accept=None)
    h = 1.2 * sigma
    state = _approach(short, top, None, h, solve)
    direct = model.solve(h, tolerance=1e-10)
    scale = top - h
    np.testing.assert_allclose(state.interference, direct.interference, rtol=0, atol=1e-9 * scale)
    assert state.force.sum() == pytest.approx(direct.force.sum(), rel=1e-8)
    assert state.residual <= 1e-10 * scale
    # halved down to steps of at most 0.2 sigma, the iterations of every half step counted
    assert len(tried) > 1 and state.iterations > direct.iterations
    with pytest.raises(RuntimeError, match="too long"):
        _approach(short, top, None, h, solve, halvings=0)
