"""The gather: the responses of finite element samples on the plan's grid (report 2.5, 8.3).

An FE job computes a geometric sequence of levels up to the largest interference
its geometry admits (`asperity.population.geometry.max_interference`). The gather
interpolates each sample onto the plan's (height, curvature, interference) grid in
log-log space (monotone cubic), continues below the first level with Hertz's power laws
of first touch (`FIRST_TOUCH`; the local power law for a plane-strain job) and above the
last with the median slope of its last steps, and flags the latter as ``extrapolated``;
samples of a self-similar family are scaled from their job's asperity, and the computed
unloading paths are kept for the blend of 8.3.

The gathered file also says how smooth the FE curves are (`curve_kinks`): a job's force
and contact area bump from step to step where its contact edge crosses the grading of
its mesh, and the largest such kink over the jobs is an attribute (and drawn in the
figure of single asperities).
"""

from __future__ import annotations

import logging
import math
from typing import Mapping

import numpy as np
import xarray as xr

from asperity.population.plan import aspect_weights

log = logging.getLogger("asperity")

#: the share of the computed range whose step slopes continue a curve beyond its end
TAIL = 0.1
#: kinks are measured from this share of each job's largest interference on: below it a
#: curve bends from its elastic start on the first small contacts, which is physics, not
#: the mesh
KINK_FROM = 0.1


def tail_slope(levels: np.ndarray, values: np.ndarray) -> float:
    """The slope that continues a curve beyond its last level: the median of the step
    slopes over the last `TAIL` of the range (at least the last step).  One step where
    an inelastic job's force jumps (a contact node snapping onto the flat) would
    otherwise set the slope of everything beyond.  For a convex curve it stays a lower
    bound, like the last tangent."""
    steps = np.diff(values) / np.diff(levels)
    window = levels[:-1] >= levels[-1] - TAIL * (levels[-1] - levels[0])
    window[-1] = True
    return float(np.median(steps[window]))


def _loglog(levels: np.ndarray, values: np.ndarray, targets: np.ndarray,
            derivative: bool = False, first_touch: float | None = None):
    """Interpolate positive increasing `values` at `levels` to `targets` (>= 0).

    Monotone cubic in (log w, log X) inside the levels; below, the power law
    w^`first_touch` through the first level, or without it that of the first two
    levels (X -> 0 as w -> 0); above, a straight line with the `tail_slope` of the
    last levels.  Returns the values and a flag of the targets beyond the last level
    (and, with `derivative`, dX/dw at the targets as a third item).
    """
    from scipy.interpolate import PchipInterpolator  # here: an import most stages never need

    out = np.zeros_like(targets, dtype=float)
    slope_out = np.zeros_like(targets, dtype=float)
    lw, lx = np.log(levels), np.log(np.maximum(values, np.finfo(float).tiny))
    inside = (targets >= levels[0]) & (targets <= levels[-1])
    spline = PchipInterpolator(lw, lx)
    out[inside] = np.exp(spline(np.log(targets[inside])))
    slope_out[inside] = out[inside] / targets[inside] * spline(np.log(targets[inside]), 1)
    below = (targets > 0) & (targets < levels[0])
    p = (lx[1] - lx[0]) / (lw[1] - lw[0]) if first_touch is None else first_touch
    out[below] = values[0] * (targets[below] / levels[0]) ** p
    slope_out[below] = p * out[below] / targets[below]
    above = targets > levels[-1]
    slope = tail_slope(levels, values)
    out[above] = values[-1] + slope * (targets[above] - levels[-1])
    slope_out[above] = slope
    if derivative:
        return out, above, slope_out
    return out, above


#: inside small-strain theory while the largest strain magnitude stays below this (report 7.3);
#: for samples without the FE job's own `small_strain` flag.  The same limit as
#: `asperity.fe.outputs.SMALL_STRAIN_LIMIT`, written here because importing `asperity.fe`
#: would load scikit-fem into every gather job
SMALL_STRAIN_LIMIT = 0.08


def _first_violation(w: np.ndarray, ok: np.ndarray) -> float:
    """Interference where a flag that holds at small w first fails (midway between
    the last step where it holds and the first where it does not; inf if never)."""
    bad = np.flatnonzero(~ok)
    if bad.size == 0:
        return math.inf
    i = int(bad[0])
    return float(w[0]) if i == 0 else 0.5 * float(w[i - 1] + w[i])


