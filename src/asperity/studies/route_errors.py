"""Every route's error against the boundary elements, map by map: the table of issue #48.

:func:`route_errors` gathers the comparisons of several reference scenes (each a map:
`deterministic_reference`'s synthetic Gaussian map, `afm_reference` and its copies on
the measured maps, `anisotropic_reference`; their `comparison.nc`, `reference.nc` and
`surface.nc`) into one dataset over (scene, route, step):

* per separation (step): h / sigma of the prepared map, the elastic boundary elements'
  contact area ratio, their cells per contact patch and whether they resolve their
  patches (at least `asperity.stages.reference` 's 10 cells), each route's pressure
  error at equal separation (the mean gap) and area error at equal pressure, and the
  route closest to the boundary elements;
* per scene and route, over the band where the boundary elements' area ratio lies in
  [0.1 %, 10 %] and they resolve their patches: the ranges of both errors, the largest
  |error|, where it is, and the goal: an elastic route within 10 % of the elastic
  boundary elements, a route of J2 asperities within 20 % of those limited by the
  hardness (`GOALS`, by the comparison's ``reference_limit``).

Beside them, what explains a miss, by numbers: per map, the skewness and kurtosis of the
prepared heights (the Nayak routes assume 0 and 3), the share of its summits elongated
beyond `ELONGATED` (an axisymmetric asperity is too soft and too wide for them), the span
of the band in sigma (a plateau puts all of it within a fraction of a sigma) and the
fewest boundary-element cells per patch in it (the reference's own resolution); per
route, where its error is largest, its contacts over the boundary elements' patches and
the share of its load carried through merged spots (where the interacting route
approximates the contact of several summits as theirs).

The errors are the comparison's own (`asperity.stages.reference.comparison_dataset`):
nothing is computed again, so the table says what the scenes say.
:func:`route_errors_figure` draws both errors against the boundary elements' area ratio,
one panel per map, with the band and the goal.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import xarray as xr

from asperity.peaks.anisotropic import principal_curvatures
from asperity.units import attrs

__all__ = ["BAND", "ELONGATED", "GOALS", "route_errors", "route_errors_figure"]

#: the contact area ratios over which the goals hold (issue #48)
BAND = (1e-3, 0.1)
#: the goal of a route by the boundary elements it is held against: elastic, or limited by
#: the hardness (a route of J2 asperities)
GOALS = {"elastic": 0.10, "hardness": 0.20}


#: a summit whose principal curvatures are in a ratio below this is elongated: its Hertz
#: contact (Johnson, Contact Mechanics 4.2) carries 4 % more force on 2.4 % less area than
#: the sphere of its Gaussian curvature at the same interference at 1/4, 16 % and 8 % at 1/16
#: (`asperity.references.hertz.elliptic_hertz`)
ELONGATED = 0.25


def _elongated_share(surface: xr.Dataset) -> float:
    """The share of the map's peaks with kappa_2 / kappa_1 < `ELONGATED` (from their second
    derivatives; of the peaks with kappa_1 > 0, a ridge's kappa_2 <= 0 counting as elongated)."""
    if "z_xx" not in surface:
        return float("nan")
    k1, k2, _ = principal_curvatures(-surface["z_xx"].values, -surface["z_xy"].values, -surface["z_yy"].values)
    summit = k1 > 0
    return float(np.mean(k2[summit] / k1[summit] < ELONGATED)) if summit.any() else float("nan")


def _merged_load(routes: Mapping[str, xr.Dataset], names: list[str], h: np.ndarray) -> np.ndarray:
    """(route, step): the share of a route's load carried through merged spots, at the
    comparison's separations `h` (NaN for a route that does not merge spots)."""
    out = np.full((len(names), h.size), np.nan)
    for i, name in enumerate(names):
        ds = routes.get(name)
        if ds is not None and "merged_load_fraction" in ds:
            if "branch" in ds.dims:
                ds = ds.isel(branch=0)
            out[i] = np.interp(h, ds["separation"].values, ds["merged_load_fraction"].values,
                               left=np.nan, right=np.nan)
    return out


