"""Verification of asperity.surface against closed forms (report 2.3, 2.4.3, 2.6.1).

Tolerances are stated next to each assert, with where they come from.
The estimates are on the dimension ``estimator`` (``method`` would clash
with the ``method=`` keyword of ``.sel``): ``ds.sel(estimator="counting")``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from asperity import surface as S

SQRT2 = math.sqrt(2.0)
PEAK = 1.0 / (6.0 * math.pi * math.sqrt(3.0))


def value(ds, name, estimator):
    return float(ds[name].sel(estimator=estimator))


def rel(a, b):
    return abs(a / b - 1.0)


# --------------------------------------------------------------------------
# finite differences
# --------------------------------------------------------------------------


def test_stencil_weights_match_the_classical_formulas():
    a2, b2 = S.stencil(2)
    np.testing.assert_allclose(a2, [0.5], rtol=0, atol=1e-15)
    np.testing.assert_allclose(b2, [-2.0, 1.0], rtol=0, atol=1e-15)
    a4, b4 = S.stencil(4)
    np.testing.assert_allclose(a4, [2 / 3, -1 / 12], rtol=1e-14)
    np.testing.assert_allclose(b4, [-5 / 2, 4 / 3, -1 / 12], rtol=1e-14)
    a8, b8 = S.stencil(8)
    np.testing.assert_allclose(a8, [4 / 5, -1 / 5, 4 / 105, -1 / 280], rtol=1e-14)
    np.testing.assert_allclose(b8, [-205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560], rtol=1e-14)


@pytest.mark.parametrize("order", [2, 4, 6, 8, 10])
def test_derivatives_exact_on_polynomials_of_degree_order(order):
    # the order-2p central formulas are exact for degree 2p (slope and curvature)
    rng = np.random.default_rng(order)
    coef = rng.uniform(-1, 1, order + 1)
    dx = 0.1
    s = np.arange(40) * dx - 2.0
    poly = np.polynomial.Polynomial(coef)
    slope, curv = S.derivatives(poly(s), dx, order)
    p = order // 2
    # tolerance: roundoff of O(1) values divided by dx^2 = 1e-2 -> ~1e-12
    np.testing.assert_allclose(slope, poly.deriv(1)(s[p:-p]), rtol=0, atol=1e-10)
    np.testing.assert_allclose(curv, poly.deriv(2)(s[p:-p]), rtol=0, atol=1e-9)


@pytest.mark.parametrize("order", [2, 4, 6, 8, 10])
def test_derivative_error_on_a_cosine_is_the_leading_truncation_term(order):
    # for cos(k s) the formulas return exactly M(kh) times the true derivative,
    # with 1 - M = (p!)^2/(2p+1)! (kh)^{2p} (slope), 2 (p!)^2/(2p+2)! (kh)^{2p}
    # (curvature) + O((kh)^{2p+2}); at kh = 0.4 the next term is < 10 % of
    # the leading one (measured: 0.5-5.5 %).
    p = order // 2
    kh = 0.4
    s = np.arange(300) * kh  # k = 1, dx = kh
    slope, curv = S.derivatives(np.cos(s + 0.3), kh, order)
    si = s[p:-p] + 0.3
    err1 = np.std(slope) / np.std(-np.sin(si)) - 1.0
    err2 = np.std(curv) / np.std(-np.cos(si)) - 1.0
    lead1 = -math.factorial(p) ** 2 / math.factorial(2 * p + 1) * kh ** (2 * p)
    lead2 = -2 * math.factorial(p) ** 2 / math.factorial(2 * p + 2) * kh ** (2 * p)
    assert abs(err1 / lead1 - 1.0) < 0.1
    assert abs(err2 / lead2 - 1.0) < 0.1


def test_derivatives_converge_at_eighth_order():
    # halving dx divides the pointwise error by 2^8 = 256 (leading term);
    # at k dx = 0.8 -> 0.4 the next term shifts the ratio by ~15 % (see above)
    errs = []
    for dx in (0.8, 0.4):
        s = np.arange(0.0, 60.0, dx)
        slope, curv = S.derivatives(np.sin(s), dx)
        errs.append((np.max(np.abs(slope - np.cos(s[4:-4]))), np.max(np.abs(curv + np.sin(s[4:-4])))))
    ratio_slope = errs[0][0] / errs[1][0]
    ratio_curv = errs[0][1] / errs[1][1]
    assert 256 * 0.8 < ratio_slope < 256 * 1.3
    assert 256 * 0.8 < ratio_curv < 256 * 1.3


def test_derivatives_along_an_axis_of_a_map():
    rng = np.random.default_rng(1)
    z = rng.standard_normal((30, 20))
    sx, cx = S.derivatives(z.T, 0.5, axis=0)
    sy, cy = S.derivatives(z, 0.5, axis=1)
    np.testing.assert_array_equal(sx, sy.T)  # same arithmetic, transposed
    np.testing.assert_array_equal(cx, cy.T)
    assert sy.shape == (30, 12)


def test_derivatives_reject_bad_arguments():
    with pytest.raises(ValueError, match="at least 9 points"):
        S.derivatives(np.zeros(8), 1.0)
    with pytest.raises(ValueError, match="even integer"):
        S.derivatives(np.zeros(20), 1.0, order=5)
    with pytest.raises(ValueError, match="positive"):
        S.derivatives(np.zeros(20), -1.0)


# --------------------------------------------------------------------------
# profile_cosine: report 2.6.1 example 1 (Fig. 2.11)
# --------------------------------------------------------------------------

C_COS, K_COS, DX_COS = 1.0, 2.0, 0.2


@pytest.fixture(scope="module")
def cosine_stats():
    # 0..20000 at 0.2: 100001 points, ~6366 wavelengths.  On a finite record
    # the (n-1) normalization and the incomplete last wavelength bias sigma
    # by ~1/(2n) + 1/(4 k L) ~ 1e-5, below the 1e-4 asserted below.
    s = np.arange(0.0, 20000.0 + 1e-9, DX_COS)
    return S.profile_statistics(C_COS * np.cos(K_COS * s), DX_COS), s[-1]


EXACT_COS = {
    "sigma": C_COS / SQRT2,  # 0.70711
    "sigma_slope": K_COS * C_COS / SQRT2,  # 1.41421
    "sigma_curvature": K_COS**2 * C_COS / SQRT2,  # 2.82843
    "beta": math.sqrt(1.5),  # 1.22474
    "peak_density": K_COS**2 * PEAK,  # m4/m2 = k^2
    "zero_density": K_COS / math.pi,
    "extremum_density": K_COS / math.pi,
}


@pytest.mark.parametrize("method", ["sampling", "counting", "spectral"])
@pytest.mark.parametrize("name", list(EXACT_COS))
def test_profile_cosine(cosine_stats, method, name):
    ds, _ = cosine_stats
    # requirement 0.1 %; achieved ~1e-5 (record bias, see fixture): assert 0.01 %
    assert rel(value(ds, name, method), EXACT_COS[name]) < 1e-4


def test_profile_cosine_on_the_reports_record_length():
    # The report's record 0..200 (1001 points, 63.7 wavelengths).  sigma is
    # biased by the record, not by the scheme: +5.0e-4 from the (n-1)
    # normalization and +6.6e-4 because the mean of cos^2 over this record
    # (incomplete last wavelength) is not 1/2: 1.16e-3 in all.  So 0.1 % is
    # out of reach on this record for sigma; assert 1.5e-3.
    s = np.arange(0.0, 200.0 + 1e-9, DX_COS)
    ds = S.profile_statistics(np.cos(K_COS * s), DX_COS, estimators=("sampling", "counting"))
    for m in ("sampling", "counting"):
        for name in ("sigma", "sigma_slope", "sigma_curvature", "beta"):
            assert rel(value(ds, name, m), EXACT_COS[name]) < 1.5e-3
        # the ratio sigma_slope / sigma = k is free of that bias: what is left
        # is the scheme ((p!)^2/9! (k dx)^8 = 6.5e-7) and the 8 dropped end
        # points (~1/n); measured 3.1e-6 (sampling), 1.1e-6 (counting)
        assert rel(value(ds, "sigma_slope", m) / value(ds, "sigma", m), K_COS) < 1e-5


def test_profile_cosine_means_are_bounded_by_the_record(cosine_stats):
    ds, L = cosine_stats
    # mean of C cos(ks) over [0, L] is at most 2C/(kL); mean slope is
    # (z(b)-z(a))/(b-a) <= 2C/(L - 8 dx); mean curvature <= 2kC/(L - 8 dx)
    assert abs(value(ds, "mean_height", "sampling")) <= 2 * C_COS / (K_COS * L) * 1.01
    assert abs(value(ds, "mean_slope", "sampling")) <= 2 * C_COS / (L - 8 * DX_COS) * 1.01
    assert abs(value(ds, "mean_curvature", "sampling")) <= 2 * K_COS * C_COS / (L - 8 * DX_COS) * 1.01
    for m in ("counting", "spectral"):
        assert np.isnan(value(ds, "mean_slope", m))


def test_profile_statistics_dataset_contract(cosine_stats):
    ds, _ = cosine_stats
    assert list(ds["estimator"].values) == ["sampling", "counting", "spectral"]
    expected_units = {
        "mean_height": "m", "mean_slope": "1", "mean_curvature": "1/m", "sigma": "m",
        "sigma_slope": "1", "sigma_curvature": "1/m", "m0": "m^2", "m2": "1", "m4": "1/m^2",
        "zero_density": "1/m", "extremum_density": "1/m", "peak_density": "1/m^2", "beta": "1",
        "points": "1", "spacing": "m",
    }
    for name, units in expected_units.items():
        assert ds[name].attrs["units"] == units, name
        assert ds[name].attrs["long_name"], name
    assert int(ds["points"]) == 100001
    assert float(ds["spacing"]) == DX_COS
    # internal consistency: m2 = sigma_slope^2 and beta from the moments
    for m in S.ESTIMATORS:
        assert rel(value(ds, "m2", m), value(ds, "sigma_slope", m) ** 2) < 1e-14
        b = math.sqrt(1.5) * value(ds, "m2", m) / math.sqrt(value(ds, "m0", m) * value(ds, "m4", m))
        assert rel(value(ds, "beta", m), b) < 1e-14


# --------------------------------------------------------------------------
# properties
# --------------------------------------------------------------------------


@settings(max_examples=25, deadline=None)
@given(
    a=st.floats(1e-3, 1e3),
    b=st.floats(1e-3, 1e3),
    seed=st.integers(0, 2**16),
)
def test_statistics_scale_with_heights_and_lengths(a, b, seed):
    # z -> a z, s -> b s: sigma ~ a, slopes ~ a/b, curvatures ~ a/b^2,
    # m0 ~ a^2, m2 ~ (a/b)^2, m4 ~ a^2/b^4, densities ~ 1/b, D_p ~ 1/b^2,
    # beta invariant.  Only roundoff differs: rtol 1e-9.
    rng = np.random.default_rng(seed)
    C, k, e = S.quasirandom_series(n=8, seed=seed, period=60.0, k_range=(0.2, 2.0))
    dx = 0.25
    z = S.evaluate_series(np.arange(400) * dx, C, k, e) + rng.uniform(-1, 1)
    ref = S.profile_statistics(z, dx)
    scaled = S.profile_statistics(a * z, b * dx)
    powers = {
        "mean_height": (1, 0), "mean_slope": (1, -1), "mean_curvature": (1, -2),
        "sigma": (1, 0), "sigma_slope": (1, -1), "sigma_curvature": (1, -2),
        "m0": (2, 0), "m2": (2, -2), "m4": (2, -4), "zero_density": (0, -1),
        "extremum_density": (0, -1), "peak_density": (0, -2), "beta": (0, 0),
    }
    for name, (pa, pb) in powers.items():
        expect = ref[name].values * a**pa * b**pb
        np.testing.assert_allclose(scaled[name].values, expect, rtol=1e-9, atol=0, err_msg=name)


@settings(max_examples=40, deadline=None)
@given(
    ppw=st.floats(12.0, 60.0),
    wavelengths=st.floats(10.0, 40.0),
    k=st.floats(0.05, 50.0),
    phase=st.floats(0.0, 2 * math.pi),
    amplitude=st.floats(1e-3, 1e3),
    offset=st.floats(-10.0, 10.0),
)
def test_counting_any_cosine_within_a_tenth_of_a_percent(ppw, wavelengths, k, phase, amplitude, offset):
    # D_zero = D_extr = k/pi exactly for a cosine (2.3.1).  With >= 12 points
    # per wavelength and >= 10 wavelengths, interpolation of the crossings and
    # the record's mean offset change (count-1)/(last-first) by < 3e-4
    # (scan of 4000 cases); the requirement is 0.1 %.
    dx = 2 * math.pi / (k * ppw)
    n = int(wavelengths * ppw) + 1
    z = amplitude * np.cos(k * np.arange(n) * dx + phase) + offset * amplitude
    ds = S.profile_statistics(z, dx, estimators=("counting",))
    assert rel(value(ds, "zero_density", "counting"), k / math.pi) < 1e-3
    assert rel(value(ds, "extremum_density", "counting"), k / math.pi) < 1e-3
    # sigma_slope / sigma = pi D_zero = k
    assert rel(value(ds, "sigma_slope", "counting") / value(ds, "sigma", "counting"), k) < 1e-3


def test_counting_handles_exact_zeros_and_touching():
    # a square-ish wave sampled with exact mean values on the crossings:
    # z = 1, 0, -1, 0, 1, ... crosses at every zero sample, positions exact
    z = np.tile([1.0, 0.0, -1.0, 0.0], 50)
    ds = S.profile_statistics(z - z.mean(), 1.0, order=2, estimators=("counting",))
    # crossings every 2 samples: D_zero = 1/2 per unit length
    assert value(ds, "zero_density", "counting") == pytest.approx(0.5, rel=1e-12)


# --------------------------------------------------------------------------
# spectral method
# --------------------------------------------------------------------------


def test_power_spectrum_parseval_for_white_noise():
    # sum P dk = sum (w z)^2 / sum w^2 exactly (normalization by window power)
    rng = np.random.default_rng(7)
    z = rng.standard_normal(4096)
    k, P = S.power_spectrum(z, 0.5)
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(z.size) / z.size)
    exact = np.sum((w * (z - z.mean())) ** 2) / np.sum(w * w)
    assert rel(P.sum() * k[1], exact) < 1e-12
    # and that is the variance to within the sampling error of a 4096-point
    # white-noise estimate weighted by w^2: ~ sqrt(2 * 1.94 / 4096) ~ 3 %; 5 sigma
    assert rel(P.sum() * k[1], z.var()) < 0.15
    assert k[1] == pytest.approx(2 * np.pi / (4096 * 0.5), rel=1e-15)


def test_spectral_moments_of_a_periodic_series_closed_form():
    # Lines on FFT bins (whole periods) leak through the Hann window into the
    # bins k, k +- dk with power fractions 2/3, 1/6, 1/6, hence exactly
    #   m0' = m0,  m2' = m2 + dk^2 m0 / 3,  m4' = m4 + 2 dk^2 m2 + dk^4 m0 / 3
    # (lines here are >= 20 bins apart: no overlap).  Roundoff only: 1e-9.
    C, k, e = S.quasirandom_series()
    periods, n_per = 20, 1250
    dx = 500.0 / n_per
    z = S.evaluate_series(np.arange(periods * n_per) * dx, C, k, e)
    ds = S.profile_statistics(z, dx, estimators=("spectral",))
    ex = S.series_statistics(C, k)
    dk = 2 * math.pi / (periods * 500.0)
    assert rel(value(ds, "m0", "spectral"), ex["m0"]) < 1e-9
    assert rel(value(ds, "m2", "spectral"), ex["m2"] + dk**2 * ex["m0"] / 3) < 1e-9
    m4 = ex["m4"] + 2 * dk**2 * ex["m2"] + dk**4 * ex["m0"] / 3
    assert rel(value(ds, "m4", "spectral"), m4) < 1e-9


# --------------------------------------------------------------------------
# profile_quasirandom: report 2.6.1 example 2 (Fig. 2.12)
# --------------------------------------------------------------------------


def test_quasirandom_series_is_in_the_reports_range():
    C, k, e = S.quasirandom_series()
    assert C.size == k.size == e.size == 40
    st_ = S.series_statistics(C, k)
    # by construction sigma = 1.162; the others within 15 % of Fig. 2.12b
    # (0.59221, 0.49315, 0.74954); ours: 0.5926, 0.5135, 0.7209
    assert st_["sigma"] == pytest.approx(1.162, rel=1e-12)
    assert rel(st_["sigma_slope"], 0.59221) < 0.15
    assert rel(st_["sigma_curvature"], 0.49315) < 0.15
    assert rel(st_["beta"], 0.74954) < 0.15
    # eq. (2.4) in 1-D
    assert st_["m2"] == pytest.approx(0.5 * np.sum(k**2 * C**2), rel=1e-14)
    # periodic with period 500: k = 2 pi m / 500, m integer, distinct
    m = k * 500.0 / (2 * math.pi)
    np.testing.assert_allclose(m, np.round(m), rtol=0, atol=1e-9)
    assert np.unique(np.round(m)).size == 40


def test_evaluate_series_derivatives_are_exact():
    C, k, e = S.quasirandom_series(n=5, seed=3, period=50.0)
    s = np.linspace(0.0, 7.0, 11)
    z = S.evaluate_series(s, C, k, e)
    np.testing.assert_allclose(z, (C * np.cos(np.outer(s, k) + e)).sum(axis=1), rtol=1e-13)
    z2 = S.evaluate_series(s, C, k, e, derivative=2)
    np.testing.assert_allclose(z2, (-C * k**2 * np.cos(np.outer(s, k) + e)).sum(axis=1), rtol=1e-12, atol=1e-14)


def test_profile_quasirandom_sampling_converges_to_the_series():
    # 20 whole periods of the period-500 series at dx = 0.8, 0.4, 0.2
    # (k_max dx = 0.96, 0.48, 0.24): two errors, both shrinking with dx:
    # * truncation of the order-8 differences, (p!)^2/(2p+1)! (k dx)^8 for
    #   the top component: 1.1e-3, 4e-6, 2e-8 of its share;
    # * the record: over whole periods the cross terms between components
    #   vanish except for the 2p = 8 end points dropped by the stencil: the
    #   variance changes by (8 m2 - sum of the 8 dropped z'^2)/(N - 8), at
    #   most 8/N * max z'^2/m2 relative (max z'^2/m2 = 9.9, z''^2/m4 = 11.5
    #   for this series), i.e. < 4/N * 11.5 = 9.2e-4 on sigma for N = 50000.
    # Measured (sigma_slope, sigma_curvature): 4.3e-4, 2.7e-4 / 3.1e-4, 1.5e-4
    # / 2.3e-4, 2.6e-5.  The report's own scheme: up to 20 % (Fig. 2.12c).
    C, k, e = S.quasirandom_series()
    ex = S.series_statistics(C, k)
    errors = []
    for n_per in (625, 1250, 2500):
        dx = 500.0 / n_per
        z = S.evaluate_series(np.arange(20 * n_per) * dx, C, k, e)
        ds = S.profile_statistics(z, dx, estimators=("sampling",))
        errors.append([rel(value(ds, q, "sampling"), ex[q]) for q in ("sigma_slope", "sigma_curvature")])
        # sigma over whole periods: only the (n-1) normalization, 1/(2N)
        assert rel(value(ds, "sigma", "sampling"), ex["sigma"]) < 1.0 / (20 * n_per)
    errors = np.array(errors)
    assert np.all(np.diff(errors, axis=0) < 0), errors  # monotone decrease
    assert np.all(errors[-1] < 1e-3), errors


# --------------------------------------------------------------------------
# argument errors
# --------------------------------------------------------------------------


def test_profile_statistics_errors_name_the_problem():
    z = np.cos(np.arange(100) * 0.3)
    bad = z.copy()
    bad[17] = np.nan
    with pytest.raises(ValueError, match="index 17"):
        S.profile_statistics(bad, 0.3)
    bad[17] = np.inf
    bad[5] = -np.inf
    with pytest.raises(ValueError, match="index 5"):
        S.profile_statistics(bad, 0.3)
    with pytest.raises(ValueError, match=r"sampling method .* at least 10 points.*got 9"):
        S.profile_statistics(z[:9], 0.3)
    with pytest.raises(ValueError, match=r"counting method .* at least 6 points"):
        S.profile_statistics(z[:5], 0.3, order=4, estimators=("counting",))
    with pytest.raises(ValueError, match=r"counting method needs at least 2 .*crossings"):
        S.profile_statistics(z[:12], 0.3, estimators=("counting",))  # 3.6 < half a wavelength
    with pytest.raises(ValueError, match=r"spectral method needs at least 4 points; got 3"):
        S.profile_statistics(z[:3], 0.3, estimators=("spectral",))
    with pytest.raises(ValueError, match="estimators must be"):
        S.profile_statistics(z, 0.3, estimators=("fourier",))
    with pytest.raises(ValueError, match="spacing dx"):
        S.profile_statistics(z, 0.0)
    with pytest.raises(ValueError, match="1-D"):
        S.profile_statistics(z.reshape(10, 10), 0.3)


# --------------------------------------------------------------------------
# anisotropic surfaces (2.3.2)
# --------------------------------------------------------------------------


def anisotropic_series(seed=3, n=6):
    rng = np.random.default_rng(seed)
    kmag = rng.uniform(0.5, 2.0, n)
    ang = rng.uniform(0.0, np.pi, n)
    C = rng.uniform(0.5, 1.5, n)
    e = rng.uniform(0.0, 2 * np.pi, n)
    return C, kmag * np.cos(ang), kmag * np.sin(ang), e


def profile_moments(C, kx, ky, theta):
    """Exact moments of profiles along theta: 1-D eq. (2.4) with k = kx c + ky s."""
    out = [S.series_statistics(C, kx * math.cos(t) + ky * math.sin(t)) for t in theta]
    return [np.array([o[m] for o in out]) for m in ("m0", "m2", "m4")]


@pytest.mark.parametrize("ndir", [5, 7, 12])
def test_directional_moments_recover_eq_2_4(ndir):
    C, kx, ky, _ = anisotropic_series()
    theta = np.linspace(0.1, 0.1 + np.pi, ndir, endpoint=False)
    ds = S.directional_moments(theta, *profile_moments(C, kx, ky, theta))
    exact = S.series_moments_2d(C, kx, ky)
    for name, v in exact.items():
        # exact data, well-conditioned systems: roundoff, 1e-12 of the scale
        order = int(name[1]) + int(name[2])
        scale = math.sqrt(exact[f"m{order}0"] * exact[f"m0{order}"])
        assert abs(float(ds[name]) - v) < 1e-12 * scale, name
    assert ds.attrs["fourth_order_moments"] == f"determined from {ndir} directions"
    inv = S.moment_invariants(**exact)
    for key, v in inv.items():
        assert rel(float(ds[f"invariant_{key}"]), v) < 1e-10
        assert ds[f"invariant_{key}"].attrs["units"]


def test_directional_moments_with_three_or_four_directions():
    C, kx, ky, _ = anisotropic_series()
    exact = S.series_moments_2d(C, kx, ky)
    # 4 profiles, one repeated at theta + pi: 3 distinct directions
    theta = np.array([0.0, 0.5, 1.5, 0.5 + np.pi])
    ds = S.directional_moments(theta, *profile_moments(C, kx, ky, theta))
    assert ds.attrs["fourth_order_moments"] == "not determined: 3 directions given, 5 needed"
    for name in ("m40", "m31", "m22", "m13", "m04"):
        assert name not in ds
    for name in ("m00", "m20", "m11", "m02"):
        assert rel(float(ds[name]), exact[name]) < 1e-12
    assert {"invariant_1", "invariant_2", "invariant_3"} <= set(ds.data_vars)
    for key in (4, 5, 6, 7):
        assert f"invariant_{key}" not in ds  # not determined by these three
    theta4 = np.array([0.0, 0.5, 1.5, 2.5])
    ds4 = S.directional_moments(theta4, *profile_moments(C, kx, ky, theta4))
    assert ds4.attrs["fourth_order_moments"] == "not determined: 4 directions given, 5 needed"


def test_invariant_4_from_three_equally_spaced_directions():
    # m4 averaged over three directions pi/3 apart is exactly 3/8 (m40 + 2 m22 + m04)
    C, kx, ky, _ = anisotropic_series()
    theta = 0.2 + np.array([0.0, 1.0, 2.0]) * np.pi / 3
    m0, m2, m4 = profile_moments(C, kx, ky, theta)
    ds = S.directional_moments(theta, m0, m2, m4)
    inv4 = S.moment_invariants(**S.series_moments_2d(C, kx, ky))[4]
    assert rel(float(ds["invariant_4"]), inv4) < 1e-12
    assert rel(inv4, 8.0 / 3.0 * m4.mean()) < 1e-12


def test_directional_moments_need_three_directions():
    with pytest.raises(ValueError, match="at least 3 distinct directions.*got 2"):
        S.directional_moments([0.0, 1.0, np.pi], [1, 1, 1], [1, 2, 1], [1, 2, 1])
    with pytest.raises(ValueError, match="one value per profile"):
        S.directional_moments([0.0, 1.0, 2.0], [1, 1], [1, 2, 1], [1, 2, 1])


@settings(max_examples=20, deadline=None)
@given(alpha=st.floats(0.0, 2 * math.pi), seed=st.integers(0, 1000))
def test_invariants_are_rotation_invariant(alpha, seed):
    C, kx, ky, _ = anisotropic_series(seed=seed, n=5)
    ca, sa = math.cos(alpha), math.sin(alpha)
    inv = S.moment_invariants(**S.series_moments_2d(C, kx, ky))
    rot = S.moment_invariants(**S.series_moments_2d(C, ca * kx - sa * ky, sa * kx + ca * ky))
    for key in inv:
        # roundoff of products of O(1..10) moments; relative to the terms' scale
        assert abs(rot[key] - inv[key]) <= 1e-10 * max(1.0, abs(inv[key])), key


def test_isotropic_surface_moments():
    # wave vectors at 6 equally spaced angles for each |k|: isotropic moments,
    # m20 = m02 = m2, m11 = 0, 3 m22 = m40 = m04 = m4 (2.3.1)
    kmag = np.repeat([0.5, 1.0, 2.0], 6)
    ang = np.tile(np.arange(6) * np.pi / 6, 3) + 0.37
    C = np.repeat([1.0, 0.6, 0.2], 6)
    kx, ky = kmag * np.cos(ang), kmag * np.sin(ang)
    theta = np.array([0.0, 0.4, 1.1, 1.9, 2.6])
    m0, m2, m4 = profile_moments(C, kx, ky, theta)
    np.testing.assert_allclose(m2, m2[0], rtol=1e-13)  # every direction alike
    np.testing.assert_allclose(m4, m4[0], rtol=1e-13)
    ds = S.directional_moments(theta, m0, m2, m4)
    assert rel(float(ds.m20), m2[0]) < 1e-12
    assert rel(float(ds.m02), m2[0]) < 1e-12
    assert abs(float(ds.m11)) < 1e-12 * m2[0]
    for name in ("m40", "m04"):
        assert rel(float(ds[name]), m4[0]) < 1e-12
    assert rel(3 * float(ds.m22), m4[0]) < 1e-12
    assert abs(float(ds.m31)) < 1e-12 * m4[0] and abs(float(ds.m13)) < 1e-12 * m4[0]


def test_directional_moments_from_sampled_profiles():
    # sample profiles of the surface along 7 directions, estimate m0, m2, m4 by
    # the sampling method, recover the m_pq.  Error budget: record of 4000
    # with projected wavenumbers >= 0.05 apart gives cross-term errors
    # ~ 1/(dk L) ~ 0.5 % of the moment scale; differences at k dx <= 0.1:
    # < 1e-9.  Tolerance 1 % of sqrt(m_{p+q,0} m_{0,p+q}) (Cauchy-Schwarz scale).
    C, kx, ky, e = anisotropic_series()
    theta = np.linspace(0.0, np.pi, 7, endpoint=False)
    dx = 0.05
    s = np.arange(0.0, 4000.0, dx)
    m0, m2, m4 = [], [], []
    for t in theta:  # one profile per direction
        kp = kx * math.cos(t) + ky * math.sin(t)
        ds = S.profile_statistics(S.evaluate_series(s, C, kp, e), dx, estimators=("sampling",))
        m0.append(float(ds.m0[0]))
        m2.append(float(ds.m2[0]))
        m4.append(float(ds.m4[0]))
    got = S.directional_moments(theta, m0, m2, m4)
    exact = S.series_moments_2d(C, kx, ky)
    for name, v in exact.items():
        order = int(name[1]) + int(name[2])
        scale = math.sqrt(exact[f"m{order}0"] * exact[f"m0{order}"])
        assert abs(float(got[name]) - v) < 0.01 * scale, name


# --------------------------------------------------------------------------
# 2-D maps (2.4.3)
# --------------------------------------------------------------------------


def hill_map(n=66, cells=16, dx=0.1, C=2.0, shift=(0.0, 0.0)):
    """z = C cos(kx) cos(ky), wavelength `cells` grid steps, peaks on grid points."""
    k = 2 * np.pi / (cells * dx)
    x = np.arange(n) * dx + shift[0]
    y = np.arange(n) * dx + shift[1]
    return C * np.cos(k * y)[:, None] * np.cos(k * x)[None, :], k


def test_map_peaks_of_cosine_hills_where_predicted():
    z, k = hill_map()
    pk = S.map_peaks(z, 0.1, 0.1)
    # maxima of cos(kx)cos(ky): both indices = 0 mod 16 or both = 8 mod 16,
    # interior (1..64)
    idx = np.arange(1, 65)
    want = {(i, j) for i in idx for j in idx if i % 8 == 0 and j % 8 == 0 and (i // 8 + j // 8) % 2 == 0}
    got = set(zip(pk.row.values.tolist(), pk.column.values.tolist()))
    assert got == want and len(want) == 32
    np.testing.assert_allclose(pk.x.values, pk.column.values * 0.1, rtol=1e-15)
    np.testing.assert_allclose(pk.height.values, 2.0 - z.mean(), rtol=1e-12)
    kh = k * 0.1  # 2 pi / 16
    full = pk.fd_order.values == 8
    # order 8: relative error of z_xx on cos is 2 (4!)^2/10! (kh)^8 = 1.80e-7
    # (+ higher terms, < 5 %); curvature = C k^2 (1 - that)
    lead = 2 * 576 / math.factorial(10) * kh**8
    np.testing.assert_allclose(pk.curvature.values[full] / (2.0 * k**2), 1 - lead, rtol=0.05 * lead)
    # peaks next to the edge (index 64 of 0..65) use order 2: exactly
    # 2 (1 - cos kh) / kh^2 times the true curvature
    edge = pk.fd_order.values == 2
    assert edge.sum() == 7
    np.testing.assert_allclose(pk.curvature.values[edge] / (2.0 * k**2), 2 * (1 - math.cos(kh)) / kh**2, rtol=1e-12)
    np.testing.assert_allclose(pk.z_xy.values, 0.0, atol=1e-10)


def test_map_peaks_order_2_is_the_three_point_formula():
    z, k = hill_map()
    pk = S.map_peaks(z, 0.1, 0.1, order=2)
    kh = k * 0.1
    np.testing.assert_allclose(pk.z_xx.values / (-2.0 * k**2), 2 * (1 - math.cos(kh)) / kh**2, rtol=1e-12)
    np.testing.assert_allclose(pk.z_yy.values, pk.z_xx.values, rtol=1e-12)


def test_map_peaks_second_derivatives_of_a_quadratic_hill():
    # z = -(a x^2 + 2 b x y + c y^2): central formulas exact, z_xy = -2b
    dx, dy = 0.2, 0.3
    x = (np.arange(21) - 10) * dx
    y = (np.arange(17) - 8) * dy
    a, b, c = 1.5, 0.4, 0.9
    z = -(a * x[None, :] ** 2 + 2 * b * x[None, :] * y[:, None] + c * y[:, None] ** 2)
    pk = S.map_peaks(z, dx, dy)
    assert pk.sizes["peak"] == 1 and int(pk.row[0]) == 8 and int(pk.column[0]) == 10
    assert float(pk.z_xx[0]) == pytest.approx(-2 * a, rel=1e-12)
    assert float(pk.z_yy[0]) == pytest.approx(-2 * c, rel=1e-12)
    assert float(pk.z_xy[0]) == pytest.approx(-2 * b, rel=1e-12)
    assert float(pk.curvature[0]) == pytest.approx(a + c, rel=1e-12)
    assert float(pk.x[0]) == pytest.approx(10 * dx) and float(pk.y[0]) == pytest.approx(8 * dy)


def test_map_peaks_off_grid_and_plateaus():
    # peaks a quarter step off the grid: found at the nearest grid point
    z, _ = hill_map(shift=(0.025, -0.025))
    pk = S.map_peaks(z, 0.1, 0.1)
    assert pk.sizes["peak"] == 32
    # a plateau of two equal maxima is no peak (strictly higher rule)
    flat = np.zeros((5, 6))
    flat[2, 2] = flat[2, 3] = 1.0
    assert S.map_peaks(flat, 1.0, 1.0).sizes["peak"] == 0
    flat[2, 3] = 0.5
    assert S.map_peaks(flat, 1.0, 1.0).sizes["peak"] == 1


def test_map_statistics_of_cosine_hills():
    # z = C cos kx cos ky = sum of (k, k), (k, -k) waves of amplitude C/2:
    # eq. (2.4): m20 = m02 = C^2 k^2 / 4, m40 = m04 = m22 = C^2 k^4 / 4;
    # peak density 2 per (2 pi/k)^2 = k^2/(2 pi^2).
    C = 2.0
    z, k = hill_map(n=130, C=C)  # interior 1..128: 8 whole wavelengths
    ds = S.map_statistics(z, 0.1, 0.1)
    assert int(ds.peak_count) == 128
    assert float(ds.peak_density) == pytest.approx(k**2 / (2 * math.pi**2), rel=1e-12)
    # moments on a map of whole periods (128 = 8 wavelengths on both axes):
    # m00 exact up to (n-1)/n; the derivatives drop 4 points at each end of a
    # line (4 % of a line), so their (co)variances carry a record bias of the
    # order of 8/128 * the scale at most (measured 6.6e-5): assert 1e-3.
    z, k = hill_map(n=128, C=C)
    ds = S.map_statistics(z, 0.1, 0.1)
    exact = S.series_moments_2d([C / 2, C / 2], [k, k], [k, -k])
    for name, v in exact.items():
        order = int(name[1]) + int(name[2])
        scale = math.sqrt(exact[f"m{order}0"] * exact[f"m0{order}"])
        assert abs(float(ds[name]) - v) < 1e-3 * scale, name
    assert rel(float(ds.sigma), C / 2 * math.sqrt(128**2 / (128**2 - 1))) < 1e-12
    assert float(ds.sigma_slope_x) ** 2 == pytest.approx(float(ds.m20), rel=1e-14)
    assert ds.peak_density.attrs["units"] == "1/m^2"
    assert ds.sigma_curvature_y.attrs["units"] == "1/m"


def test_map_statistics_moments_of_an_anisotropic_series():
    # waves on the lattice of a 40 x 40 map (whole periods): rows and columns
    # give m00, m20, m02, m40, m04 exactly up to the (n-1) normalization and
    # the 8 dropped points (< 1e-4 measured 1.6e-5); the cross moments use the
    # common interior, not whole periods: a few 1e-3 of the scale.
    rng = np.random.default_rng(5)
    L, n = 40.0, 256
    dx = L / n
    i = np.array([3, 5, -4, 7, 2, 6])
    j = np.array([1, 4, 6, -2, 7, 3])
    kx, ky = 2 * np.pi * i / L, 2 * np.pi * j / L
    C = rng.uniform(0.5, 1.5, i.size)
    e = rng.uniform(0, 2 * np.pi, i.size)
    x = np.arange(n) * dx
    phase = kx[:, None, None] * x[None, None, :] + ky[:, None, None] * x[None, :, None] + e[:, None, None]
    z = np.tensordot(C, np.cos(phase), axes=1)
    ds = S.map_statistics(z, dx, dx)
    exact = S.series_moments_2d(C, kx, ky)
    for name in ("m00", "m20", "m02", "m40", "m04"):
        assert rel(float(ds[name]), exact[name]) < 1e-4, name
    for name in ("m11", "m31", "m22", "m13"):
        order = int(name[1]) + int(name[2])
        scale = math.sqrt(exact[f"m{order}0"] * exact[f"m0{order}"])
        assert abs(float(ds[name]) - exact[name]) < 5e-3 * scale, name
    inv = S.moment_invariants(**exact)
    for key, v in inv.items():
        assert rel(float(ds[f"invariant_{key}"]), v) < 5e-3, key


def test_map_errors():
    z, _ = hill_map(n=20)
    bad = z.copy()
    bad[3, 7] = np.nan
    with pytest.raises(ValueError, match=r"\(row 3, column 7\)"):
        S.map_statistics(bad, 0.1, 0.1)
    with pytest.raises(ValueError, match=r"\(row 3, column 7\)"):
        S.map_peaks(bad, 0.1, 0.1)
    with pytest.raises(ValueError, match="at least 10 points along each axis"):
        S.map_statistics(z[:9], 0.1, 0.1)
    with pytest.raises(ValueError, match="3 x 3"):
        S.map_peaks(z[:2], 0.1, 0.1)
    with pytest.raises(ValueError, match="spacing dy"):
        S.map_peaks(z, 0.1, -1.0)


def test_estimates_are_selected_by_name():
    """The dimension is `estimator`: sel by name picks one estimate (with a dimension named
    `method`, ds.sigma.sel(method="sampling") silently returned all of them)."""
    z = np.cos(np.arange(2000) * 0.4)
    ds = S.profile_statistics(z, 0.2)
    one = ds.sigma.sel(estimator="sampling")
    assert one.ndim == 0 and str(one["estimator"].values) == "sampling"
    assert float(one) == pytest.approx(np.std(z, ddof=1), rel=1e-14)
    assert "method" not in ds.dims
