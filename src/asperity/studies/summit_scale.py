"""Summits of a map, and the routes on it, against the lateral scale (report 2.4.3 at a
stated scale; issue #48, item 1).

:func:`summit_scale_study` finds the summits of one map at each of several
short-wavelength cut-offs lambda_s (:func:`asperity.surface.summits.map_summits`)
and puts their density, mean curvature and mean height beside the spectral
moments of the low-passed map; :func:`summit_scale_figure` draws density and
curvature against lambda_s with the closed forms of an isotropic Gaussian
surface of the same moments:

* summit density D = m4 / (6 pi sqrt(3) m2) (Nayak, ASME J. Lubr. Technol.
  93 (1971) 398; Greenwood, Wear 261 (2006) 191);
* mean curvature of all summits, kappa_m = (kappa_1 + kappa_2)/2,
  E[kappa_m] = (8/3) sqrt(m4 / pi) (Nayak 1971; Greenwood 2006),

with m2, m4 the profile moments of the isotropic equivalent, m2 = (m20 +
m02)/2, m4 = 3 (m40 + 2 m22 + m04)/8 (report 2.3.2), and m_pq = sum over the
discrete Fourier modes of |Z|^2 T^2 kx^p ky^q / N^2 (Parseval; T the
filter's transmission, undefined points filled by the periodic harmonic
in-fill, :func:`asperity.surface.missing.harmonic_fill`).  The summits follow
the closed forms only where the low-passed heights are Gaussian; the pixel
scale (Greenwood and Wu, Wear 249 (2001) 766) shows up as the small-lambda_s
end where density and curvature stop depending on lambda_s.

:func:`scale_study` goes on to contact: on each map at each scale, the elastic boundary
elements and every route of the caller (the interacting route with each asperity law,
Persson's theory), each route's errors against the boundary elements, and the reference's
own resolution (cells per contact patch); :func:`scale_study_figure` draws it.
"""

from __future__ import annotations

import logging
import math

import numpy as np
import xarray as xr

from asperity.surface.filters import ALPHA
from asperity.surface.missing import defined_heights, harmonic_fill
from asperity.surface.summits import lowpass_map, map_summits
from asperity.units import attrs

__all__ = ["lowpassed_moments", "nayak_summits", "scale_study", "scale_study_figure", "summit_scale_study",
           "summit_scale_figure"]

log = logging.getLogger(__name__)


def lowpassed_moments(z, dx: float, dy: float, scale: float, *, defined=None) -> dict[str, float]:
    """Spectral moments m00, m20, m02, m40, m22, m04 of the map low-passed at ``scale``
    (periodic; module text), and the isotropic m0, m2, m4."""
    zz, mask = defined_heights(z, defined, 2, "map")
    if not mask.all():
        zz = harmonic_fill(zz, mask, periodic=True)
    ny, nx = zz.shape
    kx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)
    ky = 2 * np.pi * np.fft.fftfreq(ny, d=dy)
    fx2 = (kx / (2 * np.pi))[None, :] ** 2
    fy2 = (ky / (2 * np.pi))[:, None] ** 2
    gain = np.exp(-np.pi * (ALPHA * scale) ** 2 * (fx2 + fy2))
    power = np.abs(np.fft.fft2(zz - zz.mean()) * gain) ** 2 / (nx * ny) ** 2
    KX, KY = kx[None, :], ky[:, None]
    m = {f"m{p}{q}": float(np.sum(power * KX**p * KY**q))
         for p, q in ((0, 0), (2, 0), (0, 2), (4, 0), (2, 2), (0, 4))}
    m["m0"] = m["m00"]
    m["m2"] = 0.5 * (m["m20"] + m["m02"])
    m["m4"] = 3.0 * (m["m40"] + 2.0 * m["m22"] + m["m04"]) / 8.0
    return m


