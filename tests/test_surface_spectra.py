"""Spectra, autocorrelation and the height distribution (asperity.surface.spectra, .distribution)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, stats

from asperity import surface as S


def few_long_waves():
    """One period (500) of a series whose height lives in three long waves, 1000 points."""
    period, n = 500.0, 1000
    k = 2 * np.pi * np.array([1.0, 2.0, 3.0]) / period
    C = np.array([1.0, 0.5, 1 / 3])
    e = np.array([0.3, 2.0, 4.1])
    s = np.arange(n) * period / n
    return S.evaluate_series(s, C, k, e), period / n, S.series_statistics(C, k)


def test_spectral_moments_of_a_periodic_series_are_exact_with_the_periodic_option():
    """One period, every component below Nyquist: the plain periodogram gives m0, m2, m4 of
    eq. (2.4) to round-off (1e-12); the Hann window costs 10 % of sigma on this record."""
    z, dx, exact = few_long_waves()
    periodic = S.profile_statistics(z, dx, estimators=("spectral",), window="none")
    for name in ("m0", "m2", "m4", "sigma", "peak_density", "beta"):
        assert float(periodic[name].sel(estimator="spectral")) == pytest.approx(exact[name], rel=1e-12), name
    hann = S.profile_statistics(z, dx, estimators=("spectral",), window="hann")
    assert float(hann["sigma"].sel(estimator="spectral")) / exact["sigma"] - 1 > 0.05
    C, k, e = S.quasirandom_series()  # the report's 40-component series, period 500
    s = np.arange(2000) * 0.25
    ds = S.profile_statistics(S.evaluate_series(s, C, k, e), 0.25, estimators=("spectral",), window="none")
    series = S.series_statistics(C, k)
    for name in ("m0", "m2", "m4"):
        assert float(ds[name].sel(estimator="spectral")) == pytest.approx(series[name], rel=1e-12), name


def test_windows():
    n = 64
    assert S.window(n, "none").sum() == n
    np.testing.assert_allclose(S.window(n, "hann")[[0, n // 2]], [0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(S.window(n, "blackman")[[0, n // 2]], [0.0, 1.0], atol=1e-15)
    with pytest.raises(ValueError, match="window must be one of"):
        S.window(n, "kaiser")


def test_radial_psd_of_a_plane_wave_holds_its_variance_on_its_ring():
    """cos(q0 . r) on a periodic grid, no window: C is the variance 1/2 spread over the grid
    points of one ring (counted here on the full plane), zero on the others (1e-12)."""
    nx, ny, dx, dy = 64, 48, 1.0, 1.0
    q0 = (2 * np.pi * 5 / (nx * dx), 2 * np.pi * 3 / (ny * dy))
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    z = np.cos(q0[0] * x + q0[1] * y + 0.4)
    q, C = S.radial_power_spectrum(z, dx, dy, "none")
    dq = q[0]
    ring = int(np.rint(np.hypot(*q0) / dq))
    qx = 2 * np.pi * np.fft.fftfreq(nx, dx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, dy)
    rings = np.rint(np.hypot(qx[None, :], qy[:, None]) / dq).astype(int)
    points = np.count_nonzero(rings == ring)
    dqx, dqy = 2 * np.pi / (nx * dx), 2 * np.pi / (ny * dy)
    assert C[ring - 1] * points * dqx * dqy == pytest.approx(0.5, rel=1e-12)
    others = np.delete(C, ring - 1)
    assert np.nanmax(np.abs(others)) < 1e-12 * C[ring - 1]


def direct_autocorrelation_1d(z, defined, lag):
    i = np.arange(z.size - lag)
    both = defined[i] & defined[i + lag]
    zc = z - z[defined].mean()
    a, b = zc[i[both]], zc[i[both] + lag]
    return np.mean(a * b) / np.mean(zc[defined] ** 2), 0.5 * np.mean((b - a) ** 2)


def test_autocorrelation_over_defined_pairs_equals_the_direct_sums():
    rng = np.random.default_rng(3)
    z = np.cumsum(rng.standard_normal(300))
    defined = rng.random(300) > 0.2
    r, R, A = S.autocorrelation(np.where(defined, z, np.nan), 0.5, defined)
    assert r[0] == 0.5 and r.size == 150
    for lag in (1, 2, 7, 50, 150):
        expected_R, expected_A = direct_autocorrelation_1d(z, defined, lag)
        assert R[lag - 1] == pytest.approx(expected_R, rel=1e-10)
        assert A[lag - 1] == pytest.approx(expected_A, rel=1e-10)


def test_map_autocorrelation_pools_the_pairs_of_each_ring():
    """Ring sums of pair products over the defined pairs, counted directly (1e-10)."""
    rng = np.random.default_rng(5)
    z = S.gaussian_map(24, 1.0, 1.0, 4.0, 2)[:20]
    defined = rng.random(z.shape) > 0.1
    r, R, A = S.autocorrelation(np.where(defined, z, np.nan), (1.0, 1.0), defined)
    zc = np.where(defined, z - z[defined].mean(), 0.0)
    var = np.mean(zc[defined] ** 2)
    ny, nx = z.shape
    sums = {}
    for di in range(-ny + 1, ny):  # every lag of a small map, by hand
        for dj in range(-nx + 1, nx):
            ring = int(np.rint(np.hypot(di, dj)))
            if ring < 1 or ring > r.size:
                continue
            a = (slice(max(0, -di), ny - max(0, di)), slice(max(0, -dj), nx - max(0, dj)))
            b = (slice(max(0, di), ny - max(0, -di)), slice(max(0, dj), nx - max(0, -dj)))
            both = defined[a] & defined[b]
            prod = np.sum((zc[a] * zc[b])[both])
            diff = 0.5 * np.sum(((zc[b] - zc[a]) ** 2)[both])
            n, p, d = sums.get(ring, (0, 0.0, 0.0))
            sums[ring] = (n + both.sum(), p + prod, d + diff)
    for ring, (n, p, d) in sums.items():
        assert R[ring - 1] == pytest.approx(p / n / var, rel=1e-10, abs=1e-12)
        assert A[ring - 1] == pytest.approx(d / n, rel=1e-10)


# --------------------------------------------------------------------------
# height distribution: skewness, kurtosis, bearing-area curve
# --------------------------------------------------------------------------


def test_skewness_kurtosis_and_bearing_curve():
    rng = np.random.default_rng(1)
    z = rng.gamma(4.0, size=5000)
    defined = rng.random(5000) > 0.1
    d = S.height_distribution(np.where(defined, z, np.nan), defined)
    assert d["skewness"] == pytest.approx(stats.skew(z[defined]), rel=1e-12)
    assert d["kurtosis"] == pytest.approx(stats.kurtosis(z[defined], fisher=False), rel=1e-12)
    assert d["rms"] == pytest.approx(np.std(z[defined]), rel=1e-12)
    values = z[defined] - z[defined].mean()
    assert d["bearing_height"][0] == pytest.approx(values.max(), rel=1e-12)
    assert d["bearing_height"][-1] == pytest.approx(values.min(), rel=1e-12)
    half = int(np.flatnonzero(d["material_ratio"] == 0.5)[0])
    assert d["bearing_height"][half] == pytest.approx(np.median(values), rel=1e-12)
    for mr, height in zip(d["material_ratio"][1:-1:10], d["bearing_height"][1:-1:10]):
        assert np.mean(values >= height) == pytest.approx(mr, abs=1.0 / values.size)


def test_heights_at_material_ratios_resolve_the_tail():
    """The bearing-area curve reaches ratios down to 1e-6 (ten a decade below 0.01), and
    `bearing_heights` reads it at any ratio: at the curve's own ratios its heights (1e-12),
    between them monotone; on 10^6 Gaussian heights the height above which a share r lies
    within the sampling scatter of the normal quantile (r = 0.3 ... 1e-4: 2 %); a ratio
    outside (0, 1] or below the curve's smallest is an error."""
    rng = np.random.default_rng(2)
    values = rng.standard_normal(1_000_000)
    d = S.height_distribution(values)
    ratios = d["material_ratio"]
    assert ratios[1] == pytest.approx(1e-6) and np.all(np.diff(ratios) > 0)
    assert np.count_nonzero((ratios > 0) & (ratios < 0.01)) == 40
    inside = ratios[1:-1]
    np.testing.assert_allclose(S.bearing_heights(ratios, d["bearing_height"], inside),
                               d["bearing_height"][1:-1], rtol=1e-12)
    r = np.geomspace(0.3, 1e-4, 11)
    h = S.bearing_heights(ratios, d["bearing_height"], r)
    assert np.all(np.diff(h) > 0)
    np.testing.assert_allclose(h, stats.norm.isf(r) * values.std(), rtol=0.02)
    for bad in (0.0, 1.5, 1e-7):
        with pytest.raises(ValueError, match="material ratio"):
            S.bearing_heights(ratios, d["bearing_height"], [bad])


