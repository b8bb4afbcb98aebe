"""Form removal and the Gaussian filters of ISO 16610-21/-61 (asperity.surface.form, .filters).

Tolerances are stated next to each assert, with where they come from.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from asperity import surface as S
from asperity.scene.surface import SurfaceScene
from asperity.surface.prepare import prepare

UM = 1e-6


def series_profile(n=4000, dx=0.5 * UM, seed=4):
    """A random-phase profile, 1 um rms, x in metres."""
    C, k, e = S.quasirandom_series(n=30, seed=seed, period=n * 0.5, k_range=(0.05, 1.2), sigma=1.0)
    s = np.arange(n) * 0.5
    return S.evaluate_series(s, C, k, e) * UM, dx


def series_map(n=96, seed=5):
    return S.gaussian_map(n, 1.0, 1.0, 6.0, seed) * UM, (0.5 * UM, 0.7 * UM)


def untilted(z, degree):
    """z less its own least-squares polynomial: a surface with no form of that degree."""
    return z - S.fit_form(z, degree)


def added_form(shape, degree, spacing):
    """A large tilt (1 %, far above the 1 um roughness) plus, for degree 2, a bend."""
    if len(shape) == 1:
        x = np.arange(shape[0]) * spacing
        form = 3e-4 + 0.01 * x
        if degree == 2:
            form = form + 40.0 * (x - x.mean()) ** 2
        return form
    dx, dy = spacing
    y, x = np.meshgrid(np.arange(shape[0]) * dy, np.arange(shape[1]) * dx, indexing="ij")
    form = 3e-4 + 0.01 * x - 0.02 * y
    if degree == 2:
        form = form + 40.0 * (x - x.mean()) ** 2 - 25.0 * (x - x.mean()) * (y - y.mean()) + 30.0 * y**2
    return form


@pytest.mark.parametrize("degree, kind", [(1, "tilt"), (2, "polynomial")])
def test_form_removal_returns_the_untilted_profile_statistics(degree, kind):
    z, dx = series_profile()
    z0 = untilted(z, degree)
    form = added_form(z.shape, degree, dx)
    assert np.std(form) > 5 * np.std(z0)  # the form dwarfs the roughness, as on real files
    residual, removed = S.remove_form(z0 + form, kind, degree)
    # round-off of heights ~1e-5 m (the form) against a 1e-6 m roughness: 1e-10 relative is ample
    np.testing.assert_allclose(residual, z0, rtol=0, atol=1e-10 * np.std(z0))
    got = S.profile_statistics(residual, dx)
    ref = S.profile_statistics(z0, dx)
    for name in ("sigma", "sigma_slope", "sigma_curvature", "peak_density", "beta"):
        np.testing.assert_allclose(got[name].values, ref[name].values, rtol=1e-10, err_msg=name)


@pytest.mark.parametrize("degree, kind", [(1, "tilt"), (2, "polynomial")])
def test_form_removal_returns_the_untilted_map_statistics_and_peaks(degree, kind):
    z, (dx, dy) = series_map()
    z0 = untilted(z, degree)
    residual, _ = S.remove_form(z0 + added_form(z.shape, degree, (dx, dy)), kind, degree)
    np.testing.assert_allclose(residual, z0, rtol=0, atol=1e-10 * np.std(z0))
    got, ref = S.map_statistics(residual, dx, dy), S.map_statistics(z0, dx, dy)
    for name in ("sigma", "sigma_slope_x", "sigma_slope_y", "sigma_curvature_x", "m22", "peak_density"):
        assert float(got[name]) == pytest.approx(float(ref[name]), rel=1e-10), name
    peaks, ref_peaks = S.map_peaks(residual, dx, dy), S.map_peaks(z0, dx, dy)
    np.testing.assert_array_equal(peaks["row"], ref_peaks["row"])
    np.testing.assert_allclose(peaks["curvature"], ref_peaks["curvature"], rtol=1e-8)


def test_a_one_percent_tilt_ruins_mean_only_statistics():
    """The issue's example: 1 % tilt on a 1 um rms profile; the mean alone leaves sigma
    several times too large, the tilt removal recovers it."""
    z, dx = series_profile(n=20000)
    z0 = untilted(z, 1)
    tilted = z0 + 0.01 * np.arange(z.size) * dx
    mean_only = S.profile_statistics(S.remove_form(tilted, "mean")[0], dx)
    tilt = S.profile_statistics(S.remove_form(tilted, "tilt")[0], dx)
    sigma0 = float(np.std(z0, ddof=1))
    assert float(mean_only["sigma"].sel(estimator="sampling")) > 2 * sigma0
    assert float(tilt["sigma"].sel(estimator="sampling")) == pytest.approx(sigma0, rel=1e-10)


def test_form_is_the_least_squares_polynomial_over_the_defined_points():
    """Against numpy's least squares on the defined points alone, monomial basis."""
    rng = np.random.default_rng(1)
    z = rng.standard_normal((30, 41))
    defined = rng.random(z.shape) > 0.3
    defined[:, :5] = False
    form = S.fit_form(np.where(defined, z, np.nan), 2, defined)
    y, x = np.meshgrid(np.arange(30.0), np.arange(41.0), indexing="ij")
    terms = [x**a * y**b for b in range(3) for a in range(3) if a + b <= 2]
    A = np.column_stack([t[defined] for t in terms])
    coef = np.linalg.lstsq(A, z[defined], rcond=None)[0]
    expected = sum(c * t for c, t in zip(coef, terms))
    np.testing.assert_allclose(form, expected, rtol=0, atol=1e-11)  # O(1) values, conditioning ~1e3
    profile = z[3]
    np.testing.assert_allclose(S.fit_form(profile, 3),
                               np.polyval(np.polyfit(np.arange(41.0), profile, 3), np.arange(41.0)),
                               rtol=0, atol=1e-12)


