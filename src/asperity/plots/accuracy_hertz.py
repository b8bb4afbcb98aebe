"""Figure of the Hertz accuracy study (`study.hertz_accuracy_study`).

Drawn from the study's Dataset only.  Errors are shown in percent (the
Dataset holds them as fractions).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.lines import Line2D

from asperity.fe.contact.penalty import PENALTY_FACTOR
from asperity.plots.layout import fit, subplots
from asperity.studies.hertz import REPORT_MAX_FORCE_ERROR, REPORT_MAX_RADIUS_ERROR

#: colour per quantity
QUANTITY = {
    "force": dict(var="max_force_error", color="C0", label="load"),
    "radius": dict(var="max_radius_error", color="C3", label="contact radius"),
}
#: marker per preset (others cycle through the spares)
PRESET_MARKERS = {"draft": "o", "standard": "s", "fine": "D"}
SPARE_MARKERS = ("^", "v", "P", "X", "*")
REPORT_LABEL = "report 1993 (Fig. 6.5)"


def _percent(values) -> np.ndarray:
    v = 100.0 * np.asarray(values, dtype=float)
    return np.where(v > 0, v, np.nan)  # log axes: an exact zero is not drawn


def _error_panel(ax, ds: xr.Dataset, xvar: str, report_force: float, report_radius: float):
    kind = ds["kind"].values.astype(str)
    runs = ds["run"].values.astype(str)
    refine = kind == "refinement"
    presets = [r for r, k in zip(runs, kind) if k == "preset"]
    markers = {}
    spare = iter(SPARE_MARKERS * 10)
    for r in presets:
        markers[r] = PRESET_MARKERS.get(r) or next(spare)
    for q in QUANTITY.values():
        err = ds[q["var"]]
        x = ds[xvar]
        if refine.any():
            xs = x.sel(body="paraboloid").values[refine]
            ys = _percent(err.sel(body="paraboloid").values[refine])
            ax.plot(xs, ys, "-", color=q["color"], marker=".", ms=5, lw=1.3)
        for r in presets:
            for body, face in (("paraboloid", q["color"]), ("sphere", "none")):
                if body not in ds["body"].values:
                    continue
                xv = float(x.sel(body=body, run=r))
                yv = float(_percent(err.sel(body=body, run=r)))
                if not (np.isfinite(xv) and np.isfinite(yv)):
                    continue
                ax.plot([xv], [yv], ls="none", marker=markers[r], ms=7, mfc=face,
                        mec=q["color"], mew=1.3)
                if body == "paraboloid":
                    ax.annotate(r, (xv, yv), textcoords="offset points", xytext=(5, 4),
                                fontsize=7, color=q["color"])
    ax.axhline(100 * report_force, color=QUANTITY["force"]["color"], ls="--", lw=1)
    ax.axhline(100 * report_radius, color=QUANTITY["radius"]["color"], ls="--", lw=1)
    ax.text(0.02, 100 * report_force, f"{REPORT_LABEL}: load {100 * report_force:.1f} %",
            transform=ax.get_yaxis_transform(), va="bottom", fontsize=7,
            color=QUANTITY["force"]["color"])
    ax.text(0.02, 100 * report_radius, f"{REPORT_LABEL}: radius {100 * report_radius:.1f} %",
            transform=ax.get_yaxis_transform(), va="bottom", fontsize=7,
            color=QUANTITY["radius"]["color"])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel("max |relative error| over the steps [%]")
    ax.grid(True, which="major", alpha=0.3)
    return markers


def _error_legend(ax, markers: dict):
    handles = [Line2D([], [], color=q["color"], marker=".", label=f"{q['label']}, refinement")
               for q in QUANTITY.values()]
    handles += [Line2D([], [], ls="none", marker=m, color="k", label=f"preset {r}")
                for r, m in markers.items()]
    handles += [
        Line2D([], [], ls="none", marker="o", color="0.4", label="paraboloid (Hertz's body)"),
        Line2D([], [], ls="none", marker="o", mfc="none", mec="0.4",
               label="sphere (differs by geometry)"),
        Line2D([], [], ls="--", color="0.4", label=REPORT_LABEL),
    ]
    ax.legend(handles=handles, fontsize=7, loc="lower left")


def accuracy_figure(ds: xr.Dataset) -> plt.Figure:
    """1 x 3: error vs wall time, error vs dofs, penalty error vs factor."""
    fig, axes = subplots(1, 3, figsize=(16.5, 5.0))
    rf = float(ds.attrs.get("report_max_force_error", REPORT_MAX_FORCE_ERROR))
    rr = float(ds.attrs.get("report_max_radius_error", REPORT_MAX_RADIUS_ERROR))

    ax = axes[0]
    markers = _error_panel(ax, ds, "wall_time", rf, rr)
    ax.set_xlabel(f"{ds['wall_time'].attrs['long_name'].split(' (')[0]} "
                  f"[{ds['wall_time'].attrs['units']}]")
    ax.set_title("(a) max error against Hertz vs wall time")
    _error_legend(ax, markers)

    ax = axes[1]
    _error_panel(ax, ds, "dofs", rf, rr)
    ax.set_xlabel("degrees of freedom [1]")
    ax.set_title("(b) max error against Hertz vs mesh size")

    ax = axes[2]
    default = float(ds.attrs.get("default_penalty_factor", PENALTY_FACTOR))
    if "penalty_factor" in ds.dims and ds.sizes["penalty_factor"]:
        c = ds["penalty_factor"].values
        for name, q in (("penalty_force_error", QUANTITY["force"]),
                        ("penalty_radius_error", QUANTITY["radius"])):
            ax.plot(c, _percent(ds[name].values), "-o", color=q["color"], ms=5,
                    label=f"{q['label']}: |penalty / exact - 1|")
        # a 1/c guide, a third below the force error at the smallest factor
        ref = _percent(ds["penalty_force_error"].values)[0]
        if np.isfinite(ref):
            ax.plot(c, ref / 3 * c[0] / c, ":", color="0.5", lw=1, label="slope 1/c")
        if "penalty_wall_time" in ds:
            lines = [f"c = {ci:g}: {ti:.2f} s" for ci, ti in
                     zip(c, ds["penalty_wall_time"].values)]
            if "exact_wall_time" in ds:
                lines.append(f"exact: {float(ds['exact_wall_time']):.2f} s")
            ax.text(0.98, 0.98, "wall time of a run\n" + "\n".join(lines),
                    transform=ax.transAxes, ha="right", va="top", fontsize=7,
                    bbox=dict(boxstyle="round", fc="white", ec="0.7"))
    else:
        ax.text(0.5, 0.5, "no penalty study", transform=ax.transAxes, ha="center")
    ax.axvline(default, color="k", ls="--", lw=1, label=f"default c = {default:g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("penalty factor c in kappa = c E' / h [1]")
    ax.set_ylabel("max |relative error| over the steps [%]")
    acc = ds.attrs.get("penalty_accuracy", "")
    ax.set_title(f"(c) penalty error vs exact contact ({acc} mesh)" if acc
                 else "(c) penalty error vs exact contact")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7)

    fig.suptitle(f"Hertz problem (report 6.1): R = {ds.attrs.get('radius', np.nan):g} m, "
                 f"E = {ds.attrs.get('youngs_modulus', np.nan):g} Pa, "
                 f"nu = {ds.attrs.get('poisson', np.nan):g}", fontsize=10)
    return fit(fig)
