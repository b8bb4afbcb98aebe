"""Figures of friction.nc (report Figs. 9.1-9.3) and laws.nc (Figs. 10.1, 10.2).

Drawn from the result datasets only; the scene's pressure and length units on
the axes.  `asperity.io.figures.save_figure` saves them.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units
from asperity.friction import at_pressure
from asperity.plots.layout import fit, subplots
from asperity.plots.validity import shade_invalid

__all__ = ["friction_figure", "laws_figure"]

LAW_STYLE = {"oden_martins": dict(color="C1", label="Oden-Martins (10.42)"),
             "exponential": dict(color="C2", label="exponential")}


def friction_figure(friction: xr.Dataset, others: dict[str, xr.Dataset] | None = None,
                    pressure_unit: str = "Pa", length_unit: str = "m") -> plt.Figure:
    """mu versus nominal pressure (shear, interlocking, total; measured values and the
    report's estimate) and versus separation; compared scenes' mu dotted.

    With a sliding direction (dim ``direction``) the totals are drawn at the
    directions of the smallest and the largest mu_interlocking given; with a sweep a
    third panel draws mu_interlocking and mu at a few pressures against the
    direction (`_direction_panel`)."""
    ps = units.pressure_scale(pressure_unit)
    ls = units.length_scale(length_unit)
    p = friction["nominal_pressure"].values / ps
    h = friction["separation"].values / ls
    shear = friction["mu_shear"].values
    directed = "direction" in friction.dims
    sweep = directed and friction.sizes["direction"] > 1
    fig, axes = subplots(1, 3 if sweep else 2, figsize=(17, 4.4) if sweep else (12, 4.4))
    ax = axes[0]
    ok = np.isfinite(shear) & (p > 0)
    ax.semilogx(p[ok], shear[ok], "o-", ms=3, color="C0", label="shearing τ_s A_c / F (9.41)")
    if directed:
        mu_dir = friction["mu_interlocking"].values
        picks = sorted({int(np.argmin(mu_dir)), int(np.argmax(mu_dir))})
        curves = [(float(mu_dir[k]), friction["mu"].values[:, k],
                   f" at θ = {np.degrees(float(friction['direction'][k])):.4g}°") for k in picks]
    else:
        curves = [(float(friction["mu_interlocking"]), friction["mu"].values, "")]
    for j, (mu_i, total, at) in enumerate(curves):
        if mu_i > 0:
            color, style = ("k", "o-") if j == 0 else ("0.45", "s-")
            ax.semilogx(p[ok], np.full(ok.sum(), mu_i), "--", color=color if j else "C0", lw=1,
                        label=f"interlocking {mu_i:.3g}{at}")
            ax.semilogx(p[ok], total[ok], style, ms=3, color=color, label=f"total μ{at}")
    axes[1].plot(h[ok], shear[ok], "o-", ms=3, color="C0", label="shearing")
    for j, (mu_i, total, at) in enumerate(curves):
        if mu_i > 0:
            axes[1].plot(h[ok], total[ok], "o-" if j == 0 else "s-", ms=3, color="k" if j == 0 else "0.45",
                         label=f"total{at}")
    for i, (name, other) in enumerate((others or {}).items()):
        po = other["nominal_pressure"].values / ps
        mo = other["mu"]
        at = ""
        if "direction" in mo.dims:  # a compared scene with a direction: its first
            at = f", θ = {np.degrees(float(other['direction'][0])):.4g}°"
            mo = mo.isel(direction=0)
        mo = mo.values
        oko = np.isfinite(mo) & (po > 0)
        style = dict(ls=":", marker="s", ms=3, color=f"C{i + 3}", label=f"{name} (total{at})")
        ax.semilogx(po[oko], mo[oko], **style)
        axes[1].plot(other["separation"].values[oko] / ls, mo[oko], **style)
    if "measurement" in friction.dims:
        for j, label in enumerate(friction["measurement"].values):
            val = float(friction["measured_mu"][j])
            err = float(friction["measured_mu_uncertainty"][j])
            mp = float(friction["measured_nominal_pressure"][j]) / ps
            color = f"C{(j + 6) % 10}"
            ax.axhline(val, color=color, ls="-.", lw=1, label=f"measured {val:.3g}: {label}")
            if np.isfinite(mp):
                ax.errorbar([mp], [val], yerr=None if not np.isfinite(err) else [err], fmt="D",
                            color=color, ms=6, capsize=3)
            axes[1].axhline(val, color=color, ls="-.", lw=1)
    rp = float(friction["report_nominal_pressure"]) / ps if "report_nominal_pressure" in friction else np.nan
    for name, marker in (("report_mu_shear", "x"), ("report_mu", "*")):
        if name in friction:
            val = float(friction[name])
            what = "shearing" if name == "report_mu_shear" else "total"
            if np.isfinite(rp):
                ax.plot([rp], [val], marker, color="r", ms=9, ls="none", label=f"report's {what} {val:.3g}")
            else:
                ax.axhline(val, color="r", ls=":", lw=1, label=f"report's {what} {val:.3g}")
    ax.set(xlabel=f"nominal pressure [{pressure_unit}]", ylabel="coefficient of friction μ",
           title=f"τ_s = {float(friction['junction_shear_strength']) / ps:.4g} {pressure_unit}")
    axes[1].set(xlabel=f"separation [{length_unit}]", ylabel="coefficient of friction μ",
                title="versus separation (approach grows to the left)")
    shade_invalid(axes, [p, h], friction)
    if sweep:
        _direction_panel(axes[2], friction, pressure_unit)
    for a in axes:
        a.set_ylim(bottom=0)
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    return fit(fig)


def _direction_panel(ax, friction: xr.Dataset, pressure_unit: str) -> None:
    """mu_interlocking and mu against the sliding direction [deg]: mu at the tests'
    pressures (those inside the computed range), else at the smallest, a middle and
    the largest computed positive pressure (mu_shear interpolated in log p,
    `asperity.friction.at_pressure`); the lay and the steepest direction dotted."""
    ps = units.pressure_scale(pressure_unit)
    deg = np.degrees(friction["direction"].values)
    p = friction["nominal_pressure"].values
    shear = friction["mu_shear"].values
    mu_i = friction["mu_interlocking"].values
    ax.plot(deg, mu_i, "--", color="C0", label="interlocking")
    ok = np.flatnonzero(np.isfinite(shear) & (p > 0))
    targets = np.array([])
    if "measured_nominal_pressure" in friction:
        mp = friction["measured_nominal_pressure"].values
        targets = np.unique(mp[np.isfinite(at_pressure(p, shear, mp))])
    if targets.size == 0 and ok.size:
        order = ok[np.argsort(p[ok])]
        targets = np.unique(p[order[[0, order.size // 2, -1]]])
    for j, target in enumerate(targets[:4]):
        total = at_pressure(p, shear, target)[0] + mu_i
        ax.plot(deg, total, "o-", ms=3, color=f"C{j + 1}", label=f"total μ at {target / ps:.3g} {pressure_unit}")
    lo, hi = deg.min(), deg.max()
    for key, style, what in (("lay_direction", ":", "lay"), ("steepest_direction", "-.", "steepest")):
        if key in friction.attrs:
            base = np.degrees(float(friction.attrs[key]))
            marks = base + 180.0 * np.arange(np.floor((lo - base) / 180.0), np.ceil((hi - base) / 180.0) + 1)
            marks = marks[(marks >= lo) & (marks <= hi)]
            for k, mark in enumerate(marks):
                ax.axvline(mark, color="0.3", ls=style, lw=1, label=f"{what} {base:.3g}°" if k == 0 else None)
    flat = "" if np.ptp(mu_i) > 0 else " (flat: no direction dependence)"
    ax.set(xlabel="sliding direction θ from x [deg]", ylabel="coefficient of friction μ",
           title=f"versus sliding direction{flat}")


def laws_figure(laws: xr.Dataset, pressure_unit: str = "Pa", length_unit: str = "m") -> plt.Figure:
    """Pressure versus approach, log-log: the data (fitted points filled), the fitted
    laws and the report's law; and the relative error of each law over the data."""
    ps = units.pressure_scale(pressure_unit)
    ls = units.length_scale(length_unit)
    a = laws["approach"].values / ls
    p = laws["nominal_pressure"].values / ps
    win = laws["in_window"].values.astype(bool)
    fig, axes = subplots(1, 2, figsize=(12, 4.4))
    ax = axes[0]
    show = (a > 0) & (p > 0)
    ax.loglog(a[show & win], p[show & win], "o", color="C0", ms=4, label="homogenized (fitted)")
    if np.any(show & ~win):
        ax.loglog(a[show & ~win], p[show & ~win], "o", mfc="none", color="C0", ms=4, label="homogenized (not fitted)")
    fine = np.geomspace(a[show].min(), a[show].max(), 200) if show.any() else np.array([])
    params = laws["estimate"]
    a0 = float(laws.attrs.get("a0", 1e-6))
    for law in laws["law"].values:
        law = str(law)
        est = {str(k): float(v) for k, v in zip(laws["parameter"].values, params.sel(law=law).values)}
        if law == "oden_martins":
            u = (fine * ls - est["g"]) / a0
            curve = np.where(u > 0, est["c"] * np.where(u > 0, u, 1.0) ** est["m"], np.nan)
            text = f"c = {est['c']:.3g} Pa, g = {est['g'] / ls:.3g} {length_unit}, m = {est['m']:.3g}"
        else:
            curve = est["c"] * np.exp(fine * ls / est["decay_length"])
            text = f"c = {est['c']:.3g} Pa, λ = {est['decay_length'] / ls:.3g} {length_unit}"
        style = LAW_STYLE.get(law, {})
        ax.loglog(fine, curve / ps, "-", color=style.get("color"), label=f"{style.get('label', law)}: {text}")
        axes[1].semilogx(a[show & win], laws["relative_error"].sel(law=law).values[show & win], "o-", ms=3,
                         color=style.get("color"), label=style.get("label", law))
        rep = {str(k): float(v) for k, v in
               zip(laws["parameter"].values, laws["report_value"].sel(law=law).values)}
        if law == "oden_martins" and np.isfinite(rep["c"]) and np.isfinite(rep["m"]):
            g = rep["g"] if np.isfinite(rep["g"]) else 0.0
            u = (fine * ls - g) / a0
            curve = np.where(u > 0, rep["c"] * np.where(u > 0, u, 1.0) ** rep["m"], np.nan)
            ax.loglog(fine, curve / ps, "k--", lw=1,
                      label=f"report: {laws.attrs.get('report_as_printed', '')} (its own approach origin)")
    ax.set(xlabel=f"approach a [{length_unit}] (from {laws.attrs.get('approach_origin_from', '')})",
           ylabel=f"nominal pressure [{pressure_unit}]",
           title=f"fits with {laws.attrs.get('residual', '')} residuals, a0 = 1 μm")
    axes[1].axhline(0.0, color="k", lw=0.8)
    axes[1].set(xlabel=f"approach a [{length_unit}]", ylabel="p_fit / p - 1", title="relative error in the window")
    for a_ in axes:
        a_.grid(True, which="both", alpha=0.3)
        a_.legend(fontsize=7)
    return fit(fig)
