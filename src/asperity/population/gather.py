"""Asperity models: how a sample of the plan becomes a response.

An asperity model is named in a scene's ``asperity`` section:

- ``hertz``: the analytic sphere of report 6.1 (no job of its own);
- ``constant``: X = value, the check of report 2.6.2;
- ``fe``: the finite element asperity of `asperity.fe`, one job per key,
  with a geometry:

  * ``sphere`` / ``paraboloid`` of radius 1/kappa (the paraboloid is Hertz's
    idealization: a half space with a paraboloidal gap);
  * ``cosine`` with the ``representative`` mapping of report 8.2: every
    hill has the width-to-height ratio of a cosine whose rms slope is the
    surface's, pi / (sqrt(2) sigma_slope), and the sample's tip curvature
    kappa = C k^2 (2.5.1); its peak height only shifts the interference;
  * ``cosine`` with the ``coupled`` mapping of 2.5.1: the hill
    z = C cos(k r) of the sample has amplitude C = z_p (its peak height
    above the mean plane) and tip curvature kappa = C k^2.  Only peaks above
    the mean plane are hills; they touch a flat at separation h >= 0 with
    w = z_p - h <= C, half their height.

Sphere, paraboloid and the representative hill respond to the interference
alone (shift invariant in height): one job per curvature.  The coupled hill
depends on both: one job per (height, curvature).  An FE job computes a geometric
sequence of levels up to the largest interference the geometry admits
(`max_interference`); the gather interpolates each sample onto the plan's
interference grid in log-log space (monotone cubic), continues below the
first level with the local power law and above the last with the last
tangent, and flags the latter as ``extrapolated``.
"""

from __future__ import annotations

import json
import math
import time
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity.scene import materials

Config = Mapping[str, Any]

ANALYTIC = ("hertz", "constant")

def is_analytic(asperity: Config) -> bool:
    return asperity["model"] in ANALYTIC


def is_coupled(asperity: Config) -> bool:
    return asperity.get("geometry") == "cosine" and asperity.get("mapping", "representative") == "coupled"


def is_shift_invariant(asperity: Config) -> bool:
    """Response depends on the interference only, not on the peak height."""
    return not is_coupled(asperity)


def representative_width_to_height(sigma_slope: float) -> float:
    """Width/height of a cosine hill whose rms slope k C / sqrt(2) is sigma_slope (8.2).

    Width (valley to valley) 2 pi / k, height (peak to valley) 2 C, so the
    ratio is pi / (k C) = pi / (sqrt(2) sigma_slope).
    """
    return math.pi / (math.sqrt(2.0) * sigma_slope)


def fe_geometry(asperity: Config, curvature: float, width_to_height: float | None,
                height: float | None = None):
    """The `asperity.fe` profile of a sample of tip curvature `curvature` [1/m]
    (and, for the coupled mapping, peak height `height` [m] above the mean plane)."""
    from asperity import fe

    kind = asperity["geometry"]
    if is_coupled(asperity):
        if not height or height <= 0:
            raise ValueError(f"coupled cosine hill needs a peak height above the mean plane, got {height}")
        return fe.CosineHill(height, math.sqrt(curvature / height))
    if kind == "sphere":
        return fe.Sphere(1.0 / curvature)
    if kind == "paraboloid":
        return fe.Paraboloid(1.0 / curvature)
    if kind == "cosine":
        ratio = asperity.get("width_to_height", width_to_height)
        # kappa = C k^2 with pi / (k C) = ratio  ->  C = pi^2 / (ratio^2 kappa)
        amplitude = math.pi**2 / (ratio**2 * curvature)
        return fe.CosineHill.from_aspect(ratio, 2.0 * amplitude)
    raise ValueError(f"unknown asperity geometry {kind!r}")