def strain_magnitude(ds: xr.Dataset) -> xr.DataArray:
    """The strain of an FE sample that small-strain theory is judged by (report 7.3): its
    largest principal strain where the job records it, else its equivalent strain."""
    return ds["max_principal_strain"] if "max_principal_strain" in ds else ds["max_equivalent_strain"]


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
    strain = strain_magnitude(ds)
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
#: below its first level an axisymmetric asperity's curves follow Hertz's first touch (a
#: smooth tip touches elastically): X ~ w^p.  The first levels of an inelastic job are
#: pressed on a mesh adapted for contacts from a hundredth of its range on, so their
#: areas are those of the apex's elements (the first two can be equal, and their power
#: law flat: 2000 times Hertz's area at the smallest interference of `smooth_aluminum`)
FIRST_TOUCH = {"force": 1.5, "contact_area": 1.0, "contact_radius": 0.5, "stiffness": 0.5}


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
    hertz = FIRST_TOUCH if ds.attrs.get("symmetry", "axisymmetric") == "axisymmetric" else {}
    out["force"], beyond, slope = _loglog(w, lb["force"], grid, derivative=True,
                                          first_touch=hertz.get("force"))
    for name in ("contact_area", "contact_radius", "stiffness"):
        if lb[name] is not None:
            out[name] = _loglog(w, lb[name], grid, first_touch=hertz.get(name))[0]
    if lb["stiffness"] is None:  # inelastic: the slope of the interpolated force
        out["stiffness"] = slope
    touching = grid > 0
    out["elastic"] = (touching & (grid < lb["w_inelastic"])).astype(float)
    out["small_strain"] = (touching & (grid < lb["w_large_strain"])).astype(float)
    out["beyond"] = beyond
    out["w_inelastic"], out["w_large_strain"] = lb["w_inelastic"], lb["w_large_strain"]
    out["top"] = float(w[-1])
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
    """What a set of FE jobs cost, for the gathered file's attributes: their
    preset (and the keys of it they override), count and total CPU time, and the
    largest Newton, step-cut, dof and time-step counts of any of them (each only where
    every job records it)."""
    out = dict(accuracy=str(jobs[0].attrs.get("accuracy", "")), fe_jobs=len(jobs),
               fe_cpu_time=float(sum(j.attrs.get("cpu_time", np.nan) for j in jobs)))
    if "accuracy_overrides" in jobs[0].attrs:  # e.g. a scene's asperity.edge_band
        out["accuracy_overrides"] = str(jobs[0].attrs["accuracy_overrides"])
    for attr, var in (("max_newton_iterations", "newton_iterations"), ("max_step_cuts", "step_cuts"),
                      ("max_dofs", "dofs")):
        if all(var in j for j in jobs):
            out[attr] = int(max(j[var].max() for j in jobs))
    if all("steps" in j.attrs for j in jobs):
        out["max_time_steps"] = int(max(j.attrs["steps"] for j in jobs))
    return out


def kinks(w: np.ndarray, y: np.ndarray) -> np.ndarray:
    """y_i / y*_i - 1 at the inner points of a curve, y*_i on the straight line in
    (ln w, ln y) through the points before and after: 0 along a power law, a spike where
    a step's value bumps off its neighbours'."""
    x, z = np.log(np.asarray(w, float)), np.log(np.asarray(y, float))
    line = z[:-2] + (z[2:] - z[:-2]) * (x[1:-1] - x[:-2]) / (x[2:] - x[:-2])
    return np.expm1(z[1:-1] - line)