def load_integral(pdf, h):
    """Greenwood-Williamson's F_3/2(h) = int_h^inf (z - h)^(3/2) f(z) dz, unit-variance heights."""
    return integrate.quad(lambda z: (z - h) ** 1.5 * pdf(z), h, np.inf, limit=200)[0]


def test_gaussian_limits_mark_a_factor_two_in_the_light_load_integral():
    """The module's reason for its limits: at |Sk| = 0.3 and Ku = 4 or 2.5 (gamma, Student-t
    and symmetric beta heights of unit variance), F_3/2 at a separation of 2 sigma is off by
    a factor 1.9 to 2.7 against Gaussian heights."""
    gauss = load_integral(stats.norm.pdf, 2.0)
    k = 4 / S.SKEWNESS_LIMIT**2
    gamma = stats.gamma(k, loc=-np.sqrt(k), scale=1 / np.sqrt(k))
    nu = 4 + 6 / (S.KURTOSIS_RANGE[1] - 3)
    student = stats.t(nu, scale=np.sqrt((nu - 2) / nu))
    a = (6 / (3 - S.KURTOSIS_RANGE[0]) - 3) / 2
    beta = stats.beta(a, a, loc=-0.5 / np.sqrt(stats.beta(a, a).var()), scale=1 / np.sqrt(stats.beta(a, a).var()))
    for dist, sk, ku in ((gamma, 0.3, None), (student, 0.0, 4.0), (beta, 0.0, 2.5)):
        m, v, s, kurt = (float(x) for x in dist.stats(moments="mvsk"))
        assert (m, v) == (pytest.approx(0.0, abs=1e-12), pytest.approx(1.0, rel=1e-12))
        assert s == pytest.approx(sk, abs=1e-12)
        if ku is not None:
            assert kurt + 3 == pytest.approx(ku, rel=1e-12)
    ratios = [load_integral(gamma.pdf, 2.0) / gauss, load_integral(lambda z: gamma.pdf(-z), 2.0) / gauss,
              load_integral(student.pdf, 2.0) / gauss, load_integral(beta.pdf, 2.0) / gauss]
    np.testing.assert_allclose(ratios, [1.92, 0.373, 1.91, 0.382], rtol=0.01)
    assert S.gaussianity(0.29, 3.9)[0] and S.gaussianity(-0.29, 2.6)[0]
    assert not S.gaussianity(0.31, 3.0)[0]
    ok, why = S.gaussianity(-0.1, 4.2)
    assert not ok and "kurtosis 4.2 outside 2.5 ... 4" in why