def nayak_summits(m2: float, m4: float) -> tuple[float, float]:
    """(summit density, mean summit curvature) of an isotropic Gaussian surface:
    m4 / (6 pi sqrt 3 m2) and (8/3) sqrt(m4 / pi) (module text)."""
    return m4 / (6.0 * math.pi * math.sqrt(3.0) * m2), 8.0 / 3.0 * math.sqrt(m4 / math.pi)


def summit_scale_study(z, dx: float, dy: float, scales, *, defined=None, periodic: bool = True) -> xr.Dataset:
    """Summit statistics of one map at each lateral scale (module text).

    Returns a Dataset on dim ``scale`` (lambda_s, m): summit_count,
    summit_density (1/m^2), mean_curvature (1/m), mean_height (m),
    rms_height_lowpassed (m), rms_gradient_lowpassed (1), the isotropic m2
    and m4 of the low-passed map, and the Nayak closed forms
    nayak_density, nayak_curvature.
    """
    lam = np.asarray(scales, dtype=np.float64).ravel()
    names = ("summit_count", "summit_density", "mean_curvature", "mean_height", "rms_height_lowpassed",
             "rms_gradient_lowpassed", "m2", "m4", "nayak_density", "nayak_curvature")
    out = {name: np.full(lam.size, np.nan) for name in names}
    for k, s in enumerate(lam):  # a handful of scales, each vectorized
        ds = map_summits(z, dx, dy, s, defined=defined, periodic=periodic)
        out["summit_count"][k] = ds.sizes["summit"]
        out["summit_density"][k] = ds.attrs["summit_density"]
        if ds.sizes["summit"]:
            out["mean_curvature"][k] = float(ds["curvature"].mean())
            out["mean_height"][k] = float(ds["height"].mean())
        m = lowpassed_moments(z, dx, dy, s, defined=defined)
        out["rms_height_lowpassed"][k] = math.sqrt(m["m0"])
        out["rms_gradient_lowpassed"][k] = math.sqrt(m["m20"] + m["m02"])
        out["m2"][k], out["m4"][k] = m["m2"], m["m4"]
        out["nayak_density"][k], out["nayak_curvature"][k] = nayak_summits(m["m2"], m["m4"])
    meta = {
        "summit_count": ("1", "number of summits"),
        "summit_density": ("1/m^2", "summits per unit area where summits could be found"),
        "mean_curvature": ("1/m", "mean of the summits' mean curvature -(z_xx + z_yy)/2"),
        "mean_height": ("m", "mean summit height above the mean height of the map"),
        "rms_height_lowpassed": ("m", "rms height of the low-passed map, sqrt(m00)"),
        "rms_gradient_lowpassed": ("1", "rms gradient of the low-passed map, sqrt(m20 + m02)"),
        "m2": ("1", "isotropic profile moment m2 = (m20 + m02)/2 of the low-passed map"),
        "m4": ("1/m^2", "isotropic profile moment m4 = 3 (m40 + 2 m22 + m04)/8 of the low-passed map"),
        "nayak_density": ("1/m^2", "summit density of a Gaussian isotropic surface, m4/(6 pi sqrt3 m2)"),
        "nayak_curvature": ("1/m", "mean summit curvature of a Gaussian isotropic surface, (8/3) sqrt(m4/pi)"),
    }
    data = {name: ("scale", out[name], attrs(*meta[name])) for name in names}
    ny, nx = np.shape(z)
    return xr.Dataset(
        data,
        coords={"scale": ("scale", lam, attrs("m", "short-wavelength cut-off lambda_s of the Gaussian low-pass"))},
        attrs={"title": "summits against lateral scale (report 2.4.3)", "spacing_x": float(dx),
               "spacing_y": float(dy), "points_x": int(nx), "points_y": int(ny), "periodic": int(bool(periodic))},
    )


