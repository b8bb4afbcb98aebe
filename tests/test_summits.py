"""Summits of a map at a lateral scale (asperity.surface.summits, report 2.4.3)."""

import math

import numpy as np
import pytest

from asperity.studies.summit_scale import nayak_summits, summit_scale_study
from asperity.surface.filters import gaussian_weights, mean_line, transmission
from asperity.surface.maps import map_peaks
from asperity.surface.summits import (default_scale, fit_parameters, lowpass_map, map_summits,
                                      neighbourhood_radius)
from asperity.surface.synthetic import gaussian_map


def _paraboloid(nx=120, ny=100, dx=1.0e-6, dy=1.3e-6, x0=61.37e-6, y0=63.71e-6, z0=2.0e-6,
                r1=40e-6, r2=250e-6, theta=0.6):
    x = dx * np.arange(nx)[None, :]
    y = dy * np.arange(ny)[:, None]
    c, s = math.cos(theta), math.sin(theta)
    u = (x - x0) * c + (y - y0) * s
    v = -(x - x0) * s + (y - y0) * c
    z = z0 - 0.5 * (u * u / r1 + v * v / r2)
    hess = {"z_xx": -(c * c / r1 + s * s / r2), "z_yy": -(s * s / r1 + c * c / r2),
            "z_xy": -c * s * (1 / r1 - 1 / r2)}
    return z, dx, dy, x0, y0, z0, r1, r2, hess