def max_interference(geometry, asperity: Config) -> float:
    """Largest interference an FE job computes for `geometry` [m].

    A cosine hill up to ``max_height_fraction`` of its height (default 0.3,
    report 7.3's small-strain range is reached well before); a sphere up to
    ``max_radius_fraction`` of its radius (default 0.25: contact radius
    about 0.7 R, inside the modelled 45-degree cap), a paraboloid likewise;
    either capped at 0.9 of the modelled cap's height (0.293 R for the
    sphere, R / 8 for the paraboloid), where the flat would reach its foot.
    """
    from asperity import fe

    if isinstance(geometry, fe.CosineHill):
        return asperity.get("max_height_fraction", 0.3) * 2.0 * geometry.amplitude
    if isinstance(geometry, (fe.Sphere, fe.Paraboloid)):
        return min(asperity.get("max_radius_fraction", 0.25) * geometry.radius, 0.9 * geometry.height)
    return math.inf


def fe_levels(w_first: float, w_last: float, count: int) -> np.ndarray:
    """`count` geometric interference levels from w_first to w_last."""
    if not 0 < w_first < w_last:
        raise ValueError(f"FE levels need 0 < first < last, got {w_first:g}, {w_last:g}")
    return np.geomspace(w_first, w_last, count)


def job_range(geometry, asperity: Config, grid: np.ndarray, curvature: float,
              curvatures: np.ndarray | None = None) -> tuple[float, float]:
    """Smallest and largest interference the FE job of `geometry` computes [m].

    The plan's grid, capped by `max_interference`; for the job of a
    self-similar family (`curvatures`: the curvatures derived from the
    job's `curvature`) stretched so that every member's scaled range
    (w kappa / kappa_job) is covered.
    """
    pos = grid[grid > 0]
    lo, hi = pos[0], pos[-1]
    if curvatures is not None:
        lo *= min(1.0, float(np.min(curvatures)) / curvature)
        hi *= max(1.0, float(np.max(curvatures)) / curvature)
    return float(lo), float(min(hi, max_interference(geometry, asperity)))


def self_similar(asperity: Config, material_si: Config, effects) -> bool:
    """Whether the samples form a self-similar family (one job, the others scaled).

    Every asperity must be the same shape scaled (sphere, paraboloid, the
    representative cosine of fixed width-to-height ratio) and the body
    scale free: elastic or rate-independent plastic, no adhesion (whose
    range d does not scale).  ``scaling: self_similar`` forces it for a
    rate-dependent body (the report's assumption in 8.2.2: "due to absence
    of rate-dependent effects ... simple rescaling"), ``none`` forbids it.
    """
    choice = asperity.get("scaling", "auto")
    if choice == "none" or is_analytic(asperity) or not is_shift_invariant(asperity):
        return False
    if "adhesion" in set(effects):
        return False
    if choice == "self_similar":
        return True
    return materials.rate_independent(material_si, effects)


def unloading_levels(top: float, asperity: Config) -> tuple[np.ndarray, float]:
    """The interferences from which an asperity is unloaded (report 8.3), and the check level.

    ``unloading_levels`` (default 4, the report's "three to four") levels
    spread geometrically from ``unloading_smallest`` (default 0.05) x `top`
    to `top`; below the smallest the asperity is taken to unload along its
    loading curve (elastic rebound of a barely yielded tip).  With
    ``unloading_check`` one more level, the geometric mean of the second and
    third, is computed and left out of the blend to measure its error (the
    report's gamma_0 of Fig. 8.27); NaN otherwise.
    """
    count = int(asperity.get("unloading_levels", 4))
    levels = np.geomspace(asperity.get("unloading_smallest", 0.05) * top, top, count)
    check = math.sqrt(levels[1] * levels[2]) if asperity.get("unloading_check") and count >= 3 \
        else math.nan
    return levels, check


#: the first step of an inelastic history, as a fraction of the job's largest interference
FIRST_STEP = 1e-4


def _history(level: float, top: float, velocity: float | None):
    """Load at `velocity` to `level` and back to zero force (NaN level: load to `top`)."""
    from asperity import fe

    w_max = top if math.isnan(level) else level
    v = velocity if velocity else top / 100.0  # rate-independent body: any rate
    if math.isnan(level):
        return fe.History.loading(w_max, v)
    return fe.History.load_unload(w_max, v)