def summit_scale_figure(ds: xr.Dataset):
    """Log-log panels of summit density and mean summit curvature against lambda_s, measured
    (points) and the Gaussian closed forms of the low-passed map (lines)."""
    import asperity.plots  # noqa: F401  (the package's non-interactive backend)
    import matplotlib.pyplot as plt

    lam = ds["scale"].values
    h = max(ds.attrs.get("spacing_x", np.nan), ds.attrs.get("spacing_y", np.nan))
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8), constrained_layout=True)
    for ax, (name, closed, label) in zip(axes, (
            ("summit_density", "nayak_density", "summit density (1/m$^2$)"),
            ("mean_curvature", "nayak_curvature", "mean summit curvature (1/m)"))):
        ax.loglog(lam, ds[name].values, "o-", label="summits (map_summits)")
        ax.loglog(lam, ds[closed].values, "k--", label="Gaussian closed form (Nayak 1971)")
        if np.isfinite(h):
            ax.axvline(h, color="0.6", lw=0.8)
            ax.text(h, ax.get_ylim()[0], " dx", color="0.4", va="bottom", fontsize=8)
        ax.set_xlabel(r"lateral scale $\lambda_s$ (m)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", lw=0.3)
    axes[0].legend(fontsize=8)
    return fig


def _at_scale(z0, dx: float, dy: float, factor: float, h_sigma, bem, routes, errors) -> dict:
    """One map at lambda_s = factor max(dx, dy) (0: the pixel's eight-neighbour peaks of the
    unfiltered map): low-passed and its summits found there as the surface stage does, the
    boundary elements `bem` and each of `routes` at h_sigma sigma of the prepared map, and
    each route's `errors` against them."""
    from asperity.surface.maps import map_peaks

    scale = factor * max(dx, dy)
    if factor > 0:
        z = lowpass_map(z0, dx, dy, scale)
        peaks = map_summits(z0, dx, dy, scale).rename(summit="peak")
    else:
        z = np.array(z0, dtype=float)
        peaks = map_peaks(z, dx, dy)
    peaks = peaks.isel(peak=np.flatnonzero(peaks["curvature"].values > 0))  # as the route does
    z = z - np.nanmean(z)
    sigma = float(np.nanstd(z))
    h = np.asarray(h_sigma) * sigma
    ny, nx = z.shape
    ref = bem(z, dx, dy, h)
    p_ref, a_ref = ref["nominal_pressure"].values, ref["contact_area_ratio"].values
    out = {"scale": scale, "sigma": sigma, "summits": peaks.sizes["peak"],
           "summit_density": peaks.sizes["peak"] / (nx * dx * ny * dy),
           "mean_curvature": float(peaks["curvature"].mean()),
           "bem_area_ratio": a_ref, "cells_per_patch": ref["cells_per_patch"].values, "routes": {}}
    for name, route in routes.items():
        try:
            ds = route(z, dx, dy, peaks, h)
        except (RuntimeError, ValueError) as err:  # a failed route is a row of NaN, said in the log
            log.warning("scale study: %s at %g grid steps failed: %s", name, factor, err)
            continue
        p, a = ds["nominal_pressure"].values, ds["contact_area_ratio"].values
        out["routes"][name] = errors(p, p, a, p_ref, a_ref)
    return out


