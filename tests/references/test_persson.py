"""Persson's theory (asperity.references.persson) against closed forms, brute-force quadrature,
its own derivatives and the map's own moments."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate, special

from asperity.references import persson as ps
from asperity.stages.reference import gradient_rms
from asperity.surface.synthetic import gaussian_map

E_STAR = 70e9 / (1 - 0.33**2)  # Pa, the deterministic_reference scene
SIGMA, ELL, DX = 1e-6, 20e-6, 1.25e-6
DI_MAP = Path(__file__).resolve().parents[2] / "data" / "topographies" / "di-3.di"


@pytest.fixture(scope="module")
def scene_map():
    return gaussian_map(512, DX, SIGMA, ELL, 11)


@pytest.fixture(scope="module")
def scene_spectrum(scene_map):
    return ps.isotropic_spectrum(scene_map, DX, DX)


def gaussian_psd(q, sigma=SIGMA, ell=ELL):
    """C(q) of the autocorrelation sigma^2 exp(-r^2/l^2) (Persson's normalization)."""
    return sigma**2 * ell**2 / (4 * np.pi) * np.exp(-(q * ell) ** 2 / 4)


# --- spectrum -----------------------------------------------------------------------------------

@pytest.mark.parametrize("shape, dx, dy, along", [((64, 64), 1e-6, 1e-6, "x"),
                                                   ((32, 96), 2e-6, 0.5e-6, "y")])
def test_sinusoid_spectrum_is_exact(shape, dx, dy, along):
    """z = a cos(2 pi x / lambda), 8 periods across: h_rms = a/sqrt2, h'_rms = a k/sqrt2 (1e-10),
    all power in one node at q = k."""
    ny, nx = shape
    a = 0.3e-6
    if along == "x":
        k = 2 * np.pi * 8 / (nx * dx)
        z = a * np.cos(k * dx * np.arange(nx))[None, :] * np.ones((ny, 1))
    else:
        k = 2 * np.pi * 8 / (ny * dy)
        z = a * np.cos(k * dy * np.arange(ny))[:, None] * np.ones((1, nx))
    q, C = ps.isotropic_spectrum(z, dx, dy)
    m = ps.spectrum_moments(q, C)
    assert m["height_rms"] == pytest.approx(a / math.sqrt(2), rel=1e-10)
    assert m["gradient_rms"] == pytest.approx(a * k / math.sqrt(2), rel=1e-10)
    assert m["curvature_rms"] == pytest.approx(a * k**2 / math.sqrt(2), rel=1e-10)
    W = ps.quadrature_weights(q)
    share = 2 * np.pi * q * C * W
    peak = int(np.argmax(share))
    assert q[peak] == pytest.approx(k, rel=1e-12)
    assert share.sum() - share[peak] < 1e-20 * share[peak]


def test_gaussian_map_moments_and_density(scene_map, scene_spectrum):
    """Moments equal the map's variance and spectral gradient (1e-10); the ring density follows
    the closed form sigma^2 l^2/(4 pi) exp(-q^2 l^2/4) of its autocorrelation, mean ratio over
    the rings 1 <= q l <= 4 within 5 % (a random map: about 1 % expected scatter)."""
    q, C = scene_spectrum
    m = ps.spectrum_moments(q, C)
    assert m["m0"] == pytest.approx(np.var(scene_map), rel=1e-10)
    assert m["gradient_rms"] == pytest.approx(gradient_rms(scene_map, DX, DX), rel=1e-10)
    assert m["m2"] == pytest.approx(m["gradient_rms"] ** 2 / 2, rel=1e-12)
    band = (q * ELL >= 1) & (q * ELL <= 4)
    assert np.mean(C[band] / gaussian_psd(q[band])) == pytest.approx(1.0, abs=0.05)
    # the continuum's h'_rms = 2 sigma / l
    assert m["gradient_rms"] == pytest.approx(2 * SIGMA / ELL, rel=0.02)


def test_hann_window_normalization(scene_map):
    """The windowed density is normalized by the window power: on the 8-period sinusoid
    sum |DFT(w z)|^2 / (N sum w^2) is a^2/2 exactly (w^2 cos^2 orthogonality), 1e-10; on the
    Gaussian map the Hann estimate of sigma and h'_rms is within 10 % (statistical: the window
    halves the effective area; about 5 % scatter over seeds)."""
    n, dx, a = 64, 1e-6, 0.3e-6
    z = a * np.cos(2 * np.pi * 8 * np.arange(n) / n)[None, :] * np.ones((n, 1))
    q, C = ps.isotropic_spectrum(z, dx, dx, window="hann")
    assert ps.spectrum_moments(q, C)["height_rms"] == pytest.approx(a / math.sqrt(2), rel=1e-10)
    q, C = ps.isotropic_spectrum(scene_map, DX, DX, window="hann")
    m = ps.spectrum_moments(q, C)
    assert m["height_rms"] == pytest.approx(SIGMA, rel=0.10)
    assert m["gradient_rms"] == pytest.approx(gradient_rms(scene_map, DX, DX), rel=0.10)


def test_undefined_points_are_set_to_the_mean(scene_map):
    """NaN and defined=False give the spectrum of the map with those points at the mean (1e-12)."""
    z = scene_map[:64, :64].copy()
    holes = np.zeros(z.shape, dtype=bool)
    holes[10:14, 20:30] = True
    filled = np.where(holes, z[~holes].mean(), z)
    q0, C0 = ps.isotropic_spectrum(filled, DX, DX)
    q1, C1 = ps.isotropic_spectrum(np.where(holes, np.nan, z), DX, DX)
    q2, C2 = ps.isotropic_spectrum(z, DX, DX, defined=~holes)
    for q, C in ((q1, C1), (q2, C2)):
        np.testing.assert_allclose(q, q0, rtol=1e-12)
        np.testing.assert_allclose(C, C0, rtol=1e-10, atol=1e-12 * C0.max())


def test_measured_map_gradient_matches_reference():
    """di-3.di, tilt removed: h'_rms of the spectrum equals the reference stage's spectral
    gradient (1e-6), h_rms the map's standard deviation (1e-10)."""
    from asperity.io.topography import read_measurement
    from asperity.surface.form import remove_form

    m = read_measurement(DI_MAP, "map")
    z, _ = remove_form(m.heights, "tilt", defined=m.defined)
    q, C = ps.isotropic_spectrum(z, m.dx, m.dy, defined=m.defined)
    moments = ps.spectrum_moments(q, C)
    assert moments["gradient_rms"] == pytest.approx(gradient_rms(z, m.dx, m.dy), rel=1e-6)
    filled = np.where(m.defined, z, np.nanmean(z[m.defined]))
    assert moments["height_rms"] == pytest.approx(np.std(filled), rel=1e-10)


# --- contact area --------------------------------------------------------------------------------

def test_area_is_linear_at_small_pressure(scene_spectrum):
    """A/A0 -> sqrt(8/pi) p / (E* h'_rms) (Persson 2001), within 1 % where A/A0 < 0.05."""
    q, C = scene_spectrum
    ds = ps.persson_interface(q, C, E_STAR, np.array([2.0, 3.0, 4.0]) * SIGMA)
    grad = ps.spectrum_moments(q, C)["gradient_rms"]
    assert ds.attrs["gradient_rms"] == pytest.approx(grad, rel=1e-12)
    linear = math.sqrt(8 / math.pi) * ds.nominal_pressure.values / (E_STAR * grad)
    assert np.all(ds.contact_area_ratio.values < 0.05)
    np.testing.assert_allclose(ds.contact_area_ratio.values, linear, rtol=0.01)


# --- mean gap ------------------------------------------------------------------------------------

@pytest.mark.parametrize("s", [1e-7, 1e-3, 0.1, 0.5, 1.0, 2.0, 4.0])
def test_gap_function_against_quad(s):
    """F(s) = int_s^inf dt/t [gamma + (1-gamma) erf^2] exp(-t^2) against scipy quad (in ln t), 1e-9."""
    gamma = 0.42

    def integrand(v):
        t = math.exp(v)
        return (gamma + (1 - gamma) * math.erf(t) ** 2) * math.exp(-t * t)

    ref = integrate.quad(integrand, math.log(s), math.log(8.0), epsabs=0, epsrel=1e-13, limit=200)[0]
    assert ps.gap_function(s, gamma) == pytest.approx(ref, rel=1e-9)


def brute_force_gap(p, gamma=0.42, sigma=SIGMA, ell=ELL):
    """u(p) of the continuous Gaussian spectrum: the double integral by nested quad (in ln q and
    ln p'), w(q) from the closed form int_0^q q^3 C dq = 2 sigma^2/(pi l^2) [1 - (1+V) e^-V],
    V = q^2 l^2/4."""

    def w_of(q):
        V = (q * ell) ** 2 / 4
        return 1.0 / math.sqrt(2 * sigma**2 / ell**2 * -math.expm1(-V) - 2 * sigma**2 / ell**2 * V * math.exp(-V))

    def inner(q):
        w = w_of(q)
        s0 = w * p / E_STAR
        if s0 > 8:
            return 0.0
        f = lambda v: (gamma + (1 - gamma) * math.erf(math.exp(v)) ** 2) * math.exp(-math.exp(2 * v))
        return integrate.quad(f, math.log(s0), math.log(8.0), epsabs=0, epsrel=1e-11, limit=200)[0]

    def outer(v):
        q = math.exp(v)
        return q * math.sqrt(math.pi) * q**2 * float(gaussian_psd(q, sigma, ell)) * w_of(q) * inner(q)

    return integrate.quad(outer, math.log(0.05 / ell), math.log(14.0 / ell), epsabs=0,
                          epsrel=1e-9, limit=200)[0]


@pytest.mark.parametrize("p_over", [1e-3, 0.1])
def test_mean_gap_against_brute_force(p_over):
    """u(p) of the module (a uniform grid of 4000 nodes on the continuous Gaussian spectrum)
    against the nested-quad double integral, at p = 1e-3 and 0.1 E* h'_rms: 1e-4."""
    n = 4000
    dq = 14.0 / ELL / n
    q = (np.arange(n) + 0.5) * dq  # cells tile (0, 14/l)
    p = p_over * E_STAR * 2 * SIGMA / ELL
    u, _ = ps.mean_gap(q, gaussian_psd(q), E_STAR, p)
    assert float(u) == pytest.approx(brute_force_gap(p), rel=1e-4)


def test_pressure_decays_exponentially_at_large_gap(scene_spectrum):
    """Where every w_k p/E* < 1e-3, -d ln p / du = 1/u0, u0 = gamma sqrt(pi) int q^2 C w dq
    (Persson 2007), to 1e-5."""
    q, C = scene_spectrum
    a, w, _ = ps._gap_terms(q, C)
    p1 = 1e-3 * E_STAR / w.max()
    p = np.array([p1, p1 / 10.0])
    u, _ = ps.mean_gap(q, C, E_STAR, p)
    u0 = ps.persson_interface(q, C, E_STAR, [u[0]]).attrs["gap_decay_length"]
    assert math.log(10.0) / (u[1] - u[0]) * u0 == pytest.approx(1.0, rel=1e-5)
    # and the inversion finds those pressures, also beyond its tabulated range (p < 1e-40 E*)
    ds = ps.persson_interface(q, C, E_STAR, u)
    np.testing.assert_allclose(np.sort(ds.nominal_pressure.values), np.sort(p), rtol=1e-10)
    far = ps.persson_interface(q, C, E_STAR, [60 * SIGMA]).nominal_pressure.values
    assert 0 < far[0] < 1e-40 * E_STAR
    assert ps.mean_gap(q, C, E_STAR, far)[0][0] == pytest.approx(60 * SIGMA, rel=1e-11)


def test_inversion_and_stiffness(scene_spectrum):
    """p(u) inverts u(p) (1e-11), and the stiffness equals the central difference of the module's
    own p(u) with step 1e-4 u (1e-5)."""
    q, C = scene_spectrum
    u = np.array([0.3, 0.5, 1.0, 2.0, 3.0, 5.0]) * SIGMA
    ds = ps.persson_interface(q, C, E_STAR, u)
    back, _ = ps.mean_gap(q, C, E_STAR, ds.nominal_pressure.values)
    np.testing.assert_allclose(back, u, rtol=1e-11)
    d = 1e-4 * u
    up = ps.persson_interface(q, C, E_STAR, u + d).nominal_pressure.values
    down = ps.persson_interface(q, C, E_STAR, u - d).nominal_pressure.values
    np.testing.assert_allclose(ds.normal_stiffness.values, (down - up) / (2 * d), rtol=1e-5)
    assert np.all(np.diff(ds.nominal_pressure.values) < 0)


def test_dataset_contract(scene_spectrum):
    """Sorted separations, mean gap = separation, NaN count, units and long_name everywhere."""
    q, C = scene_spectrum
    h = np.array([2.0, 0.5, 1.0]) * SIGMA
    ds = ps.persson_interface(q, C, E_STAR, h, hardness=784e6)
    np.testing.assert_array_equal(ds.separation.values, np.sort(h))
    np.testing.assert_array_equal(ds.mean_gap.values, ds.separation.values)
    assert np.all(np.isnan(ds.contact_count.values))
    for name in list(ds.data_vars) + ["separation"]:
        assert set(ds[name].attrs) >= {"units", "long_name"}, name
    assert {"method", "gradient_rms", "contact_modulus", "hardness"} <= set(ds.attrs)
    with pytest.raises(ValueError):
        ps.persson_interface(q, C, E_STAR, [-1e-6])


# --- hardness ------------------------------------------------------------------------------------

def test_infinite_hardness_is_elastic(scene_spectrum):
    """H = 1e12 times the largest pressure: area equals the elastic one to 1e-9, plastic area < 1e-9,
    pressures identical."""
    q, C = scene_spectrum
    h = np.array([0.5, 1.0, 2.0, 3.0]) * SIGMA
    el = ps.persson_interface(q, C, E_STAR, h)
    H = 1e12 * el.nominal_pressure.max().item()
    pl = ps.persson_interface(q, C, E_STAR, h, hardness=H)
    np.testing.assert_allclose(pl.contact_area_ratio, el.contact_area_ratio, rtol=1e-9)
    assert np.all(pl.plastic_area_ratio.values < 1e-9)
    np.testing.assert_array_equal(pl.nominal_pressure, el.nominal_pressure)


@pytest.mark.parametrize("ratio", [0.3, 1.0, 3.0])
def test_images_and_series_agree(ratio):
    """The two solutions of the absorbing-boundary diffusion (images, sine series) agree to 1e-12
    at 2 sqrt(G)/H = 0.3, 1, 3."""
    H = 1e8
    G = (ratio * H / 2) ** 2
    p = np.linspace(0.01, 0.99, 25) * H
    ei, pi_ = ps.elastoplastic_areas(p, G, H, method="images")
    ef, pf = ps.elastoplastic_areas(p, G, H, method="fourier")
    np.testing.assert_allclose(ei, ef, atol=1e-12)
    np.testing.assert_allclose(pi_, pf, atol=1e-12)


@pytest.mark.parametrize("ratio", [0.1, 1.0, 10.0])
def test_hardness_area_bounds(ratio):
    """A/A0 = A_el + A_pl >= p/H everywhere (force balance); A - p/H <= A_el, and A_el -> 0
    linearly as p -> H (A_el(H(1-1e-4)) / A_el(H(1-1e-3)) = 0.1 to 1 %); at 2 sqrt(G)/H = 10
    A/A0 = p/H to 1e-12 (all flowing)."""
    H = 1e8
    G = (ratio * H / 2) ** 2
    p = np.linspace(0.001, 0.999, 200) * H
    el, pl = ps.elastoplastic_areas(p, G, H)
    area = el + pl
    assert np.all(area >= p / H - 1e-14)
    assert np.all(area - p / H <= el + 1e-14)
    assert np.all(area <= 1 + 1e-14)
    e1, _ = ps.elastoplastic_areas(np.array([1 - 1e-3, 1 - 1e-4]) * H, G, H)
    assert e1[1] / e1[0] == pytest.approx(0.1, rel=0.01)
    if ratio >= 10:
        np.testing.assert_allclose(area, p / H, atol=1e-12)
    # the elastic limit of the diffusion: H far above the stresses gives erf
    e_big, p_big = ps.elastoplastic_areas(p, G, 1e6 * H)
    np.testing.assert_allclose(e_big + p_big, special.erf(p / (2 * math.sqrt(G))), rtol=1e-5)