def test_the_scene_spectrum_section_reaches_the_spectral_estimator():
    """surface.spectrum through the surface stage: `periodic: true` (even beside a window)
    takes the plain periodogram, whose m0, m2, m4 are those of eq. (2.4) to 1e-12; the
    default Hann window and Blackman do not (sigma 8.72 % and 12.46 % high on this record,
    computed once and kept to 5e-4), and the PSD in surface.nc names its window."""
    from asperity.stages.surface import surface_from_data

    z, dx, exact = few_long_waves()
    um = 1e-6
    scale = {"m0": um**2, "m2": 1.0, "m4": um**-2, "sigma": um}

    def spectral(spectrum):
        cfg = {"profile": {"file": "p.txt"}, "form": "none", "spectrum": spectrum}
        ds = surface_from_data(z * um, dx * um, cfg, {"length": "um"})
        return ds.sel(estimator="spectral"), ds["psd"].attrs["long_name"]

    for spectrum in ({"periodic": True}, {"periodic": True, "window": "blackman"}, {"window": "none"}):
        got, name = spectral(spectrum)
        for key in ("m0", "m2", "m4", "sigma"):
            assert float(got[key]) == pytest.approx(exact[key] * scale[key], rel=1e-12), (spectrum, key)
        assert "(none window)" in name
    for spectrum, excess in (({}, 0.0872), ({"window": "blackman"}, 0.1246)):
        got, name = spectral(spectrum)
        assert float(got["sigma"]) / (exact["sigma"] * um) - 1 == pytest.approx(excess, abs=5e-4), spectrum
        assert f"({spectrum.get('window', 'hann')} window)" in name


