"""What accuracy costs for a sliding asperity: one 3-D sliding scene (report 9.2) at each
accuracy preset, each force history against the next finer preset's.

A run of the scene at a preset (``results/<scene>@<preset>/sliding.nc``) gives the normal
and tangential force on the flat at every accepted step (`asperity.fe.drivers.solid3d`).
:func:`sliding_accuracy` compares each preset with the next finer one, per force and
phase (pressing: 0 < t <= t_p, sliding: t > t_p, t_p the end of the pressing of the
scene's motion):

    d = max over t in S of |F_c(t) - F_f(t)| / max over the phase of |F_f|,

S the coarser run's step times in the phase.  Where every one of them is a step time of
the finer run (to 1e-9 relative: the presets whose steps land on the same grid of
`asperity.fe.drivers.flat_motion.step_grid`), the two are compared there, without
interpolating either; else the finer history is interpolated linearly in time onto S.
The tangential force while pressing is zero by symmetry and not compared.  Beside the
differences: what each run costs (degrees of freedom, steps, cuts, Newton iterations, the
solve's wall time) and its mean tangential traction while sliding, F_T / A, A the model's
contact area (the scene's ``mean_tangential_traction_sliding``).
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import xarray as xr

from asperity.units import attrs

__all__ = ["FORCES", "PHASES", "history_difference", "sliding_accuracy"]

FORCES = ("normal_force", "tangential_force")
PHASES = ("pressing", "sliding")

#: run attribute -> (units, long name) of what a run costs and what it finds
RUN_ATTRS = {
    "dofs": ("1", "degrees of freedom of the 3-D model"),
    "steps": ("1", "accepted steps"),
    "total_step_cuts": ("1", "step cuts"),
    "total_newton_iterations": ("1", "Newton iterations"),
    "total_wall_time": ("s", "wall time of the solve (one core)"),
    "mean_tangential_traction_sliding": ("Pa", "mean tangential traction F_T / A over the sliding steps "
                                               "with contact"),
}


def history_difference(coarse: tuple[np.ndarray, np.ndarray], fine: tuple[np.ndarray, np.ndarray],
                       phase: tuple[float, float]) -> tuple[float, bool]:
    """(d of the module text, whether the step times were shared) of one force over one
    phase (t0, t1]; `coarse` and `fine` are (times, forces).  NaN where the coarser run
    has no step in the phase or the finer one's force is zero there."""
    tc, fc = (np.asarray(a, float) for a in coarse)
    tf, ff = (np.asarray(a, float) for a in fine)
    t0, t1 = phase
    sel = (tc > t0) & (tc <= min(t1, tf[-1]) * (1 + 1e-12))
    own = (tf > t0) & (tf <= t1)
    if not sel.any() or own.sum() < 2:
        return np.nan, False
    peak = float(np.abs(ff[own]).max())
    if peak == 0.0:
        return np.nan, False
    i = np.clip(np.searchsorted(tf, tc[sel]), 1, tf.size - 1)
    nearest = np.where(np.abs(tf[i] - tc[sel]) <= np.abs(tf[i - 1] - tc[sel]), i, i - 1)
    shared = bool(np.all(np.abs(tf[nearest] - tc[sel]) <= 1e-9 * np.maximum(np.abs(tc[sel]), 1.0)))
    reference = ff[nearest] if shared else np.interp(tc[sel], tf, ff)
    return float(np.abs(fc[sel] - reference).max() / peak), shared


def sliding_accuracy(runs: Mapping[str, xr.Dataset], presets: Sequence[str]) -> xr.Dataset:
    """Module text.  `runs`: preset -> that run's sliding.nc, `presets` coarsest first."""
    presets = list(presets)
    missing = [p for p in presets if p not in runs]
    if missing:
        raise ValueError(f"no sliding run at {', '.join(missing)}")
    for p in presets:
        got = str(runs[p].attrs.get("accuracy", p))
        if got != p:
            raise ValueError(f"the run given for {p} was computed at accuracy {got!r}")
    press_end = float(runs[presets[0]].attrs["motion_times"][1])
    bounds = {"pressing": (0.0, press_end), "sliding": (press_end, np.inf)}
    pairs = list(zip(presets[:-1], presets[1:]))
    shape = (len(pairs), len(FORCES), len(PHASES))
    difference, shared = np.full(shape, np.nan), np.zeros(shape, np.int8)
    for i, (c, f) in enumerate(pairs):
        for j, force in enumerate(FORCES):
            for k, phase in enumerate(PHASES):
                if force == "tangential_force" and phase == "pressing":
                    continue  # zero by symmetry
                difference[i, j, k], shared[i, j, k] = history_difference(
                    (runs[c]["time"].values, runs[c][force].values),
                    (runs[f]["time"].values, runs[f][force].values), bounds[phase])
    dims = ("pair", "force", "phase")
    data = {
        "difference": (dims, difference, attrs(
            "1", "largest difference of the force history from the next finer preset's over the phase, "
                 "over the finer run's largest force there")),
        "shared_times": (dims, shared, attrs(
            "1", "1 where compared at step times both runs reached, 0 where the finer run was interpolated")),
    }
    for name, (units, long_name) in RUN_ATTRS.items():
        data[name] = ("preset", [float(runs[p].attrs.get(name, np.nan)) for p in presets], attrs(units, long_name))
    steps = max(runs[p].sizes["step"] for p in presets)
    for name, units, long_name in (("time", "s", "time of the step"),
                                   ("normal_force", "N", "normal force on the flat (whole model)"),
                                   ("tangential_force", "N", "tangential force on the flat (whole model)")):
        padded = np.full((len(presets), steps), np.nan)
        for i, p in enumerate(presets):
            padded[i, :runs[p].sizes["step"]] = runs[p][name].values
        data[f"history_{name}"] = (("preset", "step"), padded, attrs(units, f"{long_name}; NaN past the run's steps"))
    data["completed"] = ("preset", [int(runs[p].attrs.get("completed", 0)) for p in presets],
                         attrs("1", "1 where the run reached the end of its motion"))
    coords = {
        "pair": ("pair", [f"{c} vs {f}" for c, f in pairs], attrs("", "a preset against the next finer one")),
        "coarser": ("pair", [c for c, _ in pairs], attrs("", "the coarser preset of the pair")),
        "force": ("force", list(FORCES), attrs("", "force on the flat")),
        "phase": ("phase", list(PHASES), attrs("", f"pressing: 0 < t <= {press_end:g} s; sliding: after")),
        "preset": ("preset", presets, attrs("", "accuracy preset of the sliding run")),
        "step": ("step", np.arange(steps), attrs("1", "step of a run's history")),
    }
    return xr.Dataset(data, coords=coords, attrs={"sliding_scene": str(runs[presets[0]].attrs.get("scene", ""))
                                                  .partition("@")[0]})
