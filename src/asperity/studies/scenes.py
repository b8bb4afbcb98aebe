"""What accuracy costs for a whole scene: results/accuracy/scenes.nc.

A scene run at each accuracy preset (``results/<scene>@<preset>/interface.nc``, or the
scene's own folder at the run's preset)
gives the homogenized interface (report 2.5: the nominal pressure
p = n E(F) and the real contact area ratio n E(A) of eq. 2.7, on the loading
branch and, for scenes that unload, on the unloading branch of 8.3) and, in
its attributes, what its finite element asperities cost: the number of FE
jobs, their total CPU time, the largest Newton iteration, step-cut, dof and
time-step counts (`asperity.population.gather.gather`).  `scene_accuracy` puts these side
by side with the deviation of each preset's interface from the finest
preset's, so a user can pick a preset knowing its price.

The deviation (ours; the report has no such study) of a quantity q (nominal
pressure or contact area ratio) of preset P from the reference preset R, on
one branch, is

    max over h in S of |q_P(h) - q_R(h)| / |q_R(h)|,

where S holds the separations h that both runs computed (equal to within
1e-9 of the largest separation) at which q_R is finite and above
`threshold` (default 1e-3) times its largest value on that branch, and q_P
is finite.  No interpolation: the configured separations are common to
every preset, while the separations an unloading scene adds to resolve the
rebound (`asperity.stages.homogenize.REBOUND_POINTS`) depend on each run's own rebound
and are compared only where they coincide.  How many separations entered,
and where the largest deviation lies, are stored beside it, as is the largest
share of contacting asperities the gather extrapolated beyond their FE job's
last level: where it is large, the deviation measures the extrapolation (the
median step slope of the last tenth of the range, `asperity.population.gather`) as
much as the mesh.
The same deviation over the separations where the reference run holds (its
``valid``, `asperity.homogenize.validity`) is ``valid_deviation``.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import xarray as xr

from asperity.units import attrs

__all__ = ["QUANTITIES", "COST_ATTRS", "branch_deviation", "scene_accuracy"]

#: the interface variables compared, with the long name of their deviation
QUANTITIES = {
    "nominal_pressure": "nominal pressure n E(F) (eq. 2.7)",
    "contact_area_ratio": "real contact area ratio n E(A) (eq. 2.7)",
}

#: interface.nc attributes that say what the FE asperities cost: name -> (units, long name)
COST_ATTRS = {
    "fe_jobs": ("1", "number of finite element jobs of the scene run"),
    "fe_cpu_time": ("s", "total CPU time of the scene's finite element jobs"),
    "max_newton_iterations": ("1", "largest number of Newton iterations in one step of any FE job"),
    "max_step_cuts": ("1", "largest number of step cuts in one step of any FE job"),
    "max_dofs": ("1", "largest number of degrees of freedom of any FE job"),
    "max_time_steps": ("1", "largest number of load or time steps of any FE job"),
}

BRANCHES = ("loading", "unloading")

#: separations of two runs closer than this times the largest separation are the same
SAME_SEPARATION = 1e-9



def branch_deviation(
    separation: np.ndarray, values: np.ndarray,
    reference_separation: np.ndarray, reference: np.ndarray,
    threshold: float = 1e-3, mask: np.ndarray | None = None,
) -> tuple[float, float, int]:
    """Largest relative deviation of `values` from `reference` on one branch.

    Compared at the separations both grids hold (to `SAME_SEPARATION`
    relative), where the reference is finite and above `threshold` times its
    largest value, and `values` finite; with `mask` (on the reference's
    separations) only where it is true.  Returns (deviation, separation of
    the largest deviation (nan where the deviation is 0), number of
    separations compared); (nan, nan, 0) when none qualifies.
    """
    h, q = np.asarray(separation, float), np.asarray(values, float)
    hr, qr = np.asarray(reference_separation, float), np.asarray(reference, float)
    if h.shape != q.shape or hr.shape != qr.shape:
        raise ValueError("separations and values differ in shape")
    if h.size == 0 or hr.size == 0 or not np.isfinite(qr).any():
        return np.nan, np.nan, 0
    scale = max(np.abs(h).max(), np.abs(hr).max())
    gap = np.abs(hr[:, None] - h[None, :])  # (reference, run): small grids, one comparison each
    match = gap.argmin(axis=1)
    common = gap[np.arange(hr.size), match] <= SAME_SEPARATION * scale
    top = np.nanmax(np.abs(qr))
    qp = np.where(common, q[match], np.nan)
    use = common & np.isfinite(qr) & (np.abs(qr) > threshold * top) & np.isfinite(qp)
    if mask is not None:
        use &= np.asarray(mask, bool)
    if not use.any():
        return np.nan, np.nan, 0
    rel = np.abs(qp[use] - qr[use]) / np.abs(qr[use])
    i = int(np.argmax(rel))
    where = float(hr[use][i]) if rel[i] > 0 else np.nan  # no largest deviation where all are 0
    return float(rel[i]), where, int(use.sum())


def _branch(ds: xr.Dataset, name: str, branch: str) -> np.ndarray | None:
    """One branch of an interface variable; None where the run has no such branch."""
    var = ds[name]
    if "branch" in var.dims:
        labels = [str(b) for b in ds["branch"].values]
        return var.sel(branch=branch).values if branch in labels else None
    return var.values if branch == "loading" else None


def scene_accuracy(
    interfaces: Mapping[tuple[str, str], xr.Dataset],
    scenes: Sequence[str], presets: Sequence[str], *,
    reference: str | None = None, threshold: float = 1e-3,
    against: Mapping[str, str] | None = None,
) -> xr.Dataset:
    """Cost and deviation from the `reference` preset per (scene, preset).

    `interfaces` maps (scene, preset) to that run's interface dataset
    (``results/<scene>@<preset>/interface.nc``); `reference` defaults to the
    last of `presets` (the finest).  A run whose ``accuracy`` attribute names
    another preset is refused (the inputs were mixed up).  The deviation is
    defined in the module docstring; the reference's own is 0.  `against` maps a
    variant of a scene (e.g. the scene with the edge band, written ``like:`` it) to
    that scene: the variant runs at the presets but the reference and is compared with
    the scene's reference run, so that what the variant buys and costs stands beside
    the scene's own presets (NaN at the reference preset).
    """
    scenes, presets = list(scenes), list(presets)
    against = dict(against or {})
    reference = presets[-1] if reference is None else reference
    if reference not in presets:
        raise ValueError(f"reference preset {reference!r} is not among the presets {presets}")
    if not 0.0 <= threshold < 1.0:
        raise ValueError(f"threshold {threshold} must be in [0, 1)")
    missing = [f"{s}@{p}" for s in scenes for p in presets
               if (s, p) not in interfaces and not (s in against and p == reference)]
    if missing:
        raise ValueError(f"no interface for {', '.join(missing)}")
    for (s, p), ds in interfaces.items():
        got = str(ds.attrs.get("accuracy", p))
        if got != p:
            raise ValueError(f"interface of {s}@{p} was computed at accuracy {got!r}, not {p!r}")
    quantities = list(QUANTITIES)
    shape = (len(scenes), len(presets), len(quantities), len(BRANCHES))
    deviation, where = np.full(shape, np.nan), np.full(shape, np.nan)
    count = np.zeros(shape, int)
    valid_deviation, valid_count = np.full(shape, np.nan), np.zeros(shape, int)
    cost = {name: np.full((len(scenes), len(presets)), np.nan) for name in COST_ATTRS}
    extrapolated = np.full((len(scenes), len(presets)), np.nan)
    for i, s in enumerate(scenes):
        ref = interfaces[(against.get(s, s), reference)]
        for j, p in enumerate(presets):
            if (s, p) not in interfaces:
                continue  # a variant at the reference preset
            run = interfaces[(s, p)]
            for name in COST_ATTRS:
                cost[name][i, j] = float(run.attrs.get(name, np.nan))
            beyond = (_branch(run, "extrapolated_fraction", "loading")
                      if "extrapolated_fraction" in run else None)
            if beyond is not None and np.isfinite(beyond).any():
                extrapolated[i, j] = float(np.nanmax(beyond))
            for k, q in enumerate(quantities):
                for b, branch in enumerate(BRANCHES):
                    qr, qp = _branch(ref, q, branch), _branch(run, q, branch)
                    if qr is None and qp is None:
                        continue
                    if qr is None or qp is None:
                        raise ValueError(f"{s}: the {branch} branch is in only one of the runs at "
                                         f"{reference} and {p}")
                    deviation[i, j, k, b], where[i, j, k, b], count[i, j, k, b] = branch_deviation(
                        run["separation"].values, qp, ref["separation"].values, qr, threshold)
                    valid = _branch(ref, "valid", branch) if "valid" in ref else None
                    if valid is not None:
                        valid_deviation[i, j, k, b], _, valid_count[i, j, k, b] = branch_deviation(
                            run["separation"].values, qp, ref["separation"].values, qr, threshold,
                            mask=valid)
    dims4 = ("scene", "preset", "quantity", "branch")
    data = {
        "deviation": (dims4, deviation, attrs(
            "1", f"largest relative deviation from the {reference} preset over the separations both "
            f"runs computed where the {reference} value is above {threshold:g} of its largest")),
        "deviation_separation": (dims4, where, attrs(
            "m", "separation at which the largest deviation occurs")),
        "compared_separations": (dims4, count, attrs(
            "1", "number of separations compared (common to both runs, above the threshold)")),
        "valid_deviation": (dims4, valid_deviation, attrs(
            "1", f"the deviation over the separations where the {reference} run is valid "
            "(its interface.nc `valid`; NaN where none is)")),
        "valid_separations": (dims4, valid_count, attrs(
            "1", f"number of separations compared where the {reference} run is valid")),
    }
    for name, (units, long_name) in COST_ATTRS.items():
        data[name] = (("scene", "preset"), cost[name], attrs(units, long_name))
    data["max_extrapolated_fraction"] = (("scene", "preset"), extrapolated, attrs(
        "1", "largest fraction of contacting asperities beyond their FE job's largest interference "
        "(continued with the last tangent), loading branch, over all separations"))
    out = xr.Dataset(data, coords={
        "scene": ("scene", scenes, attrs("1", "scene")),
        "preset": ("preset", presets, attrs("1", "accuracy preset of the FE asperities")),
        "quantity": ("quantity", quantities, attrs("1", "compared interface quantity: "
                                                    + "; ".join(QUANTITIES.values()))),
        "branch": ("branch", list(BRANCHES), attrs(
            "1", "loading, or unloading from the separation unloading_from (report 8.3)")),
    })
    out.attrs.update(reference=reference, threshold=float(threshold),
                     variants="; ".join(f"{v}: against {s}" for v, s in against.items()))
    return out
