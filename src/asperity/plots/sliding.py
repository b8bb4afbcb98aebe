"""Figures of the sliding asperity (report 9.2, Figs. 9.4 and 9.5), from sliding.nc only."""

from __future__ import annotations

import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np
import xarray as xr

from asperity import units
from asperity.plots.layout import fit, subplots


def _section(ds: xr.Dataset, snapshot: str, scale: float):
    x = ds["plane_x"].values + ds["plane_ux"].sel(snapshot=snapshot).values
    z = ds["plane_z"].values + ds["plane_uz"].sel(snapshot=snapshot).values
    return mtri.Triangulation(x / scale, z / scale, ds["plane_triangles"].values)


def _zoom(ax, ds, scale, unit):
    """The top of the asperity: 2.5 contact radii around the apex and the sliding path."""
    r = float(ds.attrs.get("reference_contact_radius", 1e-6)) / scale
    slide = float(np.max(np.abs(ds["tangential_displacement"].values))) / scale
    w = float(np.max(ds["normal_displacement"].values)) / scale
    ax.set_xlim(-2.5 * r, 2.5 * r + slide)
    ax.set_ylim(-w - 2.0 * r, 0.5 * r)
    ax.set_aspect("equal")
    ax.set(xlabel=f"x [{unit}]", ylabel=f"z above the apex [{unit}]")


def _levels(values):
    top = float(np.nanmax(values)) if np.size(values) else 0.0
    return np.linspace(0.0, max(top, 1e-6), 11)


def sliding_figure(ds: xr.Dataset, length_unit: str = "um") -> plt.Figure:
    """(a) normal and tangential force versus time (Fig. 9.4); (b) the section y = 0
    at the end of pressing, equivalent inelastic strain; (c) the deformed section at
    the end with contours of the horizontal displacement (Fig. 9.5); (d) the
    equivalent inelastic strain at the end and where its maximum sits."""
    scale = units.length_scale(length_unit)
    fig, axes = subplots(2, 2, figsize=(12.0, 9.0))
    (ax_f, ax_p), (ax_u, ax_e) = axes
    t = ds["time"].values
    ax_f.plot(t, 1e3 * ds["normal_force"].values, "-o", ms=3, label="normal force")
    ax_f.plot(t, 1e3 * ds["tangential_force"].values, "-s", ms=3, label="tangential force")
    times = np.asarray(ds.attrs.get("motion_times", []), float)
    for tk in times[1:-1]:
        ax_f.axvline(tk, color="0.6", ls=":", lw=0.8)
    ax_f.set(xlabel="time [s]", ylabel="force [mN]")
    ax_f.legend(loc="best")
    notes = []
    tau = ds.attrs.get("mean_tangential_traction_sliding")
    if tau is not None and np.isfinite(tau):
        notes.append(f"mean tangential traction while sliding: {tau / 1e6:.0f} MPa "
                     "(report: about 64 MPa)")
    s_c = ds.attrs.get("critical_shear_factor")
    if s_c is not None and s_c < 1.0:
        notes.append(f"not unique while sliding: the junction's tangent turns singular at\n"
                     f"{s_c:.2g} times the shear resistance (the critical friction coefficient)")
    if "damped_solves" in ds:
        jumped = ds["damped_solves"].values > 0
        if jumped.any():
            ax_f.plot(t[jumped], 1e3 * ds["tangential_force"].values[jumped], "rx", ms=9,
                      mew=1.5, label="step through the slip (damped solves)")
            ax_f.legend(loc="best")
            notes.append(f"{int(jumped.sum())} steps taken through the slip instability "
                         "(x: damped solves)")
    if not ds.attrs.get("completed", 1):
        notes.append(f"stopped at t = {t[-1]:.0f} s of {times[-1]:.0f} s (stop_reason)"
                     if times.size else "stopped before the end (stop_reason)")
        ax_f.set_xlim(right=times[-1] if times.size else None)
    ax_f.set_title("\n".join(["Fig. 9.4: forces on the asperity (whole body)"] + notes),
                   fontsize=9)
    w_end = float(ds["normal_displacement"].values[-1])
    snaps = [str(s) for s in ds["snapshot"].values] if "snapshot" in ds.dims else []
    if "end of pressing" in snaps:
        tri = _section(ds, "end of pressing", scale)
        w_p = float(ds["snapshot_time"].sel(snapshot="end of pressing"))
        wp = float(np.interp(w_p, ds["time"].values, ds["normal_displacement"].values))
        ep = ds["plane_inelastic_strain"].sel(snapshot="end of pressing").values
        c = ax_p.tricontourf(tri, ep, levels=_levels(ep), cmap="magma_r")
        ax_p.triplot(tri, color="0.7", lw=0.2)
        ax_p.axhline(-wp / scale, color="k", lw=1.2)
        fig.colorbar(c, ax=ax_p, label="equivalent inelastic strain")
        where = ds.attrs.get("end_of_pressing_largest_deformation", "")
        d = ds.attrs.get("end_of_pressing_largest_deformation_depth_over_radius", np.nan)
        ax_p.set_title(f"end of pressing (t = {w_p:.0f} s): largest {where} "
                       f"(depth {d:.2f} a_ref)", fontsize=10)
        _zoom(ax_p, ds, scale, length_unit)
    else:
        ax_p.set_visible(False)
    if "end" in snaps:
        tri = _section(ds, "end", scale)
        ux = ds["plane_ux"].sel(snapshot="end").values / scale
        c = ax_u.tricontourf(tri, ux, levels=12, cmap="viridis")
        ax_u.triplot(tri, color="w", lw=0.2, alpha=0.5)
        ax_u.axhline(-w_end / scale, color="k", lw=1.2)
        fig.colorbar(c, ax=ax_u, label=f"horizontal displacement u_x [{length_unit}]")
        ax_u.set_title("Fig. 9.5: deformed section y = 0 at the end, u_x")
        _zoom(ax_u, ds, scale, length_unit)
        ep = ds["plane_inelastic_strain"].sel(snapshot="end").values
        c = ax_e.tricontourf(tri, ep, levels=_levels(ep), cmap="magma_r")
        ax_e.triplot(tri, color="0.7", lw=0.2)
        ax_e.axhline(-w_end / scale, color="k", lw=1.2)
        fig.colorbar(c, ax=ax_e, label="equivalent inelastic strain (node averages)")
        pos = ds.attrs.get("largest_deformation_position")
        disp = ds.attrs.get("largest_deformation_displacement")
        if pos is not None and disp is not None:
            p = (np.asarray(pos) + np.asarray(disp)) / scale
            ax_e.plot(p[0], p[2], "c*", ms=14, mec="k",
                      label=f"largest ({ds.attrs.get('largest_deformation_value', np.nan):.2f}) "
                            f"at y = {p[1]:.2f} {length_unit}")
            ax_e.legend(loc="lower left", fontsize=8)
        where = ds.attrs.get("largest_deformation", "")
        d = ds.attrs.get("largest_deformation_depth_over_radius", np.nan)
        ax_e.set_title(f"end: largest deformation {where} (depth {d:.2f} a_ref)", fontsize=10)
        _zoom(ax_e, ds, scale, length_unit)
    else:
        ax_u.set_visible(False)
        ax_e.set_visible(False)
    fig.suptitle(f"sliding asperity (report 9.2): {ds.attrs.get('dofs', '?')} dofs, "
                 f"{ds.attrs.get('steps', '?')} steps, accuracy {ds.attrs.get('accuracy', '?')}",
                 fontsize=11)
    return fit(fig)
