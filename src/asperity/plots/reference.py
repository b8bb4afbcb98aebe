"""The statistical routes beside the boundary-element reference (scene deterministic_reference)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units
from asperity.plots.figures import finish
from asperity.plots.layout import subplots

#: A/A0 = KAPPA p / (E* h'_rms) at small load, the boundary-element literature's constant
#: (Hyun et al., Phys. Rev. E 70 (2004) 026117), drawn for orientation
KAPPA = 2.0


def reference_figure(reference: xr.Dataset, comparison: xr.Dataset, length_unit: str = "m",
                     pressure_unit: str = "Pa") -> plt.Figure:
    """Pressure against separation, area against pressure, and each route's errors."""
    ls_ = units.length_scale(length_unit)
    ps = units.pressure_scale(pressure_unit)
    fig, axes = subplots(1, 3, figsize=(15, 4.4))
    h = reference["separation"].values / ls_
    for limit, style in (("elastic", "-"), ("hardness", "--")):
        if limit not in reference["limit"].values:
            continue
        ds = reference.sel(limit=limit)
        label = ("boundary elements, elastic" if limit == "elastic" else
                 f"boundary elements, hardness {reference.attrs['hardness'] / ps:.4g} {pressure_unit}")
        p = ds["nominal_pressure"].values / ps
        axes[0].semilogy(h, p, "k" + style, marker="o", ms=3, label=label)
        axes[1].loglog(p, ds["contact_area_ratio"].values, "k" + style, marker="o", ms=3, label=label)
    for i, route in enumerate(comparison["route"].values):
        c = comparison.sel(route=route)
        p = c["nominal_pressure"].values / ps
        axes[0].semilogy(h, p, ls=":", marker="s", ms=3, color=f"C{i}", label=str(route))
        axes[1].loglog(p, c["contact_area_ratio"].values, ls=":", marker="s", ms=3, color=f"C{i}",
                       label=str(route))
        axes[2].plot(h, 100 * c["pressure_error"].values, marker="s", ms=3, color=f"C{i}",
                     label=f"{route}: pressure")
        axes[2].plot(h, 100 * c["area_error"].values, ls="--", marker=".", ms=3, color=f"C{i}",
                     label=f"{route}: area at equal pressure")
    p_el = reference.sel(limit="elastic")["nominal_pressure"].values
    line = KAPPA * p_el / (reference.attrs["contact_modulus"] * reference.attrs["gradient_rms"])
    axes[1].loglog(p_el / ps, line, "k:", lw=1, label=f"A/A0 = {KAPPA:g} p / (E* h'rms)")
    band = 100 * float(comparison.attrs["agreement"])
    axes[2].axhspan(-band, band, color="0.9", zorder=0, label=f"agreement ±{band:g} %")
    top = np.nanmax(np.abs(100 * comparison["pressure_error"].values), initial=band)
    axes[2].set_ylim(-min(1.1 * top, 200), min(1.1 * top, 200))
    axes[0].set(xlabel=f"separation [{length_unit}]", ylabel=f"nominal pressure [{pressure_unit}]")
    axes[1].set(xlabel=f"nominal pressure [{pressure_unit}]", ylabel="real contact area ratio A/A0")
    axes[2].set(xlabel=f"separation [{length_unit}]",
                ylabel="statistical route against elastic boundary elements [%]")
    axes[0].set_title(f"{reference.attrs.get('boundary', '')} map, {reference.attrs.get('grid', '')}",
                      fontsize=8)
    return finish(fig, axes, fontsize=7)
