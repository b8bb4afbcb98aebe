"""Peak densities: report 2.4.1 (Nayak/Francis), 2.4.3 (sampled), 7.1 (fixed curvature)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from asperity.peaks import FixedCurvatureDensity, JointDensity, SampledDensity, francis_density
from asperity.peaks.isotropic import _eta_factor

# report 2.6.2 (with the errata of DESIGN.md for Fig. 2.12b)
SIGMA, SIGMA_SLOPE, SIGMA_CURV = 1.1620, 0.59221, 0.49315

# closed-form moments of the marginals.  Completing the square,
#   f = sqrt(3)/(pi sqrt(1-b^2)) g(eta) exp(-eta^2/2) exp(-(xi - b eta)^2 / (2 (1-b^2)))
# so xi | eta ~ N(b eta, 1 - b^2) and the eta marginal is
#   f_eta = sqrt(6/pi) (eta^2 - 1 + exp(-eta^2)) exp(-eta^2/2),
# whose raw moments follow from int_0^inf eta^k exp(-a eta^2/2):
C6 = math.sqrt(6.0 / math.pi)
E_ETA = C6 * (2.0 - 1.0 + 1.0 / 3.0)                         # 4/3 sqrt(6/pi)
E_ETA2 = 2.0 * math.sqrt(3.0) + 1.0 / 3.0                     # sqrt(3) (2 + 3^-3/2)
E_ETA3 = C6 * (8.0 - 2.0 + 2.0 / 9.0)                         # 56/9 sqrt(6/pi)


def _grid_integral(beta, moments=(0,), half_width=14.0, step=0.01):
    """Trapezoid integral of xi^m f over xi in [-L, L], eta in [0, L].

    f decays like a Gaussian; at radius 14 it is below 1e-19 for beta <= 0.95,
    so truncation is negligible, and the trapezoid rule is spectrally accurate
    except at eta = 0 where f ~ eta^4 (error O(step^6)).
    """
    xi = np.arange(-half_width, half_width + step / 2, step)
    eta = np.arange(0.0, half_width + step / 2, step)
    f = francis_density(xi[:, None], eta[None, :], beta)
    marginal_xi = np.trapezoid(f, eta, axis=1)
    return [np.trapezoid(xi**m * marginal_xi, xi) for m in moments], xi, marginal_xi


@pytest.mark.parametrize("beta", [0.0, 0.3, 0.75, 0.95])
def test_francis_density_integrates_to_one(beta):
    (total,), _, _ = _grid_integral(beta)
    assert total == pytest.approx(1.0, abs=1e-8)


def test_francis_density_integrates_to_one_adaptive():
    # independent of any grid: scipy's adaptive cubature, beta = 0.3
    val, err = integrate.dblquad(
        lambda eta, xi: francis_density(xi, eta, 0.3), -15, 15, 0, 15, epsabs=1e-12, epsrel=1e-11
    )
    assert val == pytest.approx(1.0, abs=1e-8)


@pytest.mark.parametrize("beta", [0.3, 0.75])
def test_height_marginal_moments_finite_and_not_gaussian(beta):
    (m0, m1, m2, m3), xi, marg = _grid_integral(beta, moments=(0, 1, 2, 3))
    mean = beta * E_ETA
    third_eta = E_ETA3 - 3 * E_ETA * E_ETA2 + 2 * E_ETA**3  # central
    assert m1 == pytest.approx(mean, abs=1e-8)
    assert m2 == pytest.approx((1 - beta**2) + beta**2 * E_ETA2, abs=1e-8)
    third = m3 - 3 * m1 * m2 + 2 * m1**3
    assert third == pytest.approx(beta**3 * third_eta, abs=1e-8)
    # the height marginal is skewed (third central moment 0.0032 at beta = 0.3,
    # 0.051 at 0.75, far above the 1e-8 quadrature error), hence not Gaussian:
    # it differs from the normal density of the same mean and variance
    assert third > 1e-3
    gauss = np.exp(-0.5 * (xi - m1) ** 2 / (m2 - m1**2)) / math.sqrt(2 * math.pi * (m2 - m1**2))
    assert np.max(np.abs(marg - gauss)) > 1e-4


def test_height_marginal_is_standard_normal_for_beta_zero():
    # beta = 0: height and curvature independent, xi ~ N(0, 1) exactly
    _, xi, marg = _grid_integral(0.0)
    phi = np.exp(-0.5 * xi**2) / math.sqrt(2 * math.pi)
    assert np.max(np.abs(marg - phi)) < 1e-10


def test_exponent_is_the_corrected_one():
    # direct evaluation of the erratum's formula at one point
    xi, eta, b = 0.7, 1.3, 0.6
    expected = (
        math.sqrt(3) / (math.pi * math.sqrt(1 - b * b))
        * (eta**2 - 1 + math.exp(-(eta**2)))
        * math.exp(-(xi**2 - 2 * b * xi * eta + eta**2) / (2 * (1 - b * b)))
    )
    assert francis_density(xi, eta, b) == pytest.approx(expected, rel=1e-14)
    assert francis_density(xi, -eta, b) == 0.0


def test_eta_factor_is_accurate_for_small_eta():
    def reference(x):  # sum_{k>=2} (-x)^k / k!, exactly summed
        return math.fsum((-x) ** k / math.factorial(k) for k in range(2, 40))

    etas = np.geomspace(1e-9, 1.5, 400)
    got = _eta_factor(etas)
    ref = np.array([reference(e * e) for e in etas])
    np.testing.assert_allclose(got, ref, rtol=2e-14, atol=0)
    assert np.all(got > 0)


def test_density_edge_values():
    f = francis_density(np.array([0.0, np.inf, 1.0, np.nan]), np.array([np.inf, 1.0, 0.0, 1.0]), 0.5)
    assert f[0] == 0.0 and f[1] == 0.0 and f[2] == 0.0 and np.isnan(f[3])


def test_report_beta():
    d = JointDensity(SIGMA, SIGMA_SLOPE, SIGMA_CURV)
    assert d.beta == pytest.approx(0.74954, abs=1e-4)


def test_beta_at_least_one_is_refused():
    # a pure cosine z = C cos(k s): sigma = C/sqrt2, slope k C/sqrt2, curvature k^2 C/sqrt2
    c, k = 1.0, 2.0
    with pytest.raises(ValueError, match="deterministic"):
        JointDensity(c / math.sqrt(2), k * c / math.sqrt(2), k * k * c / math.sqrt(2))
    with pytest.raises(ValueError, match="SampledDensity"):
        francis_density(0.0, 1.0, 1.2247)
    with pytest.raises(ValueError):
        francis_density(0.0, 1.0, -0.1)
    with pytest.raises(ValueError):
        JointDensity(-1.0, 1.0, 1.0)


def test_dimensional_density_integrates_to_one():
    d = JointDensity(SIGMA, SIGMA_SLOPE, SIGMA_CURV, mean_height=0.3)
    z = np.linspace(0.3 - 14 * SIGMA, 0.3 + 14 * SIGMA, 2001)
    kmax = 14 * SIGMA_CURV / math.sqrt(1.5)
    kappa = np.linspace(0.0, kmax, 1001)
    f = d.pdf(z[:, None], kappa[None, :])
    assert np.trapezoid(np.trapezoid(f, kappa, axis=1), z) == pytest.approx(1.0, abs=1e-8)
    # the change of variables
    xi, eta = d.to_nondimensional(1.0, 0.4)
    assert d.pdf(1.0, 0.4) == pytest.approx(
        francis_density(xi, eta, d.beta) * math.sqrt(1.5) / (SIGMA * SIGMA_CURV), rel=1e-14
    )


@pytest.mark.parametrize("threshold", [1e-4, 1e-12])
def test_support_contains_region_and_is_tight(threshold):
    d = JointDensity(SIGMA, SIGMA_SLOPE, SIGMA_CURV)
    resolution = 1201
    z0, z1, k0, k1 = d.support(threshold, resolution=resolution)
    # independent, finer grid on a generous box in nondimensional variables
    xi = np.linspace(-12, 12, 4001)
    eta = np.linspace(0, 12, 2001)
    f = francis_density(xi[:, None], eta[None, :], d.beta)
    above = f > threshold
    xs, es = xi[above.any(axis=1)], eta[above.any(axis=0)]
    (zl, zh), (kl, kh) = d.to_dimensional(np.array([xs[0], xs[-1]]), np.array([es[0], es[-1]]))
    assert z0 <= zl and zh <= z1 and k0 <= kl and kh <= k1
    # tight: padded by one step of the support grid plus the reference grid's step
    from asperity.peaks.isotropic import _radius_bound

    step = 2 * _radius_bound(threshold, d.beta) / (resolution - 1)
    slack = step + 24 / 4000
    assert zl - z0 <= SIGMA * 1.01 * slack and z1 - zh <= SIGMA * 1.01 * slack
    assert k1 - kh <= SIGMA_CURV / math.sqrt(1.5) * 1.01 * slack
    assert k0 >= 0.0


def test_fixed_curvature_density():
    d = FixedCurvatureDensity(sigma_p=2e-6, curvature=5e3, mean_height=1e-6)
    z = np.linspace(1e-6 - 20e-6, 1e-6 + 20e-6, 4001)
    assert np.trapezoid(d.pdf(z), z) == pytest.approx(1.0, abs=1e-12)
    lo, hi, k0, k1 = d.support(1e-12)
    assert k0 == k1 == 5e3
    assert (hi - 1e-6) / 2e-6 == pytest.approx(math.sqrt(-2 * math.log(1e-12 * math.sqrt(2 * math.pi))), rel=1e-14)
    assert lo == pytest.approx(2e-6 - hi, rel=1e-14)
    # nondimensional density equals the threshold at the ends
    assert d.pdf(hi) * 2e-6 == pytest.approx(1e-12, rel=1e-10)
    assert d.radius == pytest.approx(2e-4)
    with pytest.raises(ValueError):
        d.support(0.5)


# peak heights and curvatures on a 1e-3 lattice (realistic spreads, ties included)
peaks_strategy = st.integers(min_value=1, max_value=300).flatmap(
    lambda n: st.tuples(
        st.lists(st.integers(-5000, 5000).map(lambda i: i * 1e-3), min_size=n, max_size=n),
        st.lists(st.integers(0, 3000).map(lambda i: i * 1e-3), min_size=n, max_size=n),
        st.tuples(st.integers(1, 12), st.integers(1, 12)),
    )
)


@settings(max_examples=60, deadline=None)
@given(peaks_strategy)
def test_sampled_density_integrates_to_one(data):
    z, k, bins = data
    d = SampledDensity.from_peaks(z, k, bins=bins)
    assert d.integral() == pytest.approx(1.0, abs=1e-12)
    # cell integrals are the peak fractions n_ij / N (report 2.4.3)
    ez, ek = d.height_edges, d.curvature_edges
    zc = 0.5 * (ez[1:] + ez[:-1])
    kc = 0.5 * (ek[1:] + ek[:-1])
    cell = d.pdf(zc[:, None], kc[None, :]) * np.diff(ez)[:, None] * np.diff(ek)[None, :]
    counts, _, _ = np.histogram2d(z, k, bins=(ez, ek))
    np.testing.assert_allclose(cell, counts / len(z), rtol=1e-12, atol=1e-15)
    # every peak sits in a cell of positive density, and nothing lies outside the range
    assert np.all(d.pdf(np.asarray(z), np.asarray(k)) > 0)
    assert d.pdf(ez[-1] + 1.0, kc[0]) == 0.0 and d.pdf(zc[0], ek[0] - 1.0) == 0.0


def test_sampled_density_range_and_support():
    z = np.array([0.1, 0.2, 0.9, 1.5])
    k = np.array([0.5, 0.5, 0.7, 0.7])
    d = SampledDensity.from_peaks(z, k, bins=(2, 1), range=((0.0, 1.0), (0.0, 1.0)))
    assert d.support() == (0.0, 1.0, 0.0, 1.0)
    assert d.integral() == pytest.approx(0.75, rel=1e-14)  # one peak out of range
    assert d.pdf(0.25, 0.5) == pytest.approx(2 / 4 / 0.5, rel=1e-14)
    assert d.pdf(1.0, 1.0) == pytest.approx(1 / 4 / 0.5, rel=1e-14)  # last edge included
    assert d.count == 4
    with pytest.raises(ValueError):
        SampledDensity.from_peaks([], [])


def test_sampled_density_of_identical_peaks():
    # one distinct peak (SI magnitudes): its range is scaled around the value
    d = SampledDensity.from_peaks(np.full(5, 3e-6), np.full(5, 2e4), bins=(3, 3))
    assert d.support() == pytest.approx((1.5e-6, 4.5e-6, 1e4, 3e4), rel=1e-15)
    assert d.integral() == pytest.approx(1.0, rel=1e-14)
    assert d.pdf(3e-6, 2e4) == pytest.approx(1.0 / (1e-6 * (2e4 / 3)), rel=1e-12)
    with pytest.raises(ValueError, match="too small"):
        SampledDensity.from_peaks([0.0, 1e-200], [0.0, 1e-200], bins=(2, 2))
