"""Figures of a scene's surface, drawn from surface.nc alone (report 2.3, 2.4.3, 2.6.1).

* :func:`surface_figure` -- a profile: the heights as read with the removed
  form, the roughness, the statistics by estimator (against the exact ones
  of a synthetic profile, Figs. 2.11, 2.12), their convergence with the
  spacing, the power spectrum and the bearing-area curve;
* :func:`map_figure` -- a map: raw heights, removed form, roughness with its
  eight-neighbour peaks (Fig. 2.8), their sampled joint density (Fig. 2.9),
  the radially averaged power spectrum, the height-difference
  autocorrelation and the bearing-area curve;
* :func:`directional_figure` -- profiles in several directions (2.3.2).

Files hold SI; the figures show the scene's length unit.  A surface whose
heights are not Gaussian gets a note in red.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from scipy.special import ndtri

from asperity import units
from asperity.plots.layout import fit, subplots

__all__ = ["ESTIMATOR_STYLE", "MAX_PEAK_MARKERS", "surface_figure", "map_figure", "directional_figure",
           "robust_limits", "shown_peaks"]

#: at most this many peaks are marked on a map (the highest: they touch first)
MAX_PEAK_MARKERS = 200

ESTIMATOR_STYLE = {
    "sampling": dict(color="C0", marker="o"),
    "counting": dict(color="C1", marker="s"),
    "spectral": dict(color="C2", marker="^"),
    "exact": dict(color="k", marker="*"),
    "given": dict(color="k", marker="*"),
}


def _gaussian_note(fig: plt.Figure, surface: xr.Dataset):
    verdict = surface.attrs.get("gaussian")
    if verdict and verdict != "yes":
        fig.suptitle(f"heights not Gaussian ({verdict[4:]}; limits {surface.attrs['gaussian_limits']}): "
                     "Nayak and Greenwood-Williamson densities do not apply", color="C3", fontsize=9)


def _bearing(ax, surface: xr.Dataset, scale: float, length_unit: str):
    """The bearing-area curve against that of Gaussian heights of the same rms."""
    mr = surface["material_ratio"].values
    ax.plot(100 * mr, surface["bearing_height"].values / scale, "C0", label="measured")
    inner = (mr > 0) & (mr < 1)
    rq = float(surface["rms_height"])
    ax.plot(100 * mr[inner], rq * ndtri(1 - mr[inner]) / scale, "k--", lw=0.8, label="Gaussian, same Rq")
    ax.set(xlabel="material ratio [%]", ylabel=f"height [{length_unit}]",
           title=f"bearing-area curve (skewness {float(surface['skewness']):.2f}, "
                 f"kurtosis {float(surface['kurtosis']):.2f})")
    ax.legend(fontsize=8)


def _loglog(ax, x, y, xlabel, ylabel, title, **style):
    ok = np.isfinite(y) & (y > 0) & (x > 0)
    ax.loglog(x[ok], y[ok], **style)
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
    ax.grid(True, which="both", alpha=0.3)


def _estimators(ax, surface: xr.Dataset):
    names = ["sigma", "sigma_slope", "sigma_curvature", "beta", "peak_density"]
    names = [n for n in names if n in surface]
    reference = "exact" if "exact" in surface["estimator"].values else None
    base = reference or str(surface["estimator"].values[0])
    ref = np.array([float(surface[n].sel(estimator=base)) for n in names])
    for estimator in surface["estimator"].values:
        if reference and estimator == reference:
            continue
        vals = np.array([float(surface[n].sel(estimator=estimator)) for n in names])
        y = 100 * np.abs(vals / ref - 1) if reference else vals / ref
        ax.plot(range(len(names)), y, ls="none", label=str(estimator),
                **ESTIMATOR_STYLE.get(str(estimator), {}))
    ax.set_xticks(range(len(names)), [n.replace("sigma_", "σ ") for n in names], rotation=30)
    if reference:
        ax.set_yscale("log")
        ax.set_ylabel("error against exact [%]")
        ax.axhline(0.1, color="r", lw=0.8, ls="--", label="0.1 %")
        ax.set_title("statistics by estimator")
    else:
        ax.set_ylabel(f"estimate / {base} estimate")
        ax.set_title("statistics by estimator")
    ax.legend(fontsize=8)


def surface_figure(surface: xr.Dataset, convergence: xr.Dataset | None = None,
                   length_unit: str = "m") -> plt.Figure:
    """A profile's surface.nc: heights and form, roughness, estimators, convergence, PSD, bearing curve."""
    scale = units.length_scale(length_unit)
    if "estimator" not in surface.dims:  # statistics given in the scene
        fig, ax = subplots(figsize=(5.2, 4.0))
        text = "\n".join(f"{n} = {float(surface[n]):.6g} {surface[n].attrs['units']}"
                         for n in surface.data_vars if surface[n].ndim == 0)
        ax.text(0.05, 0.5, text, transform=ax.transAxes, va="center", family="monospace")
        ax.set_axis_off()
        return fit(fig)
    measured = "raw_height" in surface
    removed = measured and (surface.attrs.get("form_removed", "none") != "none"
                            or surface.attrs.get("filter", "none") != "none")
    panels = ["heights"] if measured else []
    panels += ["roughness"] if removed else []
    panels += ["estimators"] + (["convergence"] if convergence is not None else [])
    panels += ["psd", "bearing"] if measured else []
    cols = min(3, len(panels))
    rows = -(-len(panels) // cols)
    fig, axes = subplots(rows, cols, figsize=(5.2 * cols, 4.0 * rows), squeeze=False)
    axes = list(axes.ravel())
    for ax in axes[len(panels):]:
        ax.set_axis_off()
    for name, ax in zip(panels, axes):
        if name == "heights":
            x = surface["position"].values / scale
            n = x.size if removed else min(x.size, 1000)
            ax.plot(x[:n], surface["raw_height"].values[:n] / scale, lw=0.6, color="0.4", label="as read")
            if removed:
                ax.plot(x, surface["form_height"].values / scale, "C3", lw=1.2,
                        label=f"removed: {surface.attrs['form_removed']}")
                title = (f"heights: rms {float(surface['rms_height_raw']) / scale:.4g} {length_unit} "
                         f"(mean removed)")
            else:
                title = f"profile, first {x[n - 1]:.4g} of {x[-1]:.4g} {length_unit}"
            ax.set(xlabel=f"position [{length_unit}]", ylabel=f"height [{length_unit}]", title=title)
            ax.legend(fontsize=7)
        elif name == "roughness":
            ax.plot(surface["position"].values / scale, surface["roughness_height"].values / scale, lw=0.6)
            cutoffs = surface.attrs.get("filter", "none").partition("), ")[2] or "no filter"
            ax.set(xlabel=f"position [{length_unit}]", ylabel=f"height [{length_unit}]",
                   title=f"roughness: rms {float(surface['rms_height']) / scale:.4g} {length_unit} ({cutoffs})")
        elif name == "estimators":
            _estimators(ax, surface)
        elif name == "convergence":
            h = convergence["spacing"].values / scale
            for quantity, color in (("sigma", "C0"), ("sigma_slope", "C1"), ("sigma_curvature", "C2")):
                for estimator, ls in (("sampling", "-"), ("counting", "--")):
                    ax.loglog(h, convergence[f"{quantity}_error"].sel(estimator=estimator), ls=ls, color=color,
                              marker="o", label=f"{quantity} ({estimator})")
            ax.set(xlabel=f"sampling interval [{length_unit}]", ylabel="relative error against series",
                   title="convergence with the sampling interval")
            ax.legend(fontsize=7)
        elif name == "psd":
            _loglog(ax, surface["wavenumber"].values * scale, surface["psd"].values / scale**3,
                    f"wavenumber [rad/{length_unit}]", f"PSD [{length_unit}^3]", "power spectral density")
        elif name == "bearing":
            _bearing(ax, surface, scale, length_unit)
    _gaussian_note(fig, surface)
    return fit(fig)


def robust_limits(values: np.ndarray, percentiles: tuple[float, float] = (1.0, 99.0)
                  ) -> tuple[float, float]:
    """Colour limits symmetric about the mean m of the finite `values`, out to the
    farther of their `percentiles` (default 1st and 99th): m -+ max(|P1 - m|, |P99 - m|).
    A few spikes or pits of a measured map then do not set the scale, and the
    roughness shows."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if not v.size:
        return (-1.0, 1.0)
    mean = float(v.mean())
    lo, hi = np.percentile(v, percentiles)
    half = max(abs(float(lo) - mean), abs(float(hi) - mean)) or max(abs(mean), 1.0)
    return (mean - half, mean + half)


def shown_peaks(height: np.ndarray, count: int = MAX_PEAK_MARKERS) -> np.ndarray:
    """Indices of the `count` highest peaks (all if fewer), highest last."""
    height = np.asarray(height, float)
    if height.size <= count:
        return np.argsort(height)
    top = np.argpartition(height, height.size - count)[height.size - count:]
    return top[np.argsort(height[top])]


def _image(fig, ax, surface, name, scale, length_unit, title, cmap="terrain", robust=False,
           label="height"):
    """`surface[name]` as an image in the length unit, with a colour bar; `robust`:
    colour limits from `robust_limits` (values beyond drawn in the end colours)."""
    x, y = surface["map_x"].values / scale, surface["map_y"].values / scale
    values = surface[name].values / scale
    dx = (x[1] - x[0]) if x.size > 1 else 1.0
    dy = (y[1] - y[0]) if y.size > 1 else 1.0
    vmin, vmax = robust_limits(values) if robust else (None, None)
    im = ax.imshow(np.ma.masked_invalid(values), origin="lower", cmap=cmap, vmin=vmin, vmax=vmax,
                   extent=(x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2))
    fig.colorbar(im, ax=ax, label=f"{label} [{length_unit}]", extend="both" if robust else "neither")
    ax.set(xlabel=f"x [{length_unit}]", ylabel=f"y [{length_unit}]", title=title)


def _density_panel(fig, ax, h: np.ndarray, k: np.ndarray, bins: tuple[int, int], length_unit: str,
                   title: str, tails: float = 0.5) -> None:
    """The sampled joint density of peak height and curvature (Fig. 2.9): counts on a
    `bins` grid over the `tails`-th to (100 - `tails`)-th percentile of each, divided
    by the number of all peaks and the cell area (so the few peaks outside, e.g. of
    spikes, do not squeeze the rest into one cell, and the density keeps its scale)."""
    if not h.size:
        ax.set(title=title)
        return
    ranges = [np.percentile(v, [tails, 100.0 - tails]) for v in (h, k)]
    ranges = [(lo, hi) if hi > lo else (lo - 0.5, hi + 0.5) for lo, hi in ranges]
    counts, ze, ke = np.histogram2d(h, k, bins=bins, range=ranges)
    f = counts / (h.size * np.diff(ze)[:, None] * np.diff(ke)[None, :])
    mesh = ax.pcolormesh(ze, ke, f.T, cmap="Blues")
    fig.colorbar(mesh, ax=ax, label=f"sampled f(z_p, κ) [1/({length_unit}·1/{length_unit})]")
    inside = (h >= ranges[0][0]) & (h <= ranges[0][1]) & (k >= ranges[1][0]) & (k <= ranges[1][1])
    ax.plot(h[inside], k[inside], "k.", ms=1, alpha=0.4)
    ax.set(xlim=ranges[0], ylim=ranges[1], xlabel=f"peak height z_p [{length_unit}]",
           ylabel=f"mean curvature κ [1/{length_unit}]",
           title=title + (f"; {h.size - int(inside.sum())} beyond the {tails:g}-{100 - tails:g}th "
                          "percentiles not drawn" if not inside.all() else ""))


def map_figure(surface: xr.Dataset, length_unit: str = "m", bins: tuple[int, int] = (20, 20)) -> plt.Figure:
    """A map's surface.nc: raw, form, roughness with peaks (Fig. 2.8), sampled joint density
    of peaks (Fig. 2.9), radially averaged PSD, height-difference autocorrelation (log-log),
    bearing-area curve.

    The heights as read and the roughness are coloured on robust limits (`robust_limits`:
    1st to 99th percentile, symmetric about the mean), the roughness on a diverging map;
    on it the `MAX_PEAK_MARKERS` highest peaks are marked by small hollow circles."""
    scale = units.length_scale(length_unit)
    # "compressed": the constrained layout that packs a grid of fixed-aspect images
    fig, axes = subplots(2, 4, figsize=(22, 10), layout="compressed")
    fig.get_layout_engine().set(w_pad=6 / 72)
    a = axes.ravel()
    share = float(surface["undefined_share"])
    _image(fig, a[0], surface, "raw_height", scale, length_unit,
           f"as read: rms {float(surface['rms_height_raw']) / scale:.4g} {length_unit}, "
           f"{100 * share:.1f} % undefined (white)", robust=True)
    _image(fig, a[1], surface, "form_height", scale, length_unit,
           f"removed: {surface.attrs['form_removed']}"[:60], cmap="viridis")
    _image(fig, a[2], surface, "roughness_height", scale, length_unit,
           f"roughness: rms {float(surface['rms_height']) / scale:.4g} {length_unit} "
           "(colours: 1st-99th percentile)", cmap="RdBu_r", robust=True, label="roughness height")
    top = shown_peaks(surface["height"].values)
    a[2].plot(surface["x"].values[top] / scale, surface["y"].values[top] / scale, "o", ms=3,
              mfc="none", mec="k", mew=0.6, ls="none",
              label=f"{top.size} highest of {surface.sizes['peak']} peaks")
    a[2].legend(fontsize=8, loc="upper right")
    _density_panel(fig, a[3], surface["height"].values / scale, surface["curvature"].values * scale,
                   bins, length_unit, f"{surface.sizes['peak']} peaks, "
                   f"{float(surface['peak_density']) * scale**2:.3g} per {length_unit}^2 (2.4.3)")
    _loglog(a[4], surface["wavenumber"].values * scale, surface["psd"].values / scale**4,
            f"wavenumber q [rad/{length_unit}]", f"C(q) [{length_unit}^4]",
            "radially averaged power spectral density")
    r = surface["lag"].values / scale
    _loglog(a[5], r, surface["height_difference_autocorrelation"].values / scale**2,
            f"distance r [{length_unit}]", f"A(r) [{length_unit}^2]",
            "height-difference autocorrelation", label="1/2 <(z(x + r) - z(x))^2>")
    lc = surface.attrs.get("correlation_length")
    if lc is not None and np.isfinite(lc):
        a[5].axvline(lc / scale, color="C3", ls="--", lw=0.8,
                     label=f"correlation length {lc / scale:.3g} {length_unit}")
    a[5].legend(fontsize=8)
    _bearing(a[6], surface, scale, length_unit)
    lines = [f"axes: {surface.attrs.get('axes', '')}",
             f"form removed: {surface.attrs.get('form_removed', '')}",
             f"filter: {surface.attrs.get('filter', '')}",
             f"undefined: {100 * share:.2f} %, filled: {int(surface['filled_points'])}, "
             f"islands dropped: {int(surface['island_points'])}",
             f"sigma {float(surface['sigma']) / scale:.4g} {length_unit}, "
             f"slope x/y {float(surface['sigma_slope_x']):.3g} / {float(surface['sigma_slope_y']):.3g}",
             f"Gaussian: {surface.attrs.get('gaussian', '')}"]
    a[7].text(0.0, 0.5, "\n".join(_wrap(line, 60) for line in lines), transform=a[7].transAxes,
              va="center", fontsize=8, family="monospace")
    a[7].set_axis_off()
    _gaussian_note(fig, surface)
    return fit(fig)


def _wrap(text: str, width: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width)) or text


def directional_figure(surface: xr.Dataset, length_unit: str = "m") -> plt.Figure:
    """m2 and m4 of each profile versus direction, with the least-squares moments
    (2.3.2) and, for a synthetic surface, the exact ones (eq. 2.4)."""
    scale = units.length_scale(length_unit)
    estimator = surface.attrs.get("population_estimator", "sampling")
    t = np.linspace(0, np.pi, 181)
    c, s = np.cos(t), np.sin(t)
    fig, axes = subplots(1, 2, figsize=(11, 4.2))

    def m2(sfx=""):
        g = lambda n: float(surface[f"{n}{sfx}"])  # noqa: E731
        return g("m20") * c**2 + 2 * g("m11") * c * s + g("m02") * s**2

    def m4(sfx=""):
        g = lambda n: float(surface[f"{n}{sfx}"])  # noqa: E731
        return (g("m40") * c**4 + 4 * g("m31") * c**3 * s + 6 * g("m22") * c**2 * s**2
                + 4 * g("m13") * c * s**3 + g("m04") * s**4)

    theta = np.degrees(surface["direction"].values)
    per = surface.sel(estimator=estimator)
    axes[0].plot(theta, per["m2"], "o", label=f"profiles ({estimator})")
    axes[0].plot(np.degrees(t), m2(), "-", label="least-squares m20, m11, m02")
    if "m20_exact" in surface:
        axes[0].plot(np.degrees(t), m2("_exact"), "k--", label="exact (eq. 2.4)")
    axes[0].set(xlabel="profile direction [deg]", ylabel="m2 (slope variance) [1]")
    if "m40" in surface:
        axes[1].plot(theta, per["m4"] * scale**2, "o", label=f"profiles ({estimator})")
        axes[1].plot(np.degrees(t), m4() * scale**2, "-", label="least-squares m40 ... m04")
        if "m40_exact" in surface:
            axes[1].plot(np.degrees(t), m4("_exact") * scale**2, "k--", label="exact (eq. 2.4)")
    axes[1].set(xlabel="profile direction [deg]", ylabel=f"m4 (curvature variance) [1/{length_unit}^2]")
    for ax in axes:
        ax.legend(fontsize=8)
    return fit(fig)
