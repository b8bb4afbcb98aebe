"""Figures of the plane-strain asperities (report 6.3.2, Figs. 6.17 and 6.18; 6.3.3, Figs.
6.21 to 6.23), from plane_strain.nc only (`asperity.plane_strain` writes it).

Files hold SI; the figure shows the interference in the scene's length unit and forces
per unit length in kN/m (= N/mm).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units

#: line style of each body, colour of each mesh (in the file's order)
BODY_STYLE = {"elastic": dict(ls="--"), "viscoplastic": dict(ls="-")}
MESH_COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple")
KN = 1e-3


def _what(ds: xr.Dataset) -> tuple[str, str]:
    """The report's figures and the panel title of the section."""
    if ds.attrs.get("shape") == "cylinder":
        return "Figs. 6.17, 6.18", "cylinder (6.3.2)"
    return "Figs. 6.21-6.23", "truncated V ridge (6.3.3)"


def plane_strain_figure(ds: xr.Dataset, length_unit: str = "um") -> plt.Figure:
    """(a) force per length against interference, elastic (dashed) and viscoplastic
    (solid) on each mesh, with the experiment's load per asperity if the scene gives
    it; (b) the largest nonelastic strain against interference; (c) for a cylinder the
    contact half width against force beside the plane-strain Hertz solution, for the
    ridge the viscoplastic force over the elastic one."""
    scale = units.length_scale(length_unit)
    figs, what = _what(ds)
    fig, (ax_f, ax_e, ax_c) = plt.subplots(1, 3, figsize=(15.0, 4.6))
    w = ds["interference"].values / scale
    for j, mesh in enumerate(ds["mesh"].values):
        colour = MESH_COLOURS[j % len(MESH_COLOURS)]
        m = ds.sel(mesh=mesh)
        dofs = int(m["dofs"].sel(body="viscoplastic"))
        for body in ds["body"].values:
            ax_f.plot(np.r_[0.0, w], np.r_[0.0, KN * m["force"].sel(body=body).values],
                      color=colour, label=f"{body}, {mesh} mesh ({dofs} dofs)",
                      **BODY_STYLE.get(str(body), {}))
        wi = m["step_interference"].values / scale
        ax_e.plot(wi, m["step_inelastic_strain"].values, color=colour,
                  label=f"{mesh} mesh: largest {float(m['largest_inelastic_strain']):.3g}")
        if "hertz_half_width" in ds:
            for body in ds["body"].values:
                ax_c.plot(KN * m["force"].sel(body=body).values,
                          m["contact_half_width"].sel(body=body).values / scale, color=colour,
                          marker="o" if body == "elastic" else None, ms=3, mfc="none",
                          label=f"{body}, {mesh} mesh", **BODY_STYLE.get(str(body), {}))
        else:
            f = m["force"]
            ax_c.plot(w, (f.sel(body="viscoplastic") / f.sel(body="elastic")).values,
                      color=colour, label=f"{mesh} mesh")
    if "test_load" in ds.attrs:
        ax_f.axhline(KN * float(ds.attrs["test_load"]), color="0.4", lw=0.8, ls=":",
                     label="test's load per asperity (our estimate)")
    ax_f.set(xlabel=f"interference w [{length_unit}]", ylabel="force per length [kN/m]",
             title=f"{what}: force against interference ({figs})")
    ax_f.legend(fontsize=7, loc="upper left")
    ax_e.set(xlabel=f"interference w [{length_unit}]",
             ylabel="largest equivalent nonelastic strain [1]",
             title="nonelastic strain (viscoplastic body)")
    if ds.attrs.get("shape") == "truncated_v":
        ax_e.axhline(0.8, color="0.4", lw=0.8, ls=":", label="report 6.3.3: about 80 %")
    ax_e.legend(fontsize=7, loc="upper left")
    if "hertz_half_width" in ds:
        ref = ds["hertz_half_width"].isel(mesh=-1)
        f_el = ds["force"].sel(body="elastic").isel(mesh=-1)
        ax_c.plot(KN * f_el.values, ref.values / scale, color="k", lw=0.8,
                  label="Hertz (plane strain), a = 2 sqrt(F'R/(pi E*))")
        ax_c.set(xlabel="force per length [kN/m]", ylabel=f"contact half width a [{length_unit}]",
                 title="contact half width against force")
    else:
        ax_c.set(xlabel=f"interference w [{length_unit}]",
                 ylabel="viscoplastic / elastic force [1]", title="force ratio")
    ax_c.legend(fontsize=7, loc="best")
    for ax in (ax_f, ax_e, ax_c):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig
