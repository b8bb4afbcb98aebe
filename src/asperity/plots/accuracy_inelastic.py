"""Figure of results/accuracy/inelastic_<case>.nc: an inelastic asperity's mesh and
kinematics at each preset against the reference run, and what each costs.

Drawn from the dataset of `asperity.studies.inelastic_accuracy.inelastic_accuracy` only.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity.plots.layout import fit, subplots
from asperity.studies.inelastic_accuracy import power_interp

__all__ = ["inelastic_accuracy_figure"]

MARKERS = {"fixed": "o", "remesh": "s", "edge_band": "^", "finite_strain": "D"}


def inelastic_accuracy_figure(ds: xr.Dataset) -> plt.Figure:
    """Left, each run's contact area over the reference's at equal interference, in per cent,
    against the interference (over the case's scale); right, each run's largest difference
    in contact area over the second half of the loading against its CPU time."""
    fig, (left, right) = subplots(1, 2, figsize=(12.5, 4.6))
    reference = str(ds.attrs["reference"])
    scale = float(ds.attrs["interference_scale"])
    ref = ds.sel(preset=reference, variant="fixed")
    w_ref, a_ref = (ref[f"history_{k}"].values for k in ("interference", "contact_area"))
    keep = np.isfinite(w_ref)
    for i, preset in enumerate(p for p in ds["preset"].values if p != reference):
        for variant in ds["variant"].values:
            run = ds.sel(preset=preset, variant=variant)
            w, a = run["history_interference"].values, run["history_contact_area"].values
            ok = np.isfinite(w) & (w > 0) & np.isfinite(a) & (a > 0)
            if not ok.any():
                continue
            ratio = a[ok] / power_interp(w[ok], w_ref[keep], a_ref[keep]) - 1
            label = f"{preset}, {variant}"
            left.plot(w[ok] / scale, 100 * ratio, marker=MARKERS.get(str(variant), "."), ms=2.5, lw=1,
                      color=f"C{i}", label=label)
            d = float(run["difference"].sel(against="reference", quantity="contact_area", range="second_half"))
            cpu = float(run["cpu_time"])
            if np.isfinite(d) and d > 0 and cpu > 0:
                right.loglog(cpu, d, marker=MARKERS.get(str(variant), "."), color=f"C{i}", ls="none", label=label)
                right.annotate(label, (cpu, d), xytext=(4, 3), textcoords="offset points", fontsize=7)
    left.axhspan(-1, 1, color="0.9", label="1 %")
    left.set(xscale="log", xlabel=str(ds.attrs["interference_scale_label"]), ylabel=f"contact area / {reference}'s - 1 [%]",
             title=f"{ds.attrs['case']}: contact area against the {reference} run")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=7)
    ref_cpu = float(ref["cpu_time"])
    right.axvline(ref_cpu, color="0.5", ls=":", lw=1, label=f"{reference} (reference)")
    right.set(xlabel="CPU time of the run [s]", ylabel="largest area difference, second half of the loading",
              title="what each run costs and how far it is")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=7)
    return fit(fig)