class SampleFailed(RuntimeError):
    """A sample's FE job failed (Newton even with step cutting, the contact zone,
    rupture); the message names the sample (key, curvature) and the step."""


def job_spec(asperity: Config, material_si: Config, effects, accuracy: str, *,
             curvature: float, height: float | None = None, level: float = math.nan,
             grid: np.ndarray, family: np.ndarray | None = None,
             width_to_height: float | None = None, velocity: float | None = None,
             adhesion: Config | None = None) -> dict:
    """Exactly what the FE job of one sample depends on, as plain JSON-able values.

    The key of a sample is the hash of this dict (`asperity.population.plan.sample_key`),
    so two scenes (or two presets' runs) that need the same asperity share
    its job and its file ``results/samples/<key>.nc``.  Holds the
    geometry (kind, mapping, resolved width-to-height ratio, the job's tip
    curvature; the peak height only for the coupled hill, whose shape
    depends on it), the interference range the job computes (from the
    plan's `grid`, stretched over the self-similar `family`), the body
    (material in SI, effects, preset), and per kind of job: the level count
    and contact model of an elastic job, the loading rate and unloading level
    of an inelastic one, the law (SI) of an adhesive one (`adhesion`, with the
    effect ``adhesion``).  Nothing else of the scene enters: a change of the
    population grid that leaves the range alone keeps the key.
    """
    geometry = fe_geometry(asperity, curvature, width_to_height, height)
    first, top = job_range(geometry, asperity, grid, curvature, family)
    spec = {
        "model": "fe",
        "geometry": asperity["geometry"],
        "curvature": float(curvature),
        "range": [first, top],
        "material": dict(material_si),
        "effects": sorted(effects),
        "accuracy": accuracy,
    }
    if asperity["geometry"] == "cosine":
        spec["mapping"] = asperity.get("mapping", "representative")
        spec["width_to_height"] = asperity.get("width_to_height", width_to_height)
    if is_coupled(asperity):
        spec["height"] = float(height)
    if "adhesion" in set(effects):  # approach and retraction (asperity.population.adhesive)
        from asperity.population import adhesive as adhesive_interface

        return adhesive_interface.job_spec(spec, adhesion, effects, level)
    if "plasticity" in set(effects):
        if not materials.rate_independent(material_si, effects):
            spec["velocity"] = velocity  # a J2 body answers the same at any rate
        if not math.isnan(level):
            spec["unloading_level"] = float(level)
    else:
        if not math.isnan(level):
            raise ValueError("unloading an elastic asperity retraces its loading curve; "
                             "add the effect `plasticity`")
        spec["levels"] = int(asperity.get("levels", 40))
        spec["contact"] = asperity.get("contact", "penalty")
    return spec


def solve_job(spec: Config, key: str) -> xr.Dataset:
    """The FE response of the sample job `spec` (`job_spec`), with its `key`.

    Elastic bodies: `solve_asperity` at ``levels`` geometric interferences
    over the job's range.  Inelastic bodies (effect ``plasticity``):
    `solve_asperity_history`, loading at ``velocity`` [m/s] (8.2.2) to the
    ``unloading_level`` and unloading to zero force, or loading only to the
    top of the range.  Raises `SampleFailed` naming the sample (key,
    curvature) and the step when Newton fails even with step cutting.
    """
    from asperity import fe

    if "adhesion" in spec:  # approach and retraction (asperity.population.adhesive)
        from asperity.population import adhesive as adhesive_interface

        return adhesive_interface.solve_job(spec, key)
    curvature = float(spec["curvature"])
    geometry = fe_geometry(spec, curvature, spec.get("width_to_height"), spec.get("height"))
    first, top = spec["range"]
    material = materials.build(spec["material"], spec["effects"])
    level = float(spec.get("unloading_level", math.nan))
    cpu = time.process_time()
    try:
        if hasattr(material, "update"):
            # one mesh for every unloading level of the asperity, adapted to its whole range,
            # so that their loading branches coincide (the corners of the blend, 8.3)
            # the first step presses 1e-4 of the range (first touch, where most asperities
            # of an interface are, is resolved; steps grow geometrically from there)
            history = _history(level, top, spec.get("velocity"))
            ds = fe.solve_asperity_history(geometry, material, history, accuracy=spec["accuracy"],
                                           mesh_levels=np.geomspace(0.01 * top, top, 6),
                                           initial_time_step=FIRST_STEP * top / history.velocity(0.0))
        else:
            levels = fe_levels(first, top, spec["levels"])
            ds = fe.solve_asperity(geometry, material, levels, accuracy=spec["accuracy"],
                                   contact=spec["contact"])
    except (fe.ConvergenceError, fe.ContactZoneError) as err:
        raise SampleFailed(f"sample {key} (curvature {curvature:.6g} 1/m"
                           + ("" if math.isnan(level) else f", unloading from {level:.6g} m")
                           + f"): {err}") from err
    ds.attrs.update(key=key, model="fe", curvature=curvature, geometry=repr(geometry),
                    height=float(spec.get("height", math.nan)), unloading_level=level,
                    cpu_time=time.process_time() - cpu)
    return ds


