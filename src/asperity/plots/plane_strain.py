"""Figures of the plane-strain asperities (report 6.3.2, Figs. 6.15 to 6.18; 6.3.3, Figs.
6.19 to 6.23), from plane_strain.nc only (`asperity.studies.plane_strain` writes it).

Files hold SI; the figure shows the interference in the scene's length unit and forces
per unit length in kN/m (= N/mm).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units
from asperity.fe.outputs import SMALL_STRAIN_LIMIT
from asperity.plots.layout import fit, subplots

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
    it, and where the history unloads the viscoplastic body's unloading (dotted) to its
    permanent set (the residual interference, a marker); (b) the largest nonelastic
    strain against interference; (c) for a cylinder the contact half width against
    force beside the plane-strain Hertz solution, for the ridge the viscoplastic force
    over the elastic one."""
    scale = units.length_scale(length_unit)
    figs, what = _what(ds)
    fig, (ax_f, ax_e, ax_c) = subplots(1, 3, figsize=(15.0, 4.6))
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
        if "residual_interference" in ds:
            peak = int(np.nanargmax(wi))
            residual = float(m["residual_interference"]) / scale
            ax_f.plot(wi[peak:], KN * m["step_force"].values[peak:], color=colour, ls=":",
                      label=f"viscoplastic unloading, {mesh} mesh: permanent set "
                            f"{residual:.3g} {length_unit}")
            ax_f.plot([residual], [0.0], color=colour, marker="o", ms=4)
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
    return fit(fig)


def _triangulation(m: xr.Dataset, scale: float, deformed: bool):
    """The mesh `m` (one ``mesh`` of plane_strain.nc, its padding dropped) as a matplotlib
    triangulation in the length unit `scale`, undeformed or at the end of the history."""
    from matplotlib.tri import Triangulation

    nv, ne = int(m["vertices"]), int(m["triangles"])
    x = m["vertex_r"].values[:nv]
    z = m["vertex_z"].values[:nv]
    if deformed:
        x = x + m["vertex_displacement_r"].values[:nv]
        z = z + m["vertex_displacement_z"].values[:nv]
    return Triangulation(x / scale, z / scale, m["triangle_vertices"].values[:ne])


def plane_strain_mesh_figure(ds: xr.Dataset, length_unit: str = "um") -> plt.Figure:
    """Each mesh of the study (rows): (a) the whole section, as Figs. 6.15, 6.16, 6.19 and
    6.20 draw it; (b) the same mesh near the contact; (c) the viscoplastic body there at
    the end of the history (at the largest interference, or unloaded to zero force),
    displacements at true scale, each element coloured by its nonelastic strain on a
    log scale (Fig. 6.21), with the rigid flat; a white line
    around the elements whose strain is past the small-strain range
    (`SMALL_STRAIN_LIMIT`, report 7.3), red outlines on the elements the displacement
    turns inside out."""
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.colors import LogNorm

    scale = units.length_scale(length_unit)
    figs, what = _what(ds)
    meshes = list(ds["mesh"].values)
    a = float(ds["contact_half_width"].sel(body="viscoplastic").isel(mesh=-1, interference=-1))
    half = 2.5 * a / scale
    strain = ds["element_inelastic_strain"]
    # a log scale over three decades: the strain at the ridge's corners is a hundred times
    # that of most of its top; below the decades, the lowest colour
    norm = LogNorm(vmin=1e-3 * float(strain.max()), vmax=float(strain.max()))
    fig, axes = subplots(len(meshes), 3, figsize=(15.0, 4.4 * len(meshes)), squeeze=False)
    for row, mesh in zip(axes, meshes):
        m = ds.sel(mesh=mesh)
        ax_all, ax_near, ax_def = row
        tri = _triangulation(m, scale, deformed=False)
        for ax in (ax_all, ax_near):
            ax.triplot(tri, color="k", lw=0.3)
        ax_all.set(title=f"{mesh} mesh: {int(m['vertices'])} vertices, "
                         f"{int(m['triangles'])} elements, "
                         f"{int(m['dofs'].sel(body='viscoplastic'))} dofs")
        ax_near.set(xlim=(0.0, half), ylim=(-0.8 * half, 0.2 * half),
                    title=f"{mesh} mesh near the contact")
        ne = int(m["triangles"])
        steps = m["step_interference"].values
        w_end = float(steps[np.isfinite(steps)][-1]) / scale
        deformed = _triangulation(m, scale, deformed=True)
        ep = m["element_inelastic_strain"].values[:ne]
        pc = ax_def.tripcolor(deformed, facecolors=np.maximum(ep, norm.vmin), cmap="viridis",
                              norm=norm, edgecolors="k", lw=0.15)
        corners = np.stack((deformed.x[deformed.triangles], deformed.y[deformed.triangles]), -1)
        past = _outline(deformed, ep > SMALL_STRAIN_LIMIT)
        if len(past):
            ax_def.add_collection(LineCollection(
                past, colors="w", lw=1.2,
                label=f"strain past {SMALL_STRAIN_LIMIT:.0%} inside (small strain, report 7.3)"))
        inverted = m["element_jacobian"].values[:ne] <= 0
        if inverted.any():
            ax_def.add_collection(PolyCollection(
                corners[inverted], facecolors="none", edgecolors="tab:red", lw=1.0,
                label=f"{int(inverted.sum())} elements inside out"))
        ax_def.axhline(-w_end, color="tab:red", lw=1.0, ls="--",
                       label=f"rigid flat, w = {w_end:.4g} {length_unit}")
        ax_def.set(xlim=(0.0, half), ylim=(-w_end - 0.8 * half, -w_end + 0.2 * half),
                   title=f"{'unloaded' if ds.attrs.get('unloading') else 'at the end'}, true "
                         f"scale (element means up to "
                         f"{float(m['element_inelastic_strain'].max()):.3g})")
        ax_def.legend(fontsize=7, loc="lower right")
        fig.colorbar(pc, ax=ax_def, label="equivalent nonelastic strain [1]")
        for ax in row:
            ax.set_aspect("equal")
            ax.set(xlabel=f"x [{length_unit}]", ylabel=f"z [{length_unit}]")
    fig.suptitle(f"{what}: the meshes and the deformed body ({_mesh_figs(ds)})")
    return fit(fig)


def _outline(tri, inside: np.ndarray) -> np.ndarray:
    """The boundary of the elements of `tri` flagged `inside`: the segments (k, 2, 2) of
    their edges that no other flagged element shares."""
    t = tri.triangles[inside]
    edges = np.sort(np.concatenate((t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]])), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    e = unique[count == 1]
    return np.stack((np.stack((tri.x[e[:, 0]], tri.y[e[:, 0]]), -1),
                     np.stack((tri.x[e[:, 1]], tri.y[e[:, 1]]), -1)), 1)


def _mesh_figs(ds: xr.Dataset) -> str:
    """The report's figures of the meshes and the deformed body of the section."""
    if ds.attrs.get("shape") == "cylinder":
        return "Figs. 6.15, 6.16"
    return "Figs. 6.19-6.21"