def scale_study(maps, scales, h_sigma, errors) -> xr.Dataset:
    """Summits, the boundary elements' resolution and every route's errors against them, for
    each map and each lateral scale (in grid steps; 0 the pixel): `maps` is name -> (z, dx,
    dy, bem, routes), z the heights with the form removed and not low-passed, ``bem(z, dx,
    dy, h)`` the reference and ``routes`` name -> ``route(z, dx, dy, peaks, h)``, each an
    interface (nominal_pressure, contact_area_ratio at the separations h); `errors(p, p_curve,
    a_curve, p_ref, a_ref)` the pressure error at equal separation and area error at equal
    pressure (`asperity.stages.reference.errors_against`)."""
    factors = np.asarray(scales, dtype=float)
    h_sigma = np.asarray(h_sigma, dtype=float)
    routes = list(dict.fromkeys(name for *_, r in maps.values() for name in r))
    n_s, n_f, n_h, n_r = len(maps), factors.size, h_sigma.size, len(routes)
    per_scale = {k: np.full((n_s, n_f), np.nan) for k in ("scale", "sigma", "summits", "summit_density",
                                                          "mean_curvature")}
    per_h = {k: np.full((n_s, n_f, n_h), np.nan) for k in ("bem_area_ratio", "cells_per_patch")}
    err = {k: np.full((n_s, n_f, n_r, n_h), np.nan) for k in ("pressure_error", "area_error")}
    for i, (name, (z, dx, dy, bem, map_routes)) in enumerate(maps.items()):  # a few maps and scales
        for j, factor in enumerate(factors):
            log.info("scale study: %s at %g grid steps", name, factor)
            row = _at_scale(z, dx, dy, factor, h_sigma, bem, map_routes, errors)
            for k in per_scale:
                per_scale[k][i, j] = row[k]
            for k in per_h:
                per_h[k][i, j] = row[k]
            for r, route in enumerate(routes):
                if route in row["routes"]:
                    err["pressure_error"][i, j, r], err["area_error"][i, j, r] = row["routes"][route]
    meta = {
        "scale": ("m", "lateral scale lambda_s of the asperities (0: the pixel's peaks, unfiltered)"),
        "sigma": ("m", "rms height of the prepared map"),
        "summits": ("1", "summits with a positive mean curvature"),
        "summit_density": ("1/m^2", "summits per unit area"),
        "mean_curvature": ("1/m", "mean of the summits' mean curvature"),
        "bem_area_ratio": ("1", "real contact area ratio of the elastic boundary elements"),
        "cells_per_patch": ("1", "mean grid cells per contact patch of the elastic boundary elements"),
        "pressure_error": ("1", "route's nominal pressure at equal separation over the boundary elements', less 1"),
        "area_error": ("1", "route's contact area ratio at equal pressure over the boundary elements', less 1"),
    }
    data = {k: (("scene", "factor"), v, attrs(*meta[k])) for k, v in per_scale.items()}
    data |= {k: (("scene", "factor", "separation"), v, attrs(*meta[k])) for k, v in per_h.items()}
    data |= {k: (("scene", "factor", "route", "separation"), v, attrs(*meta[k])) for k, v in err.items()}
    return xr.Dataset(data, coords={
        "scene": ("scene", list(maps), attrs("", "scene whose map is studied")),
        "factor": ("factor", factors, attrs("1", "lateral scale in grid steps, lambda_s / max(dx, dy)")),
        "route": ("route", routes, attrs("", "route against the boundary elements")),
        "separation": ("separation", h_sigma, attrs("1", "separation of the flat over sigma of the prepared map")),
    })


def scale_study_figure(ds: xr.Dataset):
    """The scale study of `asperity.stages.studies.scale_study_dataset`: summit density, mean
    summit curvature and the interacting route's (``shape`` law) largest |pressure error|
    where the boundary elements resolve their patches (10 cells), against the scale in grid
    steps (the pixel's peaks drawn at 1), one line per map."""
    import asperity.plots  # noqa: F401  (the package's non-interactive backend)
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), layout="constrained")
    steps = np.maximum(ds["factor"].values, 1.0)
    for scene in ds["scene"].values:
        d = ds.sel(scene=scene)
        axes[0].loglog(steps, d["summit_density"].values * 1e-12, "o-", label=str(scene))
        axes[1].loglog(steps, d["mean_curvature"].values * 1e-6, "o-", label=str(scene))
        error = abs(d["pressure_error"].sel(route="interacting_shape")).where(d["cells_per_patch"] >= 10)
        axes[2].semilogx(steps, 100 * error.max("separation").values, "o-", label=str(scene))
    xlabel = "lambda_s / grid step (the pixel at 1)"
    axes[0].set(xlabel=xlabel, ylabel="summits per um$^2$")
    axes[1].set(xlabel=xlabel, ylabel="mean summit curvature (1/um)")
    axes[2].set(xlabel=xlabel, ylabel="interacting (shape): largest |p error| (%)")
    axes[0].legend(fontsize=8)
    return fig
