"""Figures drawn from the result datasets (never from anything else).

Files hold SI; figures show the scene's length unit where that reads better.
Each function returns a matplotlib Figure; ``asperity.io.figures`` saves it.
"""

from __future__ import annotations

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from asperity import units
from asperity.plots.layout import fit, subplots
from asperity.plots.material import is_elastic_fe, material_title, scene_material
from asperity.plots.validity import shade_invalid
from asperity.references.hertz import hertz_response


def finish(fig: plt.Figure, axes, fontsize: int = 8) -> plt.Figure:
    """Legend and major and minor grid on every panel, then the titles fitted
    (`asperity.plots.layout.fit`; the figure has the constrained layout)."""
    for ax in axes:
        if ax.get_legend_handles_labels()[1]:  # a panel with nothing labelled has no legend
            ax.legend(fontsize=fontsize)
        ax.grid(True, which="both", alpha=0.3)
    return fit(fig)


def expectation_figure(density_values: np.ndarray, z: np.ndarray, kappa: np.ndarray,
                       expectation: xr.Dataset) -> plt.Figure:
    """The peak density, its effective support and the integration cells (Fig. 2.10)."""
    fig, ax = subplots(figsize=(6.5, 4.8))
    positive = np.where(density_values > 0, density_values, np.nan)
    exponents = np.arange(-6, int(np.ceil(np.log10(np.nanmax(positive)))) + 1)
    cs = ax.contourf(z, kappa, positive.T, levels=10.0 ** exponents,
                     norm=matplotlib.colors.LogNorm(), cmap="viridis", extend="min")
    fig.colorbar(cs, ax=ax, label="f(z_p, κ)", ticks=10.0 ** exponents)
    s = expectation["support"].values
    r = expectation["rectangle"].values
    ax.add_patch(plt.Rectangle((s[0], s[2]), s[1] - s[0], s[3] - s[2], fill=False, ec="k", ls="--",
                               lw=1.5, label="effective support (f_ξη > 1e-4)"))
    ax.add_patch(plt.Rectangle((r[0], r[2]), r[1] - r[0], r[3] - r[2], fill=False, ec="r", lw=2,
                               label="integration rectangle"))
    pad_z, pad_k = 0.05 * (r[1] - r[0]), 0.05 * (r[3] - r[2])
    ax.set_xlim(r[0] - pad_z, r[1] + pad_z)
    ax.set_ylim(r[2] - pad_k, r[3] + pad_k)
    ax.set(xlabel="peak height z_p [m]", ylabel="tip curvature κ [1/m]",
           title=(f"raw integral (2.6) {float(expectation.integral):.10f}\n"
                  f"corrected E(X) (2.7) = {float(expectation.expectation):.12f}"))
    ax.legend(fontsize=8, loc="upper left")
    return fit(fig)


#: with adhesion the branches are the flat's approach and retraction (asperity.population.kinds.adhesive)
ADHESIVE_BRANCH = {"loading": "approach", "unloading": "retract"}


def _branch(ds: xr.Dataset, name: str) -> xr.Dataset | None:
    if "branch" not in ds.dims:
        return ds if name == "loading" else None
    if name not in ds["branch"].values:
        name = ADHESIVE_BRANCH.get(name, name)
    return ds.sel(branch=name) if name in ds["branch"].values else None


FRACTIONS = {"elastic_fraction": "elastic", "small_strain_fraction": "strains below 8 %",
             "extrapolated_fraction": "beyond the FE range",
             "extrapolated_load_fraction": "load beyond the FE range (share of p)"}