def solve_sample(plan: xr.Dataset, key: str) -> xr.Dataset:
    """The FE response of sample `key` of the plan: `solve_job` of its stored spec."""
    match = np.flatnonzero(plan["key"].values == key)
    if match.size == 0:
        raise ValueError(f"sample {key}: not in the plan")
    return solve_job(json.loads(str(plan["spec"].values[int(match[0])])), key)


#: the share of the computed range whose step slopes continue a curve beyond its end
TAIL = 0.1


def tail_slope(levels: np.ndarray, values: np.ndarray) -> float:
    """The slope that continues a curve beyond its last level: the median of the step
    slopes over the last `TAIL` of the range (at least the last step).  One step where
    an inelastic job's force jumps (a contact node snapping onto the flat) would
    otherwise set the slope of everything beyond: on steel_glass_bead at standard it
    was 6 times its neighbours'.  For a convex curve it stays a lower bound, like the
    last tangent."""
    steps = np.diff(values) / np.diff(levels)
    window = levels[:-1] >= levels[-1] - TAIL * (levels[-1] - levels[0])
    window[-1] = True
    return float(np.median(steps[window]))


def _loglog(levels: np.ndarray, values: np.ndarray, targets: np.ndarray,
            derivative: bool = False):
    """Interpolate positive increasing `values` at `levels` to `targets` (>= 0).

    Monotone cubic in (log w, log X) inside the levels; the power law of
    the first two levels below (X -> 0 as w -> 0); above, a straight line
    with the `tail_slope` of the last levels.
    Returns the values and a flag of the targets beyond the last level
    (and, with `derivative`, dX/dw at the targets as a third item).
    """
    from scipy.interpolate import PchipInterpolator  # here: 0.2 s most stages never need

    out = np.zeros_like(targets, dtype=float)
    slope_out = np.zeros_like(targets, dtype=float)
    lw, lx = np.log(levels), np.log(np.maximum(values, np.finfo(float).tiny))
    inside = (targets >= levels[0]) & (targets <= levels[-1])
    spline = PchipInterpolator(lw, lx)
    out[inside] = np.exp(spline(np.log(targets[inside])))
    slope_out[inside] = out[inside] / targets[inside] * spline(np.log(targets[inside]), 1)
    below = (targets > 0) & (targets < levels[0])
    p = (lx[1] - lx[0]) / (lw[1] - lw[0])
    out[below] = values[0] * (targets[below] / levels[0]) ** p
    slope_out[below] = p * out[below] / targets[below]
    above = targets > levels[-1]
    slope = tail_slope(levels, values)
    out[above] = values[-1] + slope * (targets[above] - levels[-1])
    slope_out[above] = slope
    if derivative:
        return out, above, slope_out
    return out, above


#: inside small-strain theory while the largest strain magnitude stays below this (report 7.3)
SMALL_STRAIN_LIMIT = 0.08


