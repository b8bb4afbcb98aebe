"""Figures of the uniaxial material-point scenes and of the integrators' accuracy study.

Drawn from the result Datasets only (`asperity.studies.uniaxial` writes them):
``uniaxial_figure`` from ``results/<scene>/uniaxial.nc`` (panels like the
report's Figs. 5.1 to 5.4, 6.14 and 8.13), ``uniaxial_accuracy_figure`` from
``results/accuracy/bodner_partom.nc``.  Files hold SI; figures show MPa,
strain in %, time in s.  Each function returns a matplotlib Figure;
``asperity.io.figures.save_figure`` saves it.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from matplotlib.lines import Line2D

from asperity.plots.layout import fit, subplots

#: variable -> (factor from SI, axis label)
AXES = {
    "time": (1.0, "time [s]"),
    "strain": (100.0, "axial strain [%]"),
    "stress": (1e-6, "axial stress [MPa]"),
    "damage": (1.0, "damage w [1]"),
    "hardness": (1e-6, "hardness Z = Z^I + Z^D [MPa]"),
}
INTEGRATOR_STYLE = {
    "implicit": dict(ls="-", marker="o", mfc=None, label="implicit (backward Euler)"),
    "explicit": dict(ls="--", marker="s", mfc="none", label="explicit (predictor-corrector)"),
}


def _text(values) -> list[str]:
    return [str(v) for v in np.asarray(values)]


def uniaxial_figure(ds: xr.Dataset) -> plt.Figure:
    """One panel per ``panel`` of the tests (in the order they come), each
    test drawn as its ``plot`` says (x-y of time, strain, stress, damage,
    hardness).  Ruptures are marked with a cross; where a test has no
    hardening and a constant strain rate, its closed-form flow stress is a
    dashed line."""
    tests = _text(ds["test"].values)
    panels = list(dict.fromkeys(_text(ds["panel"].values)))
    ncol = min(3, len(panels))
    nrow = math.ceil(len(panels) / ncol)
    fig, axes = subplots(nrow, ncol, figsize=(5.2 * ncol, 3.9 * nrow), squeeze=False)
    flat = list(axes.ravel())
    for ax in flat[len(panels):]:
        ax.set_axis_off()
    for p, (panel, ax) in enumerate(zip(panels, flat)):
        members = [i for i, t in enumerate(tests) if str(ds["panel"].values[i]) == panel]
        labels = set()
        for j, i in enumerate(members):
            one = ds.isel(test=i)
            n = int(one["records"])
            xv, yv = str(one["plot"].values).split("-")
            fx, lx = AXES[xv]
            fy, ly = AXES[yv]
            x = one[xv].values[:n] * fx
            y = one[yv].values[:n] * fy
            color = f"C{j}"
            ax.plot(x, y, "-", color=color, lw=1.3,
                    label=f"{tests[i]} ({int(one['steps'])} steps)")
            labels.update({lx: "x", ly: "y"})
            if bool(one["ruptured"]):
                ax.plot([x[-1]], [y[-1]], "x", color="k", ms=9, mew=2)
                ax.annotate(f"rupture t = {float(one['rupture_time']):.4g} s,"
                            f" w = {float(one['damage'].values[n - 1]):.3g}",
                            (x[-1], y[-1]), textcoords="offset points", xytext=(-8, -14),
                            ha="right", fontsize=7)
            flow = float(one["flow_stress_initial"])
            mechanisms = any(bool(one[f"effect_{m}"]) for m in
                             ("isotropic_hardening", "recovery", "directional_hardening", "damage"))
            if yv == "stress" and np.isfinite(flow) and not mechanisms:
                ax.axhline(flow * fy, color=color, ls="--", lw=0.9,
                           label=f"closed form, Z = Z0: {flow * fy:.1f} MPa")
            ax.set_xlabel(lx)
            ax.set_ylabel(ly)
        ax.set_title(f"({chr(97 + p)}) {panel}", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(ds.attrs.get("title", "uniaxial tests"), fontsize=10)
    return fit(fig)


def _positive(values) -> np.ndarray:
    v = np.asarray(values, float)
    return np.where(v > 0, v, np.nan)     # log axes: an exact zero is not drawn


def _sweep_panel(ax, ds: xr.Dataset, xvar: str):
    tests = _text(ds["test"].values)
    target = float(ds.attrs.get("target", 0.01))
    pi = float(ds.attrs.get("pairing_implicit_tolerance", np.nan))
    pe = float(ds.attrs.get("pairing_explicit_tolerance", np.nan))
    tol = ds["indicator_tolerance"].values
    for j, test in enumerate(tests):
        color = f"C{j}"
        for g in _text(ds["integrator"].values):
            st = INTEGRATOR_STYLE[g]
            x = ds[xvar].sel(integrator=g, test=test).values
            y = 100 * _positive(ds["error"].sel(integrator=g, test=test).values)
            ok = np.isfinite(x) & np.isfinite(y)
            ax.plot(x[ok], y[ok], ls=st["ls"], marker=st["marker"], color=color,
                    mfc=color if st["mfc"] is None else st["mfc"], ms=5, lw=1.1)
            pair = pi if g == "implicit" else pe
            k = np.nonzero(np.isclose(tol, pair))[0]
            if k.size and ok[k[0]]:
                ax.plot(x[k[0]], y[k[0]], marker="o", ms=12, mfc="none", mec=color, mew=1.5)
    ax.axhline(100 * target, color="r", ls=":", lw=1)
    ax.text(0.01, 100 * target, f" target {100 * target:g} %", color="r", fontsize=7,
            va="bottom", transform=ax.get_yaxis_transform())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel("end error against the ODE reference [%]")
    ax.grid(True, which="major", alpha=0.3)


def uniaxial_accuracy_figure(ds: xr.Dataset) -> plt.Figure:
    """1 x 3: end error vs steps, vs wall time (each integrator over its
    tolerance sweep; circled: the study's pairing of tolerances), and the step
    ratios explicit / implicit per test (the pairing and matched accuracy)."""
    tests = _text(ds["test"].values)
    fig, axes = subplots(1, 3, figsize=(17.0, 5.0))
    _sweep_panel(axes[0], ds, "steps")
    axes[0].set_xlabel("accepted integration steps [1]")
    axes[0].set_title("(a) end error vs steps (tolerance sweep)")
    handles = [Line2D([], [], color=f"C{j}", lw=2, label=t) for j, t in enumerate(tests)]
    handles += [Line2D([], [], color="0.3", ls=s["ls"], marker=s["marker"],
                       mfc="0.3" if s["mfc"] is None else "none", label=s["label"])
                for s in INTEGRATOR_STYLE.values()]
    pi = ds.attrs.get("pairing_implicit_tolerance", np.nan)
    pe = ds.attrs.get("pairing_explicit_tolerance", np.nan)
    handles.append(Line2D([], [], ls="none", marker="o", ms=11, mfc="none", mec="0.3",
                          label=f"pairing: implicit tol {pi:g}, explicit tol {pe:g}"))
    axes[0].legend(handles=handles, fontsize=7, loc="lower left")
    _sweep_panel(axes[1], ds, "wall_time")
    axes[1].set_xlabel("wall time [s]")
    axes[1].set_title("(b) end error vs wall time")

    ax = axes[2]
    x = np.arange(len(tests))
    ref = ds["steps_ratio_reference"].values
    matched = ds["steps_ratio_matched"].values
    ax.bar(x - 0.2, ref, 0.4, color="C0",
           label="explicit reference / implicit default (pairing)")
    ax.bar(x + 0.2, matched, 0.4, color="C1",
           label=f"matched: fewest steps within {100 * float(ds.attrs.get('target', 0.01)):g} %")
    for xi, r, m in zip(x, ref, matched):
        for dx, v in ((-0.2, r), (0.2, m)):
            if np.isfinite(v):
                ax.text(xi + dx, v, f"{v:.1f}", ha="center", va="bottom", fontsize=7)
    ax.axhline(20, color="k", ls="--", lw=1, label="20x fewer steps (target)")
    ax.axhline(1, color="0.5", ls=":", lw=1)
    ax.set_yscale("log")
    top = np.nanmax(np.concatenate([ref, matched, [20.0]]))
    ax.set_ylim(top=8 * top)                    # room for the legend above the bars
    ax.set_xticks(x, tests, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("explicit steps / implicit steps [1]")
    ax.set_title("(c) how many more steps the explicit integrator takes")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(True, axis="y", which="major", alpha=0.3)
    fig.suptitle(f"Bodner-Partom material point: implicit against explicit integration "
                 f"(reference: {ds.attrs.get('reference', '')})", fontsize=10)
    return fit(fig)
