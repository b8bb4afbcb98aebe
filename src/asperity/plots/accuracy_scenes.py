"""Figure of results/accuracy/scenes.nc: what accuracy costs for a whole scene.

Drawn from the dataset of `asperity.studies.scenes.scene_accuracy` only;
`asperity.io.figures.save_figure` saves it.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity.plots.layout import fit, subplots

__all__ = ["scene_accuracy_figure"]

QUANTITY_STYLE = {"nominal_pressure": dict(ls="-", marker="o", label="pressure"),
                  "contact_area_ratio": dict(ls="--", marker="s", label="contact area")}


def scene_accuracy_figure(ds: xr.Dataset) -> plt.Figure:
    """Deviation from the reference preset versus total FE CPU time, log-log.

    One panel per branch present (loading; unloading, report 8.3); one line
    per scene (colour) and quantity (solid pressure, dashed contact area),
    each point labelled with its preset.  The reference preset deviates by 0
    by definition: a dotted vertical line marks its CPU time per scene.  A
    scene whose runs extrapolated 1 % or more of the contacting asperities
    beyond their FE jobs' range says so in the legend.
    """
    branches = [str(b) for b in ds["branch"].values
                if np.isfinite(ds["deviation"].sel(branch=b).values).any()]
    fig, axes = subplots(1, max(len(branches), 1), figsize=(6.2 * max(len(branches), 1), 4.6),
                             squeeze=False, sharex=True, sharey=True)
    reference = str(ds.attrs.get("reference", ds["preset"].values[-1]))
    presets = [str(p) for p in ds["preset"].values]
    for ax, branch in zip(axes[0], branches):
        for i, scene in enumerate(ds["scene"].values):
            color = f"C{i}"
            cpu = ds["fe_cpu_time"].sel(scene=scene).values
            if not np.isfinite(ds["deviation"].sel(scene=scene, branch=branch).values).any():
                continue  # e.g. a scene that does not unload, on the unloading panel
            if reference in presets:
                ref_cpu = float(ds["fe_cpu_time"].sel(scene=scene, preset=reference))
                if np.isfinite(ref_cpu) and ref_cpu > 0:
                    ax.axvline(ref_cpu, color=color, ls=":", lw=1)
                    ax.annotate(f"{reference}", (ref_cpu, 1.0), xycoords=("data", "axes fraction"),
                                xytext=(2, -10), textcoords="offset points", color=color,
                                fontsize=7, rotation=90, va="top")
            name = str(scene)
            if "max_extrapolated_fraction" in ds:  # the gather's extrapolation: say how much
                frac = np.nanmax(np.append(ds["max_extrapolated_fraction"].sel(scene=scene).values, 0.0))
                if frac >= 0.01:
                    name += f" (up to {frac:.0%} extrapolated)"
            for quantity, style in QUANTITY_STYLE.items():
                if quantity not in ds["quantity"].values:
                    continue
                dev = ds["deviation"].sel(scene=scene, quantity=quantity, branch=branch).values
                ok = np.isfinite(dev) & (dev > 0) & np.isfinite(cpu) & (cpu > 0)
                if not ok.any():
                    continue
                ax.loglog(cpu[ok], dev[ok], color=color, ls=style["ls"], marker=style["marker"],
                          ms=5, label=f"{name}: {style['label']}")
                for x, y, p in zip(cpu[ok], dev[ok], np.array(presets)[ok]):
                    ax.annotate(p, (x, y), xytext=(4, 3), textcoords="offset points", fontsize=7,
                                color=color)
        ax.set(xlabel="total CPU time of the FE jobs [s]",
               ylabel=f"largest relative deviation from {reference}",
               title=f"{branch} branch (dotted: the {reference} run's CPU time)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"What accuracy costs per scene (threshold {float(ds.attrs.get('threshold', np.nan)):g} "
                 f"of the largest {reference} value)", fontsize=10)
    return fit(fig)