def _first_violation(w: np.ndarray, ok: np.ndarray) -> float:
    """Interference where a flag that holds at small w first fails (midway between
    the last step where it holds and the first where it does not; inf if never)."""
    bad = np.flatnonzero(~ok)
    if bad.size == 0:
        return math.inf
    i = int(bad[0])
    return float(w[0]) if i == 0 else 0.5 * float(w[i - 1] + w[i])


def loading_branch(ds: xr.Dataset) -> dict[str, np.ndarray]:
    """The loading curve of an FE sample: steps with w > 0 and F > 0, w increasing.

    Keys: interference, force, contact_area, contact_radius, stiffness (the
    consistent tangent where the job recorded it, else None) and the
    interferences where the asperity leaves the elastic range
    (``w_inelastic``: first step with inelastic strain or von Mises above
    the yield stress) and small-strain theory (``w_large_strain``: largest
    strain magnitude >= 8 %, report 7.3).
    """
    w = ds["interference"].values
    keep = (w > 0) & (ds["force"].values > 0)
    if "branch" in ds:
        keep &= ds["branch"].values.astype(str) == "loading"
    idx = np.flatnonzero(keep)
    idx = idx[np.concatenate([[True], np.diff(w[idx]) > 0])] if idx.size else idx
    if idx.size < 2:
        raise ValueError(f"sample {ds.attrs.get('key', '?')}: fewer than two loading steps in contact")
    strain = ds["max_principal_strain"] if "max_principal_strain" in ds else ds["max_equivalent_strain"]
    wi = w[idx]
    return {
        "interference": wi,
        "force": ds["force"].values[idx],
        "contact_area": ds["contact_area"].values[idx],
        "contact_radius": ds["contact_radius"].values[idx],
        "stiffness": ds["normal_stiffness"].values[idx] if "normal_stiffness" in ds else None,
        "w_inelastic": _first_violation(wi, ds["elastic"].values[idx].astype(bool)),
        "w_large_strain": _first_violation(wi, ds["small_strain"].values[idx].astype(bool)
                                           if "small_strain" in ds else
                                           strain.values[idx] < SMALL_STRAIN_LIMIT),
    }


#: how each gathered variable scales with the length scale lambda of a self-similar family
SCALING_POWER = {"force": 2, "contact_area": 2, "contact_radius": 1, "stiffness": 1,
                 "elastic": 0, "small_strain": 0}


def _curves(ds: xr.Dataset, grid: np.ndarray, scale: float = 1.0) -> dict[str, np.ndarray]:
    """One sample's loading response on the interference grid; with `scale` lambda,
    of the asperity lambda times the job's (X(w) = lambda^p X_job(w / lambda))."""
    lb = loading_branch(ds)
    w = lb["interference"] * scale
    lb = {k: (v * scale ** SCALING_POWER[k] if k in SCALING_POWER and v is not None else v)
          for k, v in lb.items()}
    lb["w_inelastic"] *= scale
    lb["w_large_strain"] *= scale
    out = {}
    out["force"], beyond, slope = _loglog(w, lb["force"], grid, derivative=True)
    out["contact_area"], _ = _loglog(w, lb["contact_area"], grid)
    out["contact_radius"], _ = _loglog(w, lb["contact_radius"], grid)
    out["stiffness"] = slope if lb["stiffness"] is None else _loglog(w, lb["stiffness"], grid)[0]
    touching = grid > 0
    out["elastic"] = (touching & (grid < lb["w_inelastic"])).astype(float)
    out["small_strain"] = (touching & (grid < lb["w_large_strain"])).astype(float)
    out["beyond"] = beyond
    return out


GATHERED_ATTRS = {
    "force": ("N", "normal contact force"),
    "contact_area": ("m^2", "real contact area"),
    "contact_radius": ("m", "contact radius (edge located between nodes)"),
    "stiffness": ("N/m", "normal stiffness dF/dw (consistent tangent, or the slope of the "
                         "interpolated force for inelastic asperities)"),
    "elastic": ("1", "1 where the asperity is in contact and still elastic (report 7.3)"),
    "small_strain": ("1", "1 where the asperity is in contact and every strain magnitude is "
                          "below 8 % (report 7.3)"),
}


