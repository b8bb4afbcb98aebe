"""The adhesion figure (report 7.3, Figs. 7.6 to 7.9): with and without adhesion.

Drawn from ``interface.nc`` and ``asperities.nc`` of an adhesive scene
(`asperity.population.kinds.adhesive`) and the interfaces of compared scenes.
Pressures change sign (net attraction), so they are drawn on a symmetric
log scale, linear within the smallest attraction shown.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units
from asperity.plots.figures import finish
from asperity.plots.layout import subplots
from asperity.plots.validity import shade_invalid

STYLE = {"approach": dict(ls="-", marker="o", ms=3), "retract": dict(ls="--", marker=".", ms=3)}


def _loading(ds: xr.Dataset) -> xr.Dataset:
    if "branch" not in ds.dims:
        return ds
    names = list(ds["branch"].values)
    return ds.sel(branch="loading" if "loading" in names else names[0])


def adhesion_figure(interface: xr.Dataset, asperities: xr.Dataset,
                    others: dict[str, xr.Dataset] | None = None, length_unit: str = "m",
                    pressure_unit: str = "Pa") -> plt.Figure:
    """Pressure (Fig. 7.7) and contact area (Fig. 7.8) versus separation, contact area
    versus pressure (Fig. 7.9), with and without adhesion; load-deflection curves of the
    computed asperities with their pull-off forces against DMT and JKR (Fig. 7.6)."""
    ls_ = units.length_scale(length_unit)
    ps = units.pressure_scale(pressure_unit)
    fig, axes = subplots(1, 4, figsize=(21, 4.6))
    p_all = [interface["nominal_pressure"].values / ps]
    for i, branch in enumerate(interface["branch"].values):
        one = interface.sel(branch=branch)
        h = one["separation"].values / ls_
        p = one["nominal_pressure"].values / ps
        a = one["contact_area_ratio"].values
        style = dict(color="C0", label=f"adhesion, {branch}", **STYLE.get(str(branch), {}))
        axes[0].plot(h, p, **style)
        axes[1].semilogy(h, np.where(a > 0, a, np.nan), **style)
        axes[2].plot(p, np.where(a > 0, a, np.nan), **style)
    for j, (name, other) in enumerate((others or {}).items()):
        o = _loading(other)
        h = o["separation"].values / ls_
        p = o["nominal_pressure"].values / ps
        a = o["contact_area_ratio"].values
        style = dict(color=f"C{j + 1}", ls=":", marker="s", ms=3, label=f"{name} (no adhesion)")
        axes[0].plot(h, p, **style)
        axes[1].semilogy(h, np.where(a > 0, a, np.nan), **style)
        axes[2].plot(p, np.where(a > 0, a, np.nan), **style)
        p_all.append(p)
    p_all = np.concatenate([np.ravel(v) for v in p_all])
    attraction = np.abs(p_all[p_all < 0])
    linthresh = float(attraction.max()) if attraction.size else float(np.abs(p_all).max() or 1.0)
    for ax in (axes[0],):
        ax.set_yscale("symlog", linthresh=linthresh)
    axes[2].set_xscale("symlog", linthresh=linthresh)
    axes[2].set_yscale("log")
    top = float(np.nanmax(interface["contact_area_ratio"].values))
    for ax in axes[1:3]:  # eight decades: below, the few asperities caught mid-jump
        ax.set_ylim(1e-8 * top, 2 * top)
    approach = interface.sel(branch=interface["branch"].values[0])
    shade_invalid(axes[:2], [approach["separation"].values / ls_] * 2, approach)
    pull = interface.attrs.get("pull_off_pressure", np.nan) / ps
    axes[0].axhline(0.0, color="k", lw=0.6)
    axes[0].set(xlabel=f"separation [{length_unit}]", ylabel=f"nominal pressure [{pressure_unit}]",
                title=f"Fig. 7.7: pull-off pressure {pull:.3g} {pressure_unit} (retraction)")
    axes[1].set(xlabel=f"separation [{length_unit}]", ylabel="real contact area ratio A/A0",
                title="Fig. 7.8")
    axes[2].set(xlabel=f"nominal pressure [{pressure_unit}]", ylabel="real contact area ratio A/A0",
                title="Fig. 7.9")
    # Fig. 7.6: the computed asperities
    paths = []
    for j, k in enumerate(asperities["curvature"].values):
        valid = asperities["path_valid"].values[j].astype(bool)
        paths.append((1.0 / k, asperities["path_interference"].values[j][valid],
                      asperities["path_force"].values[j][valid],
                      asperities["path_branch"].values[j][valid].astype(str)))
    _curves_panel(axes[3], paths, asperities, float(asperities.attrs.get("reach", np.nan)), ls_,
                  length_unit)
    return finish(fig, axes, fontsize=7)


def _curves_panel(ax, paths, pull: xr.Dataset, reach: float, ls_: float, length_unit: str) -> None:
    """Fig. 7.6 on `ax`: load against interference of each asperity, `paths` its (tip
    radius, interference, force, branch) on approach (solid) and retraction (dashed),
    its pull-off (``pull_off_force``, ``pull_off_interference`` of `pull`, in the same
    order) against DMT's 2 pi R W; x from the cut-off to a few times it (`reach`)."""
    for j, (radius, w, F, br) in enumerate(paths):
        ratio = float(pull["pull_off_force"][j] / pull["pull_off_force_dmt"][j])
        for branch in ("approach", "retract"):
            m = br == branch
            ax.plot(w[m] / ls_, F[m], color=f"C{j}", ls=STYLE[branch]["ls"],
                    label=(f"R = {1e6 * radius:.3g} um: pull-off {ratio:.3f} x 2πRW"
                           if branch == "approach" else None))
        ax.plot(float(pull["pull_off_interference"][j]) / ls_, -float(pull["pull_off_force"][j]), "v",
                color=f"C{j}")
    ax.axhline(0.0, color="k", lw=0.6)
    if np.isfinite(reach):  # where the adhesion acts: from the cut-off to a few times it
        ax.set_xlim(-1.3 * reach / ls_, 3.0 * reach / ls_)
    ax.set_yscale("symlog", linthresh=float(pull["pull_off_force"].min()))
    ax.set(xlabel=f"interference [{length_unit}] (negative: gap)", ylabel="force [N]",
           title="Fig. 7.6: computed asperities (dashed: retraction, ▼ pull-off)")


