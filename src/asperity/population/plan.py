"""The plan: which asperity samples a scene needs (DESIGN.md, task graph).

A sample is (height, curvature, unloading level).  The plan lays samples on
a grid over the effective support of the peak density (report 2.5.1,
assumption (a)), gives every sample the interference levels at which its
response is needed, and a key: a short hash of everything its job depends on
and nothing else.  Where the physics makes samples the same problem up to a
shift (an asperity whose response depends on the interference only, not on
the height of its peak), they share one key and the plan marks all but one
as derived.
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any, Callable, Mapping

import numpy as np
import xarray as xr


def spec_json(spec: Mapping[str, Any]) -> str:
    """A job spec as canonical JSON (sorted keys; floats round-trip exactly)."""

    def plain(obj):
        if isinstance(obj, Mapping):
            return {str(k): plain(v) for k, v in obj.items()}
        if isinstance(obj, (list, tuple, np.ndarray)):
            return [plain(v) for v in obj]
        if isinstance(obj, np.floating):
            return float(obj)
        if isinstance(obj, np.integer):
            return int(obj)
        return obj

    return json.dumps(plain(spec), sort_keys=True, separators=(",", ":"))


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def sample_key(payload: Mapping[str, Any]) -> str:
    """A 12-hex-digit hash of a job's inputs (their canonical JSON: floats exact)."""
    return _digest(spec_json(payload))


def interference_grid(largest: float, count: int, smallest_fraction: float = 1e-5) -> np.ndarray:
    """0 followed by `count - 1` geometrically spaced levels up to `largest`.

    A geometric grid resolves the onset of contact (force ~ w^{3/2} for a
    Hertzian tip) with the same relative accuracy at every scale, which a
    uniform grid cannot.
    """
    if not largest > 0:
        raise ValueError(f"largest interference must be positive, got {largest}")
    if count < 4:
        raise ValueError(f"the interference grid needs at least 4 levels, got {count}")
    return np.concatenate([[0.0], geometric_levels(largest * smallest_fraction, largest, count - 1)])


def geometric_levels(start: float, stop: float, count: int) -> np.ndarray:
    """`count` geometrically spaced values from `start` to `stop` (both > 0), as
    `numpy.geomspace` computes them, but with the C library's scalar ``log10`` and
    ``pow``.

    Levels that enter a job spec enter its key, so they must be the same numbers on
    every machine: numpy's vectorized ``power`` and ``log10`` take other code paths on
    CPUs with AVX-512 and differ there in the last bit.
    """
    if not (start > 0 and stop > 0):
        raise ValueError(f"geometric levels need start, stop > 0, got {start:g}, {stop:g}")
    exponents = np.linspace(math.log10(start), math.log10(stop), count)
    out = np.array([10.0 ** e for e in exponents.tolist()])
    if count > 0:
        out[0] = start
    if count > 1:
        out[-1] = stop
    return out


def sample_grid(lo: float, hi: float, count: int, positive: bool = False) -> np.ndarray:
    """`count` equally spaced values on [lo, hi] (one value: the midpoint).

    With `positive`, a zero lower end is moved to hi / (2 (count - 1)) so that
    no sample sits at zero curvature (a flat tip, infinite Hertz force).
    """
    if count == 1 or hi == lo:
        return np.array([0.5 * (lo + hi)])
    if positive and lo <= 0:
        lo = hi / (2.0 * (count - 1))
    return np.linspace(lo, hi, count)


def aspect_jobs(aspects: np.ndarray, count: int, check: bool) -> tuple[np.ndarray, float]:
    """The aspects q_j of the family's FE jobs and the left-out check aspect (NaN: none).

    `count` aspects geometrically spaced over the range of the samples' `aspects`
    (q = kappa z_p, the ends exact), and with `check` the geometric mean of the two
    middle ones (an aspect halfway between two jobs in log q, where the interpolation
    error is largest).
    """
    aspects = np.asarray(aspects, float)
    lo, hi = float(np.min(aspects)), float(np.max(aspects))
    if not 0 < lo:
        raise ValueError(f"aspects of coupled hills must be positive, got {lo:g}")
    if count < 2:
        raise ValueError(f"an aspect family needs at least 2 jobs, got {count}")
    hi = hi if hi > lo else 2.0 * lo  # a single aspect: a second job above it
    jobs = geometric_levels(lo, hi, count)  # the same numbers on every CPU: they enter the keys
    middle = (jobs.size - 1) // 2
    checked = math.sqrt(jobs[middle] * jobs[middle + 1]) if check else math.nan
    return jobs, checked