def samples_by_key(plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> dict[str, xr.Dataset]:
    """The samples by key; raises naming every sample of the plan missing or failed."""
    by_key = {str(ds.attrs["key"]): ds for ds in samples.values()}
    needed = set(plan["key"].values)
    missing = sorted(needed - set(by_key))
    failed = sorted(k for k in needed & set(by_key) if by_key[k].attrs.get("status") == "failed")
    if missing or failed:
        raise ValueError(
            f"{len(missing) + len(failed)} of {len(needed)} samples missing from the gather; "
            "not homogenizing over a hole: "
            + "; ".join([f"{k}: no result" for k in missing]
                        + [f"{by_key[k].attrs.get('error', k)}" for k in failed]))
    return by_key


def fe_cost(jobs) -> dict:
    """What a set of FE jobs cost, for the gathered file's attributes (issue #6): their
    preset, count and total CPU time, and the largest Newton, step-cut, dof and time-step
    counts of any of them (each only where every job records it)."""
    out = dict(accuracy=str(jobs[0].attrs.get("accuracy", "")), fe_jobs=len(jobs),
               fe_cpu_time=float(sum(j.attrs.get("cpu_time", np.nan) for j in jobs)))
    for attr, var in (("max_newton_iterations", "newton_iterations"), ("max_step_cuts", "step_cuts"),
                      ("max_dofs", "dofs")):
        if all(var in j for j in jobs):
            out[attr] = int(max(j[var].max() for j in jobs))
    if all("steps" in j.attrs for j in jobs):
        out["max_time_steps"] = int(max(j.attrs["steps"] for j in jobs))
    return out


def gather(plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """FE samples onto the plan's (height, curvature, interference) grid.

    Samples that share a key (derived by a shift in height) share the
    response.  The loading branch of a (height, curvature) comes from its
    sample unloaded from the largest level (or its loading-only sample).
    ``extrapolated`` marks grid points beyond the sample's last computed
    level.  Samples with unloading levels also give their computed
    unloading paths on (curvature, unloading_level, point) for the blend
    of report 8.3 (`asperity.unloading.family_table`).
    """
    by_key = samples_by_key(plan, samples)
    heights, curvatures = plan["height"].values, plan["curvature"].values
    grid = plan["interference"].values
    ph, pk = plan["sample_height"].values, plan["sample_curvature"].values
    level = np.nan_to_num(plan["unloading_level"].values, nan=np.inf)
    scale = plan["scale"].values if "scale" in plan else np.ones(ph.size)
    # the loading source of every grid point: the sample of its (height, curvature) with the largest level
    order = np.lexsort((level, pk, ph))
    last = np.ones(order.size, bool)
    last[:-1] = (ph[order][1:] != ph[order][:-1]) | (pk[order][1:] != pk[order][:-1])
    source = plan["key"].values[order][last]  # in (height, curvature) order, the plan's grid order
    source_scale = scale[order][last]
    pairs = np.array([f"{k}@{x!r}" for k, x in zip(source, source_scale)])
    unique, first, index = np.unique(pairs, return_index=True, return_inverse=True)
    names = list(GATHERED_ATTRS)
    curves = {name: np.empty((unique.size, grid.size)) for name in names}
    beyond = np.empty((unique.size, grid.size), bool)
    for u, i in enumerate(first):  # one curve per (FE job, scale), each vectorized over the grid
        c = _curves(by_key[str(source[i])], grid, float(source_scale[i]))
        for name in names:
            curves[name][u] = c[name]
        beyond[u] = c["beyond"]
    shape = (heights.size, curvatures.size, grid.size)
    dims = ("height", "curvature", "interference")
    ds = xr.Dataset(
        {name: (dims, curves[name][index].reshape(shape),
                {"units": GATHERED_ATTRS[name][0], "long_name": GATHERED_ATTRS[name][1]})
         for name in names},
        coords={
            "height": ("height", heights, {"units": "m", "long_name": "asperity peak height"}),
            "curvature": ("curvature", curvatures, {"units": "1/m", "long_name": "tip curvature"}),
            "interference": ("interference", grid, {"units": "m", "long_name": "interference"}),
        },
    )
    ds.attrs.update(fe_cost([by_key[str(k)] for k in np.unique(plan["key"].values)]))
    ds["extrapolated"] = (dims, beyond[index].reshape(shape), {
        "units": "1", "long_name": "beyond the largest interference the FE job computed "
        "(continued with the median slope of its last steps)"})
    if np.isfinite(level).any():
        ds = ds.merge(_unloading_paths(plan, by_key))
    return ds


def _unloading_paths(plan: xr.Dataset, by_key: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """The computed unloading paths per curvature (dims curvature, unloading_level, point)."""
    if not np.all(plan.attrs.get("shift_invariant", 1)):
        raise ValueError("unloading is supported for asperities whose response does not depend "
                         "on their peak height (sphere, paraboloid, representative cosine)")
    curvatures = plan["curvature"].values
    pk, lv = plan["sample_curvature"].values, plan["unloading_level"].values
    scale = plan["scale"].values if "scale" in plan else np.ones(pk.size)
    left = plan["left_out"].values if "left_out" in plan else np.zeros(pk.size, bool)
    per = []
    for k in curvatures:
        rows = np.flatnonzero((pk == k) & np.isfinite(lv))
        rows = rows[np.unique(lv[rows], return_index=True)[1]]
        per.append(rows)
    nlev = max(r.size for r in per)
    paths = [[by_key[str(plan["key"].values[r])] for r in rows] for rows in per]
    npts = max(int((p["branch"].values.astype(str) == "unloading").sum()) + 1
               for ps in paths for p in ps)
    shape3 = (curvatures.size, nlev, npts)
    W, F, A = (np.full(shape3, np.nan) for _ in range(3))
    level = np.full(shape3[:2], np.nan)
    residual = np.full(shape3[:2], np.nan)
    check = np.zeros(shape3[:2], bool)
    for i, (rows, ps) in enumerate(zip(per, paths)):
        for j, (r, p) in enumerate(zip(rows, ps)):
            br = p["branch"].values.astype(str)
            start = int(np.flatnonzero(br == "unloading")[0]) - 1  # the step at w_max
            sel = slice(start, None)
            n = p["interference"].values[sel].size
            lam = float(scale[r])
            W[i, j, :n] = p["interference"].values[sel] * lam
            F[i, j, :n] = p["force"].values[sel] * lam**2
            A[i, j, :n] = p["contact_area"].values[sel] * lam**2
            level[i, j] = lv[r] * lam
            residual[i, j] = p.attrs.get("residual_interference", np.nan) * lam
            check[i, j] = bool(left[r])
    d3 = ("curvature", "unloading_level", "point")
    d2 = ("curvature", "unloading_level")
    return xr.Dataset({
        "unloading_interference": (d3, W, {"units": "m", "long_name": "interference along a computed unloading path"}),
        "unloading_force": (d3, F, {"units": "N", "long_name": "contact force along a computed unloading path"}),
        "unloading_contact_area": (d3, A, {"units": "m^2", "long_name": "real contact area along a computed unloading path"}),
        "maximum_interference": (d2, level, {"units": "m", "long_name": "interference from which the path unloads"}),
        "residual_interference": (d2, residual, {"units": "m", "long_name": "interference where the unloading force returns to zero"}),
        "left_out": (d2, check, {"units": "1", "long_name": "path left out of the blend to measure its error (gamma_0 of Fig. 8.27)"}),
    }, coords={
        "unloading_level": ("unloading_level", np.arange(nlev), {"units": "1", "long_name": "index of the computed unloading level"}),
        "point": ("point", np.arange(npts), {"units": "1", "long_name": "point along an unloading path (0: the maximum interference)"}),
    })