def test_fit_recovers_a_rotated_paraboloid():
    z, dx, dy, x0, y0, z0, r1, r2, hess = _paraboloid()
    scale = 8 * dx
    ds = map_summits(z, dx, dy, scale, periodic=False)
    assert ds.sizes["summit"] == 1
    for name, exact in hess.items():
        assert float(ds[name][0]) == pytest.approx(exact, rel=1e-6)
    assert float(ds["principal_curvature_1"][0]) == pytest.approx(1 / r1, rel=1e-6)
    assert float(ds["principal_curvature_2"][0]) == pytest.approx(1 / r2, rel=1e-6)
    assert float(ds["curvature"][0]) == pytest.approx(0.5 * (1 / r1 + 1 / r2), rel=1e-6)
    assert bool(ds["vertex"][0])
    assert abs(float(ds["x"][0]) - x0) < 1e-9 * dx
    assert abs(float(ds["y"][0]) - y0) < 1e-9 * dy
    # height: z0 less the mean of the map, lowered by the low-pass (discrete kernel second
    # moments S) and the fit's weighted mean (disc weight second moments M): the shifts
    # (z_xx (S_x + M_x) + z_yy (S_y + M_y)) / 2 of a quadratic
    sigma_w, r_fit, pre = fit_parameters(scale, dx, dy)

    def kernel_moment(h):
        w = gaussian_weights(pre, h)
        off = h * (np.arange(w.size) - w.size // 2)
        return float(np.sum(w * off * off))

    ii, jj = np.meshgrid(np.arange(-20, 21), np.arange(-20, 21), indexing="ij")
    u, v = jj * dx, ii * dy
    inside = u * u + v * v <= r_fit * r_fit * (1 + 1e-9)
    w = np.exp(-(u * u + v * v) / (2 * sigma_w**2)) * inside
    mx, my = float(np.sum(w * u * u) / w.sum()), float(np.sum(w * v * v) / w.sum())
    expected = (z0 - z.mean() + 0.5 * (hess["z_xx"] * (kernel_moment(dx) + mx)
                                       + hess["z_yy"] * (kernel_moment(dy) + my)))
    assert abs(float(ds["height"][0]) - expected) < 1e-9 * (z.max() - z.min())
    for var in ds.variables.values():
        assert "units" in var.attrs and "long_name" in var.attrs


def _egg_crate(points_per_wavelength, wavelengths=4, wavelength=10e-6, amplitude=0.1e-6):
    n = wavelengths * points_per_wavelength
    h = wavelength / points_per_wavelength
    k = 2 * np.pi / wavelength
    x = h * np.arange(n)
    return amplitude * np.cos(k * x)[None, :] * np.cos(k * x)[:, None], h, k


def test_lowpass_transmission_of_a_periodic_wave():
    z, h, k = _egg_crate(32)
    scale = 4e-6
    # cos kx cos ky is two waves of wavelength 2 pi / (sqrt 2 k)
    t = float(transmission(2 * np.pi / (math.sqrt(2) * k), scale))
    np.testing.assert_allclose(lowpass_map(z, h, h, scale), t * z, atol=1e-12 * np.abs(z).max())
    # the truncated-kernel filter agrees away from the edges (truncation at +-lambda_s: < 1e-6)
    inner = lowpass_map(z, h, h, scale, periodic=False)[40:-40, 40:-40]
    np.testing.assert_allclose(inner, t * z[40:-40, 40:-40], atol=1e-6 * np.abs(z).max())


@pytest.mark.parametrize("points_per_wavelength", [16, 32, 64])
def test_summit_curvature_does_not_depend_on_sampling(points_per_wavelength):
    wavelength, amplitude = 10e-6, 0.1e-6
    z, h, k = _egg_crate(points_per_wavelength, wavelength=wavelength, amplitude=amplitude)
    scale = wavelength / 2
    ds = map_summits(z, h, h, scale)
    # summits at (m, n) L and ((m + 1/2), (n + 1/2)) L: 2 per wavelength squared
    assert ds.sizes["summit"] == 2 * 4 * 4
    assert ds.attrs["summit_density"] == pytest.approx(2 / wavelength**2, rel=1e-12)
    t = float(transmission(2 * np.pi / (math.sqrt(2) * k), scale))
    exact = amplitude * k * k * t  # -(z_xx + z_yy)/2 of a t cos kx cos ky at its summit
    np.testing.assert_allclose(ds["curvature"].values, exact, rtol=1e-2)
    np.testing.assert_allclose(ds["principal_curvature_1"].values, exact, rtol=1e-2)
    np.testing.assert_allclose(ds["principal_curvature_2"].values, exact, rtol=1e-2)
    np.testing.assert_allclose(ds["height"].values, amplitude * t, rtol=1e-3)


def test_pixel_scale_is_the_eight_neighbour_rule():
    h = 1e-6
    z = gaussian_map(128, h, 1e-6, 2e-6, seed=3)
    peaks = map_peaks(z, h, h)
    n = z.shape[0]
    pk = set(zip(peaks["row"].values.tolist(), peaks["column"].values.tolist()))
    assert len(pk) > 200
    periodic = map_summits(z, h, h, 0.0)
    sp = set(zip(periodic["row"].values.tolist(), periodic["column"].values.tolist()))
    # the same rule away from the edge; the periodic map adds the edge rows and columns
    assert {p for p in sp if 1 <= p[0] <= n - 2 and 1 <= p[1] <= n - 2} == pk
    cut = map_summits(z, h, h, 0.0, periodic=False)
    reach = int(math.floor(fit_parameters(0.0, h, h)[1] / h))
    sc = set(zip(cut["row"].values.tolist(), cut["column"].values.tolist()))
    assert sc == {p for p in pk if reach <= p[0] <= n - 1 - reach and reach <= p[1] <= n - 1 - reach}
    assert cut.attrs["area"] == pytest.approx((n - 2 * reach) ** 2 * h * h)
    # densities: the pixel-scale peaks' count within edge effects (Poisson: 3 / sqrt(count))
    density = float(peaks.sizes["peak"]) / ((n - 2) * h) ** 2
    assert periodic.attrs["summit_density"] == pytest.approx(density, rel=3 / math.sqrt(len(pk)))


@pytest.mark.parametrize("periodic", [False, True])
def test_no_summit_touches_a_hole(periodic):
    h = 1e-6
    z = gaussian_map(128, h, 1e-6, 4e-6, seed=5)
    scale = 8 * h
    rows, cols = np.indices(z.shape)
    hole = (rows - 60) ** 2 + (cols - 70) ** 2 <= 12**2
    ds = map_summits(np.where(hole, np.nan, z), h, h, scale, defined=~hole, periodic=periodic)
    full = map_summits(z, h, h, scale, periodic=periodic)
    reach = max(neighbourhood_radius(scale, h, h), ds.attrs["fit_radius"])
    hr, hc = np.nonzero(hole)
    d2 = ((ds["row"].values[:, None] - hr[None, :]) ** 2 + (ds["column"].values[:, None] - hc[None, :]) ** 2) * h * h
    assert d2.min() > reach**2
    # where the hole is out of reach of the low-pass (lambda_s) and the disc, nothing changes
    far = lambda d: (np.sqrt(((d["row"].values - 60) ** 2 + (d["column"].values - 70) ** 2)) * h
                     > 12 * h + scale + reach)
    a = set(zip(full["row"].values[far(full)].tolist(), full["column"].values[far(full)].tolist()))
    b = set(zip(ds["row"].values[far(ds)].tolist(), ds["column"].values[far(ds)].tolist()))
    assert a == b and len(a) > 20
    assert full.sizes["summit"] > ds.sizes["summit"]
    # the area where summits can be found loses at least the hole grown by the disc's reach
    lost = np.count_nonzero((rows - 60) ** 2 + (cols - 70) ** 2 <= (12 + math.floor(reach / h)) ** 2) * h * h
    assert full.attrs["area"] - ds.attrs["area"] >= lost


def test_gaussian_map_follows_nayak():
    h = 1e-6
    z = gaussian_map(256, h, 1e-6, 4e-6, seed=7)
    ds = summit_scale_study(z, h, h, [8 * h, 12 * h])
    assert ds.sizes["scale"] == 2
    for var in ds.variables.values():
        assert "units" in var.attrs and "long_name" in var.attrs
    # Gaussian isotropic surface: density m4/(6 pi sqrt3 m2), mean curvature (8/3) sqrt(m4/pi);
    # tolerance 3 / sqrt(count) (Poisson) on the density, 10 % on the curvature
    count = ds["summit_count"].values
    assert np.all(count > 300)
    np.testing.assert_array_less(np.abs(ds["summit_density"] / ds["nayak_density"] - 1), 3 / np.sqrt(count))
    np.testing.assert_array_less(np.abs(ds["mean_curvature"] / ds["nayak_curvature"] - 1), 0.1)
    d, c = nayak_summits(2.0, 3.0)
    assert d == pytest.approx(3.0 / (6 * math.pi * math.sqrt(3) * 2.0))
    assert c == pytest.approx(8 / 3 * math.sqrt(3.0 / math.pi))


def test_default_scale():
    h = 1e-6
    scale, text = default_scale(h, 0.5 * h)
    assert scale == pytest.approx(8 * h) and "8" in text
    # a rough map keeps 8 h; a map with few summits at 8 h goes down by sqrt(N/200), not below 5 h
    rough = gaussian_map(192, h, 1e-6, 3e-6, seed=2)
    assert default_scale(h, h, rough)[0] == pytest.approx(8 * h)
    smooth = gaussian_map(64, h, 1e-6, 6e-6, seed=2)
    n8 = map_summits(smooth, h, h, 8 * h).sizes["summit"]
    assert n8 < 200
    scale, text = default_scale(h, h, smooth)
    assert scale == pytest.approx(max(5 * h, 8 * h * math.sqrt(n8 / 200)))
    assert "fewer than 200" in text or map_summits(smooth, h, h, scale).sizes["summit"] >= 200


def test_mean_line_agrees_with_truncated_lowpass():
    z, h, _ = _egg_crate(16)
    np.testing.assert_array_equal(lowpass_map(z, h, h, 3e-6, periodic=False), mean_line(z, 3e-6, (h, h)))


def test_summit_scale_figure():
    from asperity.studies.summit_scale import summit_scale_figure

    h = 1e-6
    ds = summit_scale_study(gaussian_map(64, h, 1e-6, 2e-6, seed=1), h, h, [4 * h, 8 * h])
    fig = summit_scale_figure(ds)
    assert len(fig.axes) == 2
    for ax in fig.axes:
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        np.testing.assert_allclose(ax.lines[0].get_xdata(), ds["scale"].values)