def interface_figure(interface: xr.Dataset, verification: xr.Dataset | None = None,
                     length_unit: str = "m", pressure_unit: str = "Pa",
                     others: dict[str, xr.Dataset] | None = None) -> plt.Figure:
    """Pressure, real contact area and normal stiffness versus separation, and pressure
    versus area (Figs. 7.1, 7.4, 7.11-7.13, 8.18, 8.19), the unloading branch dashed
    (Fig. 8.28); with inelastic asperities a fifth panel: the shares of contacting
    asperities still elastic and inside small-strain theory (Figs. 7.10, 7.14, 8.24);
    `others`: interfaces of compared scenes (their loading branch), drawn beside.

    The stiffness is the file's ``normal_stiffness`` k = -dp/dh [Pa/m] (report 2.5,
    the expectation of the asperity stiffness dF/dw), shown in `pressure_unit` per
    `length_unit`; the suptitle names the material (`asperity.plots.material`).
    Separations where the interface leaves its validity are shaded."""
    ls_ = units.length_scale(length_unit)
    ps = units.pressure_scale(pressure_unit)
    ks = ps / ls_
    shares = [n for n in FRACTIONS if n in interface and float(interface[n].max()) > 0]
    n = 4 + bool(shares)
    fig, axes = subplots(1, n, figsize=(4.6 * n, 4.4))

    def draw(ds, label, **style):
        h = ds["separation"].values / ls_
        p = ds["nominal_pressure"].values / ps
        a = ds["contact_area_ratio"].values
        axes[0].semilogy(h, p, label=label, **style)
        axes[1].semilogy(h, a, label=label, **style)
        if "normal_stiffness" in ds:
            axes[2].semilogy(h, ds["normal_stiffness"].values / ks, label=label, **style)
        axes[3].loglog(a, p, label=label, **style)

    adhesive = "retract_from" in interface.attrs  # branches approach, retract
    draw(_branch(interface, "loading"), "homogenized" if "branch" not in interface.dims else
         ("approach (p > 0 drawn)" if adhesive else "loading"), marker="o", ms=3, color="C0")
    unloading = _branch(interface, "unloading")
    if unloading is not None:
        turn = interface.attrs.get("retract_from" if adhesive else "unloading_from", np.nan)
        draw(unloading, f"{'retract' if adhesive else 'unloading'} from {turn / ls_:.3g} "
             f"{length_unit}", ls="--", marker=".", ms=3, color="C3")
    for i, (name, other) in enumerate((others or {}).items()):
        draw(_branch(other, "loading"), name, ls=":", marker="s", ms=3, color=f"C{i + 1}")
    if "extrapolated_fraction" in interface and float(interface["extrapolated_fraction"].max()) > 0:
        load_share = (f" ({100 * float(interface['extrapolated_load_fraction'].max()):.2g} % of the load)"
                      if "extrapolated_load_fraction" in interface else "")
        axes[1].set_title(f"largest share of contacts beyond the FE range: "
                          f"{100 * float(interface['extrapolated_fraction'].max()):.2g} %{load_share}",
                          fontsize=9)
    if verification is not None:
        h = interface["separation"].values / ls_
        pc = verification["nominal_pressure_closed_form"].values / ps
        ac = verification["contact_area_ratio_closed_form"].values
        axes[0].semilogy(h, pc, "k--", label="closed form")
        axes[1].semilogy(h, ac, "k--", label="closed form")
        if "normal_stiffness_closed_form" in verification:
            axes[2].semilogy(h, verification["normal_stiffness_closed_form"].values / ks, "k--",
                             label="closed form")
        axes[3].loglog(ac, pc, "k--", label="closed form")
        worst = verification.attrs.get("max_nominal_pressure_error", np.nan)
        axes[0].set_title(f"largest load error {100 * worst:.3f} % (load ≥ 1e-6 max)", fontsize=9)
    axes[0].set(xlabel=f"separation [{length_unit}]", ylabel=f"nominal pressure [{pressure_unit}]")
    axes[1].set(xlabel=f"separation [{length_unit}]", ylabel="real contact area ratio A/A0")
    axes[2].set(xlabel=f"separation [{length_unit}]",
                ylabel=f"normal stiffness -dp/dh [{pressure_unit}/{length_unit}]")
    if "normal_stiffness" not in interface:
        axes[2].set_title("no normal_stiffness in the file", fontsize=9)
    axes[3].set(xlabel="real contact area ratio A/A0", ylabel=f"nominal pressure [{pressure_unit}]")
    if shares:
        _shares_panel(axes[4], interface, shares, others or {}, ls_, length_unit)
    load = _branch(interface, "loading")
    h_load = load["separation"].values / ls_
    shade_invalid(axes, [h_load, h_load, h_load, load["contact_area_ratio"].values, h_load], load)
    title = material_title(interface, pressure_unit)
    if title:
        fig.suptitle(title, fontsize=10)
    return finish(fig, axes, fontsize=8)


def _shares_panel(ax, interface: xr.Dataset, shares: list[str], others: dict[str, xr.Dataset],
                  ls_: float, length_unit: str) -> None:
    """The shares of contacting asperities still elastic, inside small strain, or beyond
    the FE range, against separation (loading branch; compared scenes dotted)."""
    load = _branch(interface, "loading")
    for i, name in enumerate(shares):
        ax.plot(load["separation"].values / ls_, 100 * load[name].values, marker="o",
                ms=3, color=f"C{i + 4}", label=FRACTIONS[name])
    for oname, other in others.items():
        for i, name in enumerate(shares):
            if name in other:
                o = _branch(other, "loading")
                ax.plot(o["separation"].values / ls_, 100 * o[name].values, ls=":",
                        color=f"C{i + 4}", label=f"{oname}: {FRACTIONS[name]}")
    ax.set(xlabel=f"separation [{length_unit}]", ylim=(-2, 102),
           ylabel="share of contacting asperities (or of p) [%]")


