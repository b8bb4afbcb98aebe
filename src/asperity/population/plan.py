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
    if not 0 < start and 0 < stop:
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