def test_a_maps_surface_nc_holds_its_radial_psd_and_autocorrelation():
    """surface.nc of a map (the surface stage): the radially averaged PSD (m^4, dim
    `wavenumber`) and the autocorrelation and height-difference autocorrelation (1 and
    m^2, dim `lag`) are those of asperity.surface.spectra on the map's roughness (tested
    above against closed forms; here equal to 1e-12), a plane wave's PSD peaks on the
    ring of its wavenumber, and the correlation length is where the autocorrelation,
    linearly interpolated, first falls to 0.2."""
    from asperity.stages.surface import surface_from_data

    nx, ny, dx, dy = 96, 80, 1e-6, 1e-6
    q0 = 2 * np.pi * 6 / (nx * dx)
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    wave = 1e-7 * np.cos(q0 * x + 0.2)
    z = wave + 1e-8 * S.gaussian_map(96, 1.0, 1.0, 4.0, 2)[:ny]
    cfg = {"map": {"file": "m.npy"}, "form": "none", "spectrum": {"periodic": True}}
    ds = surface_from_data(z, (dx, dy), cfg, {"length": "um"}, defined=np.ones(z.shape, bool))
    q, C = S.radial_power_spectrum(z, dx, dy, "none")
    np.testing.assert_allclose(ds["wavenumber"].values, q, rtol=1e-12)
    np.testing.assert_allclose(ds["psd"].values, C, rtol=1e-12)
    r, R, A = S.autocorrelation(z, (dx, dy), np.ones(z.shape, bool))
    np.testing.assert_allclose(ds["lag"].values, r, rtol=1e-12)
    np.testing.assert_allclose(ds["autocorrelation"].values, R, rtol=1e-12)
    np.testing.assert_allclose(ds["height_difference_autocorrelation"].values, A, rtol=1e-12)
    assert (ds["psd"].attrs["units"], ds["autocorrelation"].attrs["units"],
            ds["height_difference_autocorrelation"].attrs["units"]) == ("m^4", "1", "m^2")
    assert abs(float(ds["wavenumber"][int(np.argmax(ds["psd"].values))]) - q0) <= 0.5 * float(q[0])
    i = int(np.argmax(R <= 0.2))
    expected = r[i - 1] + (R[i - 1] - 0.2) * (r[i] - r[i - 1]) / (R[i - 1] - R[i])
    assert ds.attrs["correlation_length"] == pytest.approx(expected, rel=1e-12)


def test_correlation_length_where_the_autocorrelation_falls_to_its_threshold():
    """R = exp(-r / l) falls to 0.2 at r = l ln 5; linear interpolation on a grid of l / 100
    is within (dr)^2 / 8 |R''| / |R'| = 2e-5 l of it. NaN where R never falls that far,
    the first lag where it already has."""
    from asperity.surface import CORRELATION_THRESHOLD, correlation_length

    ell = 3e-6
    r = np.arange(1, 400) * ell / 100
    assert CORRELATION_THRESHOLD == 0.2
    assert correlation_length(r, np.exp(-r / ell)) == pytest.approx(ell * np.log(5), rel=2e-5)
    assert correlation_length(r, np.exp(-r / ell), 0.5) == pytest.approx(ell * np.log(2), rel=2e-5)
    assert np.isnan(correlation_length(r, np.full(r.size, 0.9)))
    assert correlation_length(r, np.full(r.size, 0.1)) == r[0]