def _step_frame(comparison: xr.Dataset, reference: xr.Dataset, surface: xr.Dataset,
                interfaces: Mapping[str, xr.Dataset], routes: list[str]) -> xr.Dataset:
    """One scene's comparison on the common route axis `routes` (NaN where the scene lacks
    a route), with what explains its misses."""
    sigma = float(reference.attrs["sigma"])
    cmp_ = comparison.reindex(route=routes)
    limit = cmp_["reference_limit"].astype(object).where(cmp_["reference_limit"].notnull(), "")
    h = comparison["separation"].values
    return xr.Dataset({
        "contact_count_ratio": (("route", "step"), cmp_["contact_count_ratio"].values),
        "merged_load_fraction": (("route", "step"), _merged_load(interfaces, routes, h)),
        "skewness": float(surface["skewness"]),
        "kurtosis": float(surface["kurtosis"]),
        "elongated_share": _elongated_share(surface),
        "separation_over_sigma": ("step", comparison["separation"].values / sigma),
        "reference_area_ratio": ("step", comparison["reference_area_ratio"].values),
        "reference_pressure": ("step", comparison["reference_pressure"].values),
        "cells_per_patch": ("step", reference["cells_per_patch"].sel(limit="elastic").values),
        "reference_resolved": ("step", comparison["reference_resolved"].values.astype(bool)),
        "pressure_error": (("route", "step"), cmp_["pressure_error"].values),
        "area_error": (("route", "step"), cmp_["area_error"].values),
        "recommended_route": ("step", comparison["recommended_route"].values.astype(str)),
        "reference_limit": ("route", np.asarray(limit.values, dtype=str)),
        "sigma": sigma,
        "scale": float(surface.attrs.get("scale") or 0.0),
        "scale_rule": str(surface.attrs.get("scale_rule", "")),
    }, coords={"route": routes, "step": np.arange(comparison.sizes["separation"])})


def _band(ds: xr.Dataset) -> xr.Dataset:
    """Per scene and route, the errors over the band (module text)."""
    a = ds["reference_area_ratio"]
    inside = (a >= BAND[0]) & (a <= BAND[1]) & ds["reference_resolved"]
    out = {"band_steps": inside.sum("step")}
    worst = None
    for name in ("pressure_error", "area_error"):
        e = ds[name].where(inside)
        out[f"{name}_low"], out[f"{name}_high"] = e.min("step"), e.max("step")
        worst = abs(e) if worst is None else np.fmax(worst, abs(e))
    largest = worst.max("step")
    at = worst.fillna(-1.0).argmax("step")
    where = ds["reference_area_ratio"].isel(step=at).where(largest.notnull())
    h = ds["separation_over_sigma"].where(inside)
    out["band_width"] = h.max("step") - h.min("step")
    out["least_cells_in_band"] = ds["cells_per_patch"].where(inside).min("step")
    for name in ("contact_count_ratio", "merged_load_fraction"):
        out[f"{name}_at_largest_error"] = ds[name].isel(step=at).where(largest.notnull())
    goal = xr.apply_ufunc(np.vectorize(lambda k: GOALS.get(k, np.nan), otypes=[float]),
                          ds["reference_limit"])
    return xr.Dataset({**out, "largest_error": largest, "largest_error_area_ratio": where,
                       "goal": goal.where(ds["reference_limit"] != "")})