def test_form_kinds_and_degrees():
    z = np.arange(10.0) ** 2
    assert np.array_equal(S.remove_form(z, "none")[0], z)
    assert abs(S.remove_form(z, "mean")[0].mean()) < 1e-12
    with pytest.raises(ValueError, match="needs a degree"):
        S.remove_form(z, "polynomial")
    with pytest.raises(ValueError, match="form must be one of"):
        S.remove_form(z, "plane")


# --------------------------------------------------------------------------
# Gaussian filters (ISO 16610-21, -61)
# --------------------------------------------------------------------------


def amplitude(signal, phase):
    """Least-squares amplitude of cos/sin of `phase` in `signal`."""
    A = np.column_stack([np.cos(phase), np.sin(phase)])
    c = np.linalg.lstsq(A, signal, rcond=None)[0]
    return float(np.hypot(*c))


@pytest.mark.parametrize("ratio", [0.25, 0.5, 1.0, 2.0, 4.0])
def test_gaussian_profile_filter_transmission_is_the_closed_form(ratio):
    """Mean line of a sine of wavelength lambda: exp(-pi (alpha lambda_c / lambda)^2), 50 % at
    lambda_c. Where the whole truncated kernel (+-lambda_c) lies in the record, the discrete
    weights (lambda_c / dx = 160) differ from the continuous Gaussian by at most 1.6e-7 in
    transmission; bound 1e-6. Over the ISO evaluation region (lambda_c / 2 from the ends,
    where the normalized kernel is cut) the mean amplitude is within 2e-5; bound 1e-4."""
    cutoff, dx = 0.8e-3, 5e-6
    wavelength = ratio * cutoff
    x = np.arange(8000) * dx
    phase = 2 * np.pi * x / wavelength
    z = np.cos(phase + 0.3)
    rough, wav, region = S.filter_heights(z, dx, lambda_c=cutoff)
    whole = slice(160, 8000 - 160)
    got = amplitude(wav[whole], phase[whole])
    assert got == pytest.approx(float(S.transmission(wavelength, cutoff)), abs=1e-6)
    assert amplitude(rough[whole], phase[whole]) == pytest.approx(1 - got, abs=1e-6)
    assert amplitude(wav[region], phase[region]) == pytest.approx(got, abs=1e-4)
    if ratio == 1.0:
        assert got == pytest.approx(0.5, abs=1e-6)


@pytest.mark.parametrize("direction", [0.0, 90.0, 45.0, 30.0])
def test_areal_filter_passes_half_of_a_wave_of_the_cutoff_wavelength_in_any_direction(direction):
    """ISO 16610-61 is the product of the profile filters: its transmission depends on the
    wavelength only (isotropy), 50 % at lambda_c, where the whole kernel lies in the map.
    Bound 1e-6 (the sampled weights, lambda_c / dx = 20, are within 1e-7)."""
    cutoff, dx, dy = 40.0, 2.0, 2.0
    ny, nx = 160, 180
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    t = np.radians(direction)
    phase = 2 * np.pi * (x * np.cos(t) + y * np.sin(t)) / cutoff
    rough, wav, region = S.filter_heights(np.cos(phase), (dx, dy), lambda_c=cutoff)
    whole = (slice(20, ny - 20), slice(20, nx - 20))
    assert amplitude(wav[whole].ravel(), phase[whole].ravel()) == pytest.approx(0.5, abs=1e-6)