def curves_figure(curves: xr.Dataset) -> plt.Figure:
    """Fig. 7.6 from `asperity.studies.adhesion.smooth_aluminum_curves` (dims radius,
    step): each asperity's load against interference, approach and retraction, its
    pull-off against DMT's 2 pi R W and JKR's 3/2 pi R W (the ratios on the right)."""
    fig, axes = subplots(1, 2, figsize=(12, 4.6))
    paths = []
    for j, radius in enumerate(curves["radius"].values):
        valid = curves["valid"].values[j].astype(bool)
        paths.append((radius, curves["interference"].values[j][valid], curves["force"].values[j][valid],
                      curves["branch"].values[j][valid].astype(str)))
    _curves_panel(axes[0], paths, curves, np.nan, 1e-9, "nm")  # the whole path, cut-off to w_max
    R = curves["radius"].values * 1e6
    for name, label, marker in (("pull_off_force_dmt", "DMT 2πRW", "s"),
                                ("pull_off_force_jkr", "JKR 3/2 πRW", "D")):
        axes[1].plot(R, curves["pull_off_force"].values / curves[name].values, marker=marker,
                     label=f"computed / {label}")
    axes[1].axhline(1.0, color="k", lw=0.6)
    axes[1].set(xlabel="tip radius R [um]", ylabel="pull-off force ratio",
                title=f"Tabor parameter {curves['tabor_parameter'].values.min():.2g} to "
                      f"{curves['tabor_parameter'].values.max():.2g}")
    fig.suptitle("Report 7.3, Fig. 7.6: smooth elastic aluminum asperities with adhesion "
                 f"({curves.attrs.get('accuracy', '')})")
    return finish(fig, axes, fontsize=7)