def largest_kink(w: np.ndarray, y: np.ndarray, start: float = KINK_FROM) -> float:
    """The largest |`kinks`| at the points with w >= `start` x the largest w (0 if there
    are none); a point whose kink is not defined (beside a zero value, as an area at
    first touch can be) is left out."""
    w = np.asarray(w, float)
    use = w[1:-1] >= start * np.max(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.abs(kinks(w, y)[use])
    return float(np.max(k[np.isfinite(k)], initial=0.0))


def curve_kinks(jobs) -> dict:
    """How smooth the FE jobs' loading curves are, for the gathered file's attributes:
    the largest `largest_kink` of force and of contact area over the jobs
    (``max_kink_force``, ``max_kink_contact_area``, from ``kink_from`` of each job's
    range on), also logged with what refines them.  At 'standard' the default run's
    areas kink by 1.4-3.8 % (elastic) and 2.2-4.2 % (inelastic on the default mesh; 1.3 %
    for the J2 job, which has the edge band) where the located edge crosses the mesh's
    grading; the interface averages this over its asperities (docs: changelog, "The gather")."""
    force = area = 0.0
    for job in jobs:
        lb = loading_branch(job)
        force = max(force, largest_kink(lb["interference"], lb["force"]))
        area = max(area, largest_kink(lb["interference"], lb["contact_area"]))
    inelastic = all("time_step" in job for job in jobs)
    band = "edge_size" in str(jobs[0].attrs.get("accuracy_overrides", ""))
    remedy = ("asperity: {edge_band: true} refines the mesh where the plastic contact edge goes"
              if inelastic and not band else "a finer accuracy preset refines the contact edge")
    log.info("the FE curves kink from step to step by up to %.1f %% in force and %.1f %% in "
             "contact area (from %g of each job's largest interference on); %s",
             100 * force, 100 * area, KINK_FROM, remedy)
    return dict(max_kink_force=force, max_kink_contact_area=area, kink_from=KINK_FROM)


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
    ds = _grid_dataset(plan, {name: curves[name][index].reshape(shape) for name in names},
                       beyond[index].reshape(shape), by_key,
                       "beyond the largest interference the FE job computed "
                       "(continued with the median slope of its last steps)")
    if np.isfinite(level).any():
        ds = ds.merge(_unloading_paths(plan, by_key))
    return ds


def _grid_dataset(plan: xr.Dataset, data: Mapping[str, np.ndarray], beyond: np.ndarray,
                  by_key: Mapping[str, xr.Dataset], extrapolated: str) -> xr.Dataset:
    """The gathered responses `data` (name -> values on the plan's height x curvature x
    interference grid) as a Dataset, with the FE cost of the jobs, their curves' kinks
    (`curve_kinks`) and the flag `beyond` (long name `extrapolated`)."""
    dims = ("height", "curvature", "interference")
    ds = xr.Dataset(
        {name: (dims, data[name], {"units": GATHERED_ATTRS[name][0], "long_name": GATHERED_ATTRS[name][1]})
         for name in GATHERED_ATTRS},
        coords={
            "height": ("height", plan["height"].values,
                       {"units": "m", "long_name": "asperity peak height"}),
            "curvature": ("curvature", plan["curvature"].values,
                          {"units": "1/m", "long_name": "tip curvature"}),
            "interference": ("interference", plan["interference"].values,
                             {"units": "m", "long_name": "interference"}),
        },
    )
    jobs = [by_key[str(k)] for k in np.unique(plan["key"].values)]
    ds.attrs.update(fe_cost(jobs))
    ds.attrs.update(curve_kinks(jobs))
    ds["extrapolated"] = (dims, beyond, {"units": "1", "long_name": extrapolated})
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


def _geometric(x0: np.ndarray, x1: np.ndarray, t: float) -> np.ndarray:
    """x0^(1 - t) x1^t of non-negative values (x0 itself at t = 0, 0 where either is 0)."""
    if t == 0.0:
        return np.asarray(x0, float)
    x0, x1 = np.maximum(x0, 0.0), np.maximum(x1, 0.0)
    both = (x0 > 0) & (x1 > 0)
    out = np.zeros(np.broadcast(x0, x1).shape)
    out[both] = np.exp((1.0 - t) * np.log(x0[both]) + t * np.log(x1[both]))
    return out


def _threshold(w0: float, w1: float, top: float, t: float) -> float:
    """The interference where a flag first fails, interpolated like the responses; a
    neighbour where it never fails (inf) counts as failing at the top of the range,
    so the interpolation errs on the side of failing early."""
    if t == 0.0 or (math.isinf(w0) and math.isinf(w1)):
        return w0 if t == 0.0 else math.inf
    w0, w1 = min(w0, top), min(w1, top)
    return float(w0 ** (1.0 - t) * w1 ** t)


def aspect_curves(lower: xr.Dataset, upper: xr.Dataset, height: float, t: float,
                  grid: np.ndarray) -> dict[str, np.ndarray]:
    """The loading response on `grid` of the coupled hill of amplitude `height` whose
    aspect lies at weight `t` in log q between the jobs `lower` and `upper` (2.5.1).

    Each job's hill (amplitude C_j) is scaled by z_p / C_j, so that its response is
    taken at the same fraction w / C of the amplitude as the sample's (both jobs
    computed it: each goes to the same fraction of its own height), and the two scaled
    responses are interpolated geometrically, X = X_j^(1 - t) X_(j+1)^t: linear in
    log q of log X at fixed w / C. Exact at a job (t = 0); exact too where the
    response is a power of q at fixed w / C, as for an elastic hill of small slope
    (half-space theory: F = E* C / k phi(w / C), so F kappa^2 / E* = q^(3/2) phi).
    Scaling by 1/kappa instead of by C changes every job's value by a power of
    q_j / q, which this interpolation leaves unchanged. The interferences where the
    hill yields and leaves small strain are interpolated likewise; ``beyond`` where
    either job is beyond its computed range.
    """
    c0 = _curves(lower, grid, height / float(lower.attrs["height"]))
    if t == 0.0:
        c1 = c0
    else:
        c1 = _curves(upper, grid, height / float(upper.attrs["height"]))
    out = {name: _geometric(c0[name], c1[name], t)
           for name in ("force", "contact_area", "contact_radius", "stiffness")}
    touching = grid > 0
    top = min(c0["top"], c1["top"])
    for flag, w in (("elastic", "w_inelastic"), ("small_strain", "w_large_strain")):
        out[flag] = (touching & (grid < _threshold(c0[w], c1[w], top, t))).astype(float)
    out["beyond"] = c0["beyond"] | c1["beyond"]
    return out


def aspect_check(plan: xr.Dataset, by_key: Mapping[str, xr.Dataset]) -> dict[str, float]:
    """The error of the interpolation in aspect at the left-out job (`make_aspect_plan`):
    its computed loading curve against the one interpolated from its two neighbouring
    jobs, at its own computed levels. Force and contact area: the largest difference
    over the job's largest value; ``..._relative``: the largest relative difference
    from a tenth of the job's range up (below, a few nodes in contact)."""
    left = plan["left_out"].values.astype(bool)
    if not left.any():
        return {}
    row = int(np.flatnonzero(left)[0])
    key = str(plan["key"].values[row])
    job = by_key[key]
    q = float(plan["aspect"].values[row])
    fam = plan["family_job"].values.astype(bool) & ~left
    qj = plan["aspect"].values[fam]
    kj = plan["key"].values[fam]
    order = np.argsort(qj)
    qj, kj = qj[order], kj[order]
    j, t = aspect_weights(np.array([q]), qj)
    j, t = int(j[0]), float(t[0])
    lb = loading_branch(job)
    w = lb["interference"]
    c = aspect_curves(by_key[str(kj[j])], by_key[str(kj[j + 1])], float(job.attrs["height"]), t, w)
    out = {"aspect_check": q, "aspect_check_weight": t}
    upper = w >= 0.1 * w[-1]
    for name in ("force", "contact_area"):
        ref = lb[name]
        out[f"aspect_check_{name}_error"] = float(np.max(np.abs(c[name] - ref)) / np.max(ref))
        out[f"aspect_check_{name}_relative"] = float(np.max(np.abs(c[name][upper] / ref[upper] - 1)))
    return out


def gather_aspects(plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """The samples of coupled hills scaled from the family of aspects
    (`asperity.population.plan.make_aspect_plan`) on the plan's (height, curvature,
    interference) grid, each from its two neighbouring jobs (`aspect_curves`), and the
    error of the interpolation at the left-out job (`aspect_check`) as attributes."""
    by_key = samples_by_key(plan, samples)
    heights, curvatures = plan["height"].values, plan["curvature"].values
    grid = plan["interference"].values
    rows = np.flatnonzero(~plan["family_job"].values.astype(bool))
    names = list(GATHERED_ATTRS)
    shape = (heights.size, curvatures.size, grid.size)
    data = {name: np.empty(shape) for name in names}
    beyond = np.empty(shape, bool)
    ph, pk = plan["sample_height"].values, plan["sample_curvature"].values
    for r in rows:
        i = int(np.flatnonzero(heights == ph[r])[0])
        k = int(np.flatnonzero(curvatures == pk[r])[0])
        c = aspect_curves(by_key[str(plan["key"].values[r])], by_key[str(plan["upper_key"].values[r])],
                          float(ph[r]), float(plan["aspect_weight"].values[r]), grid)
        for name in names:
            data[name][i, k] = c[name]
        beyond[i, k] = c["beyond"]
    ds = _grid_dataset(plan, data, beyond, by_key,
                       "beyond the largest interference the FE jobs computed "
                       "(continued with the median slope of their last steps)")
    ds["aspect"] = (("height", "curvature"), heights[:, None] * curvatures[None, :], {
        "units": "1", "long_name": "aspect q = kappa z_p of the coupled hill (2.5.1)"})
    ds.attrs["aspects"] = np.asarray(plan.attrs["aspects"], float)
    ds.attrs["interpolation"] = ("coupled hills scaled from the jobs of the two neighbouring aspects "
                                 "at the same fraction of their amplitude, geometric in log aspect")
    ds.attrs.update(aspect_check(plan, by_key))
    return ds