@pytest.mark.parametrize("ratio", [0.5, 0.75, 1.5, 2.0, 4.0])
@pytest.mark.parametrize("direction", [0.0, 30.0, 45.0])
def test_areal_filter_transmission_is_the_closed_form(ratio, direction):
    """ISO 16610-61 passes a plane wave of any wavelength in any direction with the profile
    filter's exp(-pi (alpha lambda_c / lambda)^2), where the whole kernel lies in the map;
    bound 1e-6 as above (the sampled weights give at most 1.3e-7 here)."""
    cutoff, dx, dy = 40.0, 2.0, 2.0
    ny, nx = 160, 180
    y, x = np.meshgrid(np.arange(ny) * dy, np.arange(nx) * dx, indexing="ij")
    t, wavelength = np.radians(direction), ratio * cutoff
    phase = 2 * np.pi * (x * np.cos(t) + y * np.sin(t)) / wavelength
    rough, wav, region = S.filter_heights(np.cos(phase), (dx, dy), lambda_c=cutoff)
    whole = (slice(20, ny - 20), slice(20, nx - 20))
    got = amplitude(wav[whole].ravel(), phase[whole].ravel())
    assert got == pytest.approx(math.exp(-math.pi * (math.sqrt(math.log(2) / math.pi) / ratio) ** 2), abs=1e-6)
    assert amplitude(rough[whole].ravel(), phase[whole].ravel()) == pytest.approx(1 - got, abs=1e-6)

def test_mean_line_over_undefined_points_is_the_normalized_weighted_average():
    """At a defined point next to a gap, the mean line is sum w h / sum w over the defined
    neighbours within the kernel: summed directly here (1e-12)."""
    rng = np.random.default_rng(2)
    dx, cutoff = 1.0, 12.0
    z = rng.standard_normal(200)
    defined = np.ones(200, bool)
    defined[80:95] = False
    defined[3] = False
    line = S.mean_line(np.where(defined, z, np.nan), cutoff, dx, defined)
    w = S.gaussian_weights(cutoff, dx)
    half = w.size // 2
    for i in (0, 2, 4, 79, 95, 150, 199):  # a few points, each summed by hand
        idx = np.arange(i - half, i + half + 1)
        ok = (idx >= 0) & (idx < 200)
        ok[ok] &= defined[idx[ok]]
        expected = np.sum(w[ok] * z[idx[ok]]) / np.sum(w[ok])
        assert line[i] == pytest.approx(expected, abs=1e-12), i


def test_roughness_and_waviness_add_up_to_the_heights():
    z, dx = series_profile(n=3000)
    rough, wav, region = S.filter_heights(z, dx, lambda_c=100 * dx)
    np.testing.assert_allclose(rough + wav, z, rtol=0, atol=1e-20)
    assert region[0] == slice(50, 2950)  # lambda_c / 2 = 50 points dropped at each end


def test_lambda_s_removes_short_waves():
    """A wave at lambda_s keeps 50 % in the roughness between lambda_s and lambda_c, and a
    wave well inside the band keeps all (within 1e-6)."""
    dx, lc, ls = 1.0, 400.0, 8.0
    x = np.arange(6000) * dx
    band = np.cos(2 * np.pi * x / 40.0)
    short = np.cos(2 * np.pi * x / ls)
    rough, _, region = S.filter_heights(band + short, dx, lambda_c=lc, lambda_s=ls)
    r = rough[region]
    assert amplitude(r, 2 * np.pi * x[region] / ls) == pytest.approx(0.5, abs=1e-5)
    expected_band = (1 - float(S.transmission(40.0, lc))) * float(S.transmission(40.0, ls))
    assert amplitude(r, 2 * np.pi * x[region] / 40.0) == pytest.approx(expected_band, abs=1e-5)
    with pytest.raises(ValueError, match="lambda_s .* must be shorter"):
        S.filter_heights(band, dx, lambda_c=ls, lambda_s=lc)


def test_profile_too_short_after_filtering_is_a_clear_error():
    z, dx = series_profile(n=400)
    scene = SurfaceScene.from_config({"profile": {"file": "p.txt"}, "form": "tilt",
                                      "filter": {"lambda_c": 150.0}}, {"length": "um"})
    with pytest.raises(ValueError, match=r"profile too short after filtering: 400 points .*surface.filter"):
        prepare(z, dx, scene)
    fits = SurfaceScene.from_config({"profile": {"file": "p.txt"}, "filter": {"lambda_c": 50.0}},
                                    {"length": "um"})
    prep = prepare(z, dx, fits)  # 200 - 100 points dropped: 300 left, 150 um > lambda_c
    assert prep.region == (slice(50, 350),)
    assert math.isnan(prep.roughness[10]) and np.isfinite(prep.roughness[200])
