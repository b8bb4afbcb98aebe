"""Figure of results/accuracy/sliding.nc: a sliding asperity's force histories at each
preset, and what each finer preset changes against what it costs.

Drawn from the dataset of `asperity.studies.sliding_accuracy.sliding_accuracy` only.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity.plots.layout import fit, subplots

__all__ = ["sliding_accuracy_figure"]


def sliding_accuracy_figure(ds: xr.Dataset) -> plt.Figure:
    """Left, the normal (solid) and tangential (dashed) force against time, one colour per
    preset; right, each preset's largest difference from the next finer one (per force
    and phase) against the coarser run's wall time."""
    fig, (left, right) = subplots(1, 2, figsize=(12.5, 4.6))
    for i, preset in enumerate(ds["preset"].values):
        d = ds.sel(preset=preset)
        t = d["history_time"].values
        for name, ls in (("normal_force", "-"), ("tangential_force", "--")):
            left.plot(t, 1e3 * d[f"history_{name}"].values, ls, color=f"C{i}", lw=1.2,
                      label=f"{preset}: {'F_N' if name == 'normal_force' else 'F_T'}")
    left.set(xlabel="time [s]", ylabel="force [mN]", title=f"{ds.attrs.get('sliding_scene', '')}: forces on the flat")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=7)
    styles = {("normal_force", "pressing"): ("o", "-"), ("normal_force", "sliding"): ("s", "-"),
              ("tangential_force", "sliding"): ("^", "--")}
    wall = ds["total_wall_time"].sel(preset=ds["coarser"]).values
    for (force, phase), (marker, ls) in styles.items():
        d = ds["difference"].sel(force=force, phase=phase).values
        ok = np.isfinite(d) & (d > 0) & np.isfinite(wall) & (wall > 0)
        if ok.any():
            right.loglog(wall[ok], d[ok], marker=marker, ls=ls, color="k",
                         label=f"{'F_N' if force == 'normal_force' else 'F_T'}, {phase}")
            for x, y, pair in zip(wall[ok], d[ok], ds["pair"].values[ok]):
                right.annotate(str(pair), (x, y), xytext=(4, 3), textcoords="offset points", fontsize=7)
    right.set(xlabel="wall time of the coarser run [s]", ylabel="largest difference / largest force",
              title="each preset against the next finer one")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=7)
    return fit(fig)