def aspect_weights(aspects: np.ndarray, jobs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For every aspect the index j of its lower neighbouring job and the weight t of
    the upper one in log q: q = q_j^(1 - t) q_(j+1)^t, t in [0, 1] (0 at a job)."""
    aspects = np.asarray(aspects, float)
    jobs = np.asarray(jobs, float)
    j = np.clip(np.searchsorted(jobs, aspects, side="right") - 1, 0, jobs.size - 2)
    t = np.log(aspects / jobs[j]) / np.log(jobs[j + 1] / jobs[j])
    t = np.where(aspects == jobs[j], 0.0, np.clip(t, 0.0, 1.0))
    return j, t


def make_plan(
    heights: np.ndarray,
    curvatures: np.ndarray,
    interferences: np.ndarray,
    *,
    model: str,
    job_spec: Callable[[float, float, float], Mapping[str, Any]],
    shift_invariant: bool,
    analytic: bool,
    unloading_levels: Callable[[float, float], np.ndarray] | None = None,
    reference_curvature: float | None = None,
) -> xr.Dataset:
    """The samples of a scene on the grid heights x curvatures (x unloading levels).

    `job_spec(height, job curvature, unloading level)`: exactly what the
    sample's job depends on (the kind's `spec`, `asperity.population.kinds`), stored as JSON in
    ``spec``; the key is its hash, so samples with equal specs share a job.
    `shift_invariant`: the response depends on the interference only, not
    on the peak height (the spec leaves the height out, and samples of one
    curvature share a key).  `analytic`: a closed form, no job of its own.
    `unloading_levels(height, curvature)`: the interferences [m] from which
    the sample is unloaded (report 8.3: three or four per asperity), one
    sample (and key) per level; None: loading only (level NaN).
    `reference_curvature`: the samples form a self-similar family (every
    asperity the same shape scaled by lambda = reference / curvature, and
    a body whose response scales with it: DESIGN.md); one job per
    unloading level computes the asperity of the reference curvature and
    every sample is derived from it by scaling (``scale`` = lambda).  The
    ``unloading_level`` of a sample is then that of its job.
    """
    heights = np.asarray(heights, float)
    curvatures = np.asarray(curvatures, float)
    hh, kk = np.meshgrid(heights, curvatures, indexing="ij")
    hh, kk = hh.ravel(), kk.ravel()
    scaled = reference_curvature is not None
    if scaled and not shift_invariant:
        raise ValueError("a self-similar family must also be shift invariant in height")
    jk = np.full(kk.size, float(reference_curvature)) if scaled else kk
    if unloading_levels is None:
        ll = np.full(hh.size, np.nan)
    else:
        per = [np.asarray(unloading_levels(h, k), float) for h, k in zip(hh, jk)]
        counts = np.array([p.size for p in per])
        hh, kk, jk = (np.repeat(a, counts) for a in (hh, kk, jk))
        ll = np.concatenate(per)
    specs = [spec_json(job_spec(h, k, lv)) for h, k, lv in zip(hh, jk, ll)]
    keys = np.array([_digest(text) for text in specs])
    _, first = np.unique(keys, return_index=True)
    representative = np.zeros(keys.size, bool)
    representative[first] = True
    derived_from = np.where(representative, "", keys)
    job = representative & (not analytic)
    sample = np.arange(keys.size)
    ds = xr.Dataset(
        {
            "sample_height": ("sample", hh, {"units": "m", "long_name": "peak height of the sample"}),
            "sample_curvature": (
                "sample",
                kk,
                {"units": "1/m", "long_name": "mean tip curvature of the sample"},
            ),
            "unloading_level": (
                "sample",
                ll,
                {"units": "m", "long_name": "interference from which the sample unloads (NaN: loading only)"},
            ),
            "job_curvature": ("sample", jk, {"units": "1/m", "long_name": "tip curvature of the asperity the sample's job computes"}),
            "scale": ("sample", jk / kk, {"units": "1", "long_name": "length scale of the sample over its job's asperity (1: computed as is)"}),
            "key": ("sample", keys, {"units": "1", "long_name": "hash of the inputs of the sample's job"}),
            "spec": ("sample", np.array(specs, dtype=object), {
                "units": "1", "long_name": "what the sample's job depends on (JSON; its hash is the key)"}),
            "derived_from": (
                "sample",
                derived_from,
                {
                    "units": "1",
                    "long_name": "key of the job this sample is derived from by a shift in height "
                    "or a scaling (empty: computed itself)",
                },
            ),
            "job": ("sample", job, {"units": "1", "long_name": "sample needs a finite element job"}),
        },
        coords={
            "sample": ("sample", sample, {"units": "1", "long_name": "sample index"}),
            "height": ("height", heights, {"units": "m", "long_name": "peak height grid"}),
            "curvature": ("curvature", curvatures, {"units": "1/m", "long_name": "tip curvature grid"}),
            "interference": (
                "interference",
                np.asarray(interferences, float),
                {"units": "m", "long_name": "interference levels of every sample"},
            ),
        },
    )
    ds.attrs["model"] = model
    how = "a shift in height and a scaling (self-similar family)" if scaled else \
        "a shift in height (response depends on interference only)"
    ds.attrs["derived"] = (
        f"{int((~representative).sum())} of {keys.size} samples derived by {how}"
        if shift_invariant
        else "no sample derived"
    )
    if scaled:
        ds.attrs["reference_curvature"] = float(reference_curvature)
    return ds


def job_keys(plan: xr.Dataset) -> list[str]:
    """Keys of the samples that need a job of their own."""
    return [str(k) for k in plan["key"].values[plan["job"].values.astype(bool)]]


def make_aspect_plan(
    heights: np.ndarray,
    curvatures: np.ndarray,
    interferences: np.ndarray,
    *,
    model: str,
    job_spec: Callable[[float, float, float], Mapping[str, Any]],
    aspects: int,
    check: bool,
    reference_curvature: float,
) -> xr.Dataset:
    """The samples of coupled cosine hills (report 2.5.1) scaled from a family of FE
    jobs at a few aspects (8.2.2's self-similar scaling, one job per aspect).

    A sample of peak height z_p and tip curvature kappa is the hill of amplitude z_p
    and aspect q = kappa z_p; `aspects` jobs (`aspect_jobs`) compute the hills of aspects q_j
    spread over the samples' range, each
    of tip curvature `reference_curvature` and amplitude q_j / reference_curvature. A
    sample is derived from its two neighbouring jobs (``key`` the lower, ``upper_key``
    the upper, ``aspect_weight`` t of the upper in log q; t = 0 at a job). With `check`
    one more job at the geometric mean of two middle aspects is computed and left out
    of the interpolation (``left_out``) to measure its error.

    The samples come first, in (height, curvature) order, all derived (``job`` False);
    the jobs follow as rows of their own (``family_job``), the hills they compute
    (``sample_height`` the amplitude, ``sample_curvature`` the reference). `job_spec`
    as for `make_plan`.
    """
    heights = np.asarray(heights, float)
    curvatures = np.asarray(curvatures, float)
    hh, kk = np.meshgrid(heights, curvatures, indexing="ij")
    hh, kk = hh.ravel(), kk.ravel()
    if np.any(hh <= 0):
        raise ValueError("a coupled hill needs a peak height above the mean plane (2.5.1)")
    qq = hh * kk
    qj, qc = aspect_jobs(qq, aspects, check)
    kref = float(reference_curvature)
    job_q = np.append(qj, qc) if np.isfinite(qc) else qj
    job_h = job_q / kref
    job_specs = [spec_json(job_spec(h, kref, math.nan)) for h in job_h]
    job_keys_ = [_digest(text) for text in job_specs]
    j, t = aspect_weights(qq, qj)
    n, m = hh.size, job_q.size
    left = np.zeros(n + m, bool)
    if np.isfinite(qc):
        left[-1] = True
    specs = [job_specs[i] for i in j] + job_specs
    keys = np.array([job_keys_[i] for i in j] + job_keys_)
    upper = np.array([job_keys_[i + 1] for i in j] + job_keys_)
    family = np.r_[np.zeros(n, bool), np.ones(m, bool)]
    sh, sk = np.r_[hh, job_h], np.r_[kk, np.full(m, kref)]
    ds = xr.Dataset(
        {
            "sample_height": ("sample", sh, {"units": "m", "long_name": "peak height of the sample (of a job: its hill's amplitude)"}),
            "sample_curvature": ("sample", sk, {"units": "1/m", "long_name": "mean tip curvature of the sample"}),
            "unloading_level": ("sample", np.full(n + m, np.nan), {"units": "m", "long_name": "interference from which the sample unloads (NaN: loading only)"}),
            "job_curvature": ("sample", np.full(n + m, kref), {"units": "1/m", "long_name": "tip curvature of the asperities the sample's jobs compute"}),
            "scale": ("sample", kref / sk, {"units": "1", "long_name": "length scale of the sample over the hill of its aspect at the jobs' curvature"}),
            "aspect": ("sample", sh * sk, {"units": "1", "long_name": "aspect q = kappa z_p = (k C)^2 of the coupled hill (2.5.1)"}),
            "key": ("sample", keys, {"units": "1", "long_name": "hash of the inputs of the sample's (lower neighbouring) job"}),
            "upper_key": ("sample", upper, {"units": "1", "long_name": "key of the upper neighbouring job in aspect"}),
            "aspect_weight": ("sample", np.r_[t, np.zeros(m)], {"units": "1", "long_name": "weight t of the upper job: log q = (1 - t) log q_j + t log q_j+1"}),
            "spec": ("sample", np.array(specs, dtype=object), {
                "units": "1", "long_name": "what the sample's job depends on (JSON; its hash is the key)"}),
            "derived_from": ("sample", np.r_[keys[:n], np.full(m, "")], {
                "units": "1", "long_name": "key of the lower job this sample is interpolated from "
                "(empty: computed itself)"}),
            "job": ("sample", family, {"units": "1", "long_name": "sample needs a finite element job"}),
            "family_job": ("sample", family, {"units": "1", "long_name": "a job of the family of aspects, not a sample of the grid"}),
            "left_out": ("sample", left, {"units": "1", "long_name": "job computed to check the interpolation in aspect, left out of it"}),
        },
        coords={
            "sample": ("sample", np.arange(n + m), {"units": "1", "long_name": "sample index"}),
            "height": ("height", heights, {"units": "m", "long_name": "peak height grid"}),
            "curvature": ("curvature", curvatures, {"units": "1/m", "long_name": "tip curvature grid"}),
            "interference": ("interference", np.asarray(interferences, float), {
                "units": "m", "long_name": "interference levels of every sample"}),
        },
    )
    ds.attrs["model"] = model
    ds.attrs["aspect_family"] = 1
    ds.attrs["aspects"] = qj
    ds.attrs["aspect_check"] = qc
    ds.attrs["reference_curvature"] = kref
    ds.attrs["derived"] = (f"{n} samples derived from {qj.size} jobs at aspects "
                           f"{qj[0]:.3g} .. {qj[-1]:.3g} by scaling and interpolation in log aspect"
                           + (f", one job at {qc:.3g} to check it" if np.isfinite(qc) else ""))
    return ds


def make_ratio_plan(ratios: np.ndarray, *, model: str, job_spec: Callable[[float], Mapping[str, Any]],
                    reference_curvature: float) -> xr.Dataset:
    """The jobs of elliptic summits (`asperity.population.kinds.elliptic`): one per curvature
    ratio t = kappa_2 / kappa_1 of `ratios`, each at `reference_curvature` kappa_1; every
    summit of the anisotropic density is derived from them by scaling (its kappa_1) and
    interpolation in ln t (its ratio). `job_spec(ratio)` as the kind's spec; the key is
    its hash."""
    ratios = np.asarray(ratios, float)
    specs = [spec_json(job_spec(float(t))) for t in ratios]
    keys = np.array([_digest(text) for text in specs])
    n = ratios.size
    kref = float(reference_curvature)
    ds = xr.Dataset(
        {
            "sample_ratio": ("sample", ratios, {"units": "1", "long_name": "curvature ratio kappa_2 / kappa_1 of the job's summit"}),
            "job_curvature": ("sample", np.full(n, kref), {"units": "1/m", "long_name": "larger principal curvature kappa_1 of the job's summit"}),
            "unloading_level": ("sample", np.full(n, np.nan), {"units": "m", "long_name": "interference from which the sample unloads (NaN: loading only)"}),
            "key": ("sample", keys, {"units": "1", "long_name": "hash of the inputs of the sample's job"}),
            "spec": ("sample", np.array(specs, dtype=object), {
                "units": "1", "long_name": "what the sample's job depends on (JSON; its hash is the key)"}),
            "derived_from": ("sample", np.full(n, ""), {"units": "1", "long_name": "key of the job this sample is derived from (empty: computed itself)"}),
            "job": ("sample", np.ones(n, bool), {"units": "1", "long_name": "sample needs a finite element job"}),
        },
        coords={"sample": ("sample", np.arange(n), {"units": "1", "long_name": "sample index"})},
    )
    ds.attrs["model"] = model
    ds.attrs["reference_curvature"] = kref
    ds.attrs["derived"] = (f"every summit derived from {n} jobs at curvature ratios {ratios[0]:.3g} .. "
                           f"{ratios[-1]:.3g} by scaling in kappa_1 and interpolation in ln(kappa_2 / kappa_1)")
    return ds