def unloading_figure(unloading: xr.Dataset, length_unit: str = "m", count: int = 8) -> plt.Figure:
    """The family of unloading paths of one asperity (Figs. 8.26, 8.27): its
    loading curve, the computed paths (thick), `count` blended paths (thin)
    and the path left out of the blend against the blend from its level."""
    ls_ = units.length_scale(length_unit)
    i = unloading.sizes["curvature"] // 2
    one = unloading.isel(curvature=i)
    fig, ax = subplots(figsize=(7, 5))
    top = float(np.nanmax(one["computed_maximum_interference"].values))
    wm_all = one["maximum_interference"].values
    load = one["path_force"].values[:, -1]  # every path starts on the loading curve
    keep = wm_all <= top
    ax.plot(wm_all[keep] / ls_, load[keep], "k-", lw=1.5, label="loading")
    lo = float(one["lowest_level"])
    picks = np.unique(np.searchsorted(wm_all, np.geomspace(lo, top, count)).clip(0, wm_all.size - 1))
    for n, j in enumerate(picks):
        ax.plot(one["path_interference"].values[j] / ls_, one["path_force"].values[j], color="C0",
                lw=0.7, label="blended" if n == 0 else None)
    W, F = one["computed_unloading_interference"].values, one["computed_unloading_force"].values
    left = one["computed_left_out"].values
    for j in range(W.shape[0]):
        ok = np.isfinite(W[j])
        if not ok.any():
            continue
        style = dict(color="C3", ls="--", lw=2, label="computed, left out (γ0)") if left[j] else \
            dict(color="C1", lw=2, label="computed" if j == 0 else None)
        ax.plot(W[j][ok] / ls_, F[j][ok], **style)
    err = float(one["check_force_error"])
    title = f"κ = {float(one['curvature']) * ls_:.3g} 1/{length_unit}"
    if np.isfinite(err):
        title += f"; blend vs left-out path: {100 * err:.2g} % of its peak force"
    ax.set(xlabel=f"interference [{length_unit}]", ylabel="force [N]", title=title,
           xlim=(0, 1.05 * top / ls_))
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return fit(fig)