def route_errors(comparisons: Mapping[str, tuple]) -> xr.Dataset:
    """The table of every route on every map (module text): `comparisons` maps a scene name
    to its (comparison.nc, reference.nc, surface.nc, {route: its interface.nc})."""
    routes = list(dict.fromkeys(r for c, *_ in comparisons.values() for r in c["route"].values.astype(str)))
    steps = max(c.sizes["separation"] for c, *_ in comparisons.values())
    frames = [_step_frame(c, r, s, (rest[0] if rest else {}), routes).reindex(step=np.arange(steps))
              for c, r, s, *rest in comparisons.values()]
    ds = xr.concat(frames, dim=xr.DataArray(list(comparisons), dims="scene", name="scene"))
    ds["reference_resolved"] = ds["reference_resolved"].fillna(False).astype(bool)
    ds = ds.merge(_band(ds))
    pct, one = "1", "1"
    ds["separation_over_sigma"].attrs = attrs(one, "separation of the flat over the rms height of the prepared map")
    ds["reference_area_ratio"].attrs = attrs(one, "real contact area ratio of the elastic boundary elements")
    ds["reference_pressure"].attrs = attrs("Pa", "nominal pressure of the elastic boundary elements")
    ds["cells_per_patch"].attrs = attrs(one, "mean grid cells per contact patch of the elastic boundary elements")
    ds["reference_resolved"].attrs = attrs(one, "the boundary elements resolve their contact patches (at least 10 cells)")
    ds["pressure_error"].attrs = attrs(pct, "route's nominal pressure at equal separation over the boundary elements', less 1")
    ds["area_error"].attrs = attrs(pct, "route's contact area ratio at equal pressure over the boundary elements', less 1")
    ds["recommended_route"].attrs = attrs("", "route closest to the boundary elements")
    ds["reference_limit"].attrs = attrs("", "boundary elements the route is held against: elastic, or limited by the hardness")
    ds["sigma"].attrs = attrs("m", "rms height of the prepared map")
    ds["scale"].attrs = attrs("m", "lateral scale of the asperities (0: the pixel)")
    ds["scale_rule"].attrs = attrs("", "how the lateral scale was chosen")
    ds["band_steps"].attrs = attrs(one, f"separations in the band (area ratio {BAND[0]:g}-{BAND[1]:g}, resolved)")
    ds["contact_count_ratio"].attrs = attrs(one, "route's contacts over the boundary elements' contact patches")
    ds["merged_load_fraction"].attrs = attrs(one, "share of the route's load carried by merged spots")
    ds["skewness"].attrs = attrs(one, "skewness of the prepared heights (0: Gaussian)")
    ds["kurtosis"].attrs = attrs(one, "kurtosis of the prepared heights (3: Gaussian)")
    ds["elongated_share"].attrs = attrs(one, f"share of the summits with kappa_2/kappa_1 < {ELONGATED:g}")
    ds["band_width"].attrs = attrs(one, "span of the band's separations over sigma")
    ds["least_cells_in_band"].attrs = attrs(one, "fewest boundary-element cells per contact patch in the band")
    ds["contact_count_ratio_at_largest_error"].attrs = attrs(
        one, "route's contacts over the boundary elements' patches where its error is largest")
    ds["merged_load_fraction_at_largest_error"].attrs = attrs(
        one, "share of the route's load through merged spots where its error is largest")
    for name in ("pressure_error", "area_error"):
        ds[f"{name}_low"].attrs = attrs(pct, f"least {name.replace('_', ' ')} in the band")
        ds[f"{name}_high"].attrs = attrs(pct, f"largest {name.replace('_', ' ')} in the band")
    ds["largest_error"].attrs = attrs(pct, "largest |pressure or area error| in the band")
    ds["largest_error_area_ratio"].attrs = attrs(one, "boundary elements' area ratio where the largest error is")
    ds["goal"].attrs = attrs(pct, "issue #48's goal: largest |error| in the band at most this")
    ds["scene"].attrs = attrs("", "reference scene (its map)")
    ds["route"].attrs = attrs("", "statistical route of the scene")
    ds["step"].attrs = attrs("", "separation of the scene, from the lightest load")
    ds.attrs.update(band_low=BAND[0], band_high=BAND[1])
    return ds


def route_errors_figure(ds: xr.Dataset):
    """Pressure (solid) and area (dashed) error of every route against the boundary
    elements' contact area ratio, one panel per scene, the band shaded and the goals dotted."""
    import matplotlib.pyplot as plt

    n = ds.sizes["scene"]
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n, 3.8), sharey=True, squeeze=False,
                             layout="constrained")
    colors = {r: f"C{i}" for i, r in enumerate(ds["route"].values)}
    for ax, scene in zip(axes[0], ds["scene"].values):
        d = ds.sel(scene=scene)
        a = d["reference_area_ratio"].values
        for route in d["route"].values:
            for name, style in (("pressure_error", "-"), ("area_error", "--")):
                e = d[name].sel(route=route).values
                if np.isfinite(e).any():
                    ax.semilogx(a, 100 * e, style, color=colors[route],
                                label=route if name == "pressure_error" else None)
        ax.axvspan(*BAND, color="0.92", zorder=0)
        for goal in set(GOALS.values()):
            ax.axhline(100 * goal, color="0.5", ls=":", lw=0.8)
            ax.axhline(-100 * goal, color="0.5", ls=":", lw=0.8)
        ax.set(title=str(scene), xlabel="boundary elements' contact area ratio", ylim=(-100, 150))
    axes[0][0].set_ylabel("error (%): pressure solid, area dashed")
    axes[0][-1].legend(fontsize=7, loc="upper right")
    return fig