def asperities_figure(asperities: xr.Dataset, others: dict[str, xr.Dataset] | None = None,
                      length_unit: str = "m", pressure_unit: str = "Pa") -> plt.Figure:
    """Force and contact area of single asperities versus interference at three
    curvatures (Figs. 7.2, 7.3); compared scenes' asperities dotted.

    Beside each curve of finite element asperities of an elastic body
    (`asperity.plots.material.is_elastic_fe`), dashed in black, the Hertz
    solution at the sample's curvature kappa and the file's material (report 6.1,
    `asperity.references.hertz.hertz_response`): P = 4/3 E* R^(1/2) w^(3/2),
    A = pi R w, E* = E/(1 - nu^2), R = 1/kappa; a third panel shows the FE force
    and area over Hertz's (cf. Fig. 6.5).  The suptitle names the material
    (stresses in `pressure_unit`)."""
    ls_ = units.length_scale(length_unit)
    sets = {"this scene": asperities, **(others or {})}
    materials = {name: scene_material(ds) if is_elastic_fe(ds) else {} for name, ds in sets.items()}
    with_hertz = {name for name, m in materials.items() if "youngs_modulus" in m and "poisson" in m}
    fig, axes = subplots(1, 2 + bool(with_hertz), figsize=(5.5 * (2 + bool(with_hertz)), 4.6))
    curv = asperities["curvature"].values
    picks = sorted(set([0, curv.size // 2, curv.size - 1]))
    hertz_label = "Hertz (6.1), same κ, E, ν"
    for s_i, (name, ds) in enumerate(sets.items()):
        material = materials[name]
        hertz = name in with_hertz
        ds = _branch(ds, "loading")
        for c_i, j in enumerate(picks):
            k = curv[j]
            one = ds.sel(curvature=k, method="nearest").isel(height=0)
            w = one["interference"].values
            keep = w > 0
            label = f"{name}, κ = {k * ls_:.3g} 1/{length_unit}"
            style = dict(color=f"C{c_i}", ls="-" if s_i == 0 else ":", label=label)
            axes[0].loglog(w[keep] / ls_, one["force"].values[keep], **style)
            axes[1].loglog(w[keep] / ls_, one["contact_area"].values[keep] / ls_**2, **style)
            if hertz:
                ref = hertz_response(w[keep], float(one["curvature"]), material["youngs_modulus"],
                                     material["poisson"])
                style = dict(color="k", ls="--", lw=0.9, zorder=3, gid="hertz", label=hertz_label)
                axes[0].loglog(w[keep] / ls_, ref["force"], **style)
                axes[1].loglog(w[keep] / ls_, ref["contact_area"] / ls_**2, **style)
                hertz_label = None  # once in each legend
                ratio_style = dict(color=f"C{c_i}", ls="-" if s_i == 0 else ":")
                axes[2].semilogx(w[keep] / ls_, one["force"].values[keep] / ref["force"],
                                 label="force" if c_i + s_i == 0 else None, **ratio_style)
                axes[2].semilogx(w[keep] / ls_, one["contact_area"].values[keep] / ref["contact_area"],
                                 marker=".", ms=3, label="contact area" if c_i + s_i == 0 else None,
                                 **ratio_style)
            if "extrapolated" in one and s_i == 0:
                beyond = one["extrapolated"].values & keep
                if beyond.any():
                    axes[0].loglog(w[beyond] / ls_, one["force"].values[beyond], "x",
                                   color=f"C{c_i}", ms=3)
    axes[0].set(xlabel=f"interference [{length_unit}]", ylabel="force [N]",
                title="single asperities (x: beyond the FE range)")
    axes[1].set(xlabel=f"interference [{length_unit}]", ylabel=f"contact area [{length_unit}^2]")
    if "max_kink_contact_area" in asperities.attrs:  # FE jobs (asperity.population.gather)
        axes[1].set_title(
            f"FE curves kink by up to {100 * asperities.attrs['max_kink_force']:.1f} % (force), "
            f"{100 * asperities.attrs['max_kink_contact_area']:.1f} % (area) from step to step",
            fontsize=9)
    if with_hertz:
        axes[2].axhline(1.0, color="k", ls="--", lw=0.9)
        axes[2].set(xlabel=f"interference [{length_unit}]", ylabel="FE / Hertz [1]",
                    title="finite elements over Hertz (dots: contact area)")
    title = material_title(asperities, pressure_unit)
    if title:
        fig.suptitle(title, fontsize=10)
    return finish(fig, axes, fontsize=7)


def hertz_verification_figure(ds: xr.Dataset) -> plt.Figure:
    """Finite element asperities against Hertz (report Figs. 6.5, 6.6)."""
    fig, axes = subplots(1, 3, figsize=(15, 4.2))
    w = ds["interference"].values
    axes[0].plot(w, ds["hertz_force"], "k-", label="Hertz")
    axes[1].plot(w, ds["hertz_contact_radius"], "k-", label="Hertz")
    markers = {"paraboloid": "o", "sphere": "s"}
    for b in ds["body"].values:
        for r_i, run in enumerate(ds["run"].values):
            f = ds["force"].sel(body=b, run=run).values
            if np.all(np.isnan(f)):
                continue
            style = dict(marker=markers.get(str(b), "^"), ls="none", color=f"C{r_i}",
                         mfc="none" if b == "sphere" else None, label=f"{b}, {run}")
            axes[0].plot(w, f, **style)
            axes[1].plot(w, ds["contact_radius"].sel(body=b, run=run).values, **style)
            axes[2].plot(w, 100 * ds["force_error"].sel(body=b, run=run).values,
                         ls="-" if b == "paraboloid" else "--", marker=style["marker"],
                         color=f"C{r_i}", mfc=style["mfc"], label=f"load, {b}, {run}")
    axes[2].axhline(1.0, color="r", lw=0.8, ls=":", label="±1 % (standard bound)")
    axes[2].axhline(-1.0, color="r", lw=0.8, ls=":")
    axes[0].set(xlabel="interference w", ylabel="load P", title="load (Fig. 6.6)")
    axes[1].set(xlabel="interference w", ylabel="contact radius r")
    axes[2].set(xlabel="interference w", ylabel="load error against Hertz [%]",
                title="report 1993: up to 17.5 % (Fig. 6.5)")
    for ax in axes:
        ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    return fit(fig)
