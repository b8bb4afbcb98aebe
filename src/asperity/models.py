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

import math
import time
from typing import Any, Mapping

import numpy as np
import xarray as xr
from scipy.interpolate import PchipInterpolator

Config = Mapping[str, Any]

ANALYTIC = ("hertz", "constant")

#: variables of an FE sample gathered onto the plan's grid, with their names there
GATHERED = {"force": "force", "contact_area": "contact_area", "contact_radius": "contact_radius",
            "normal_stiffness": "stiffness"}


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
    about 0.7 R, inside the modelled 45-degree cap); a paraboloid (a half
    space) without limit.
    """
    from asperity import fe

    if isinstance(geometry, fe.CosineHill):
        return asperity.get("max_height_fraction", 0.3) * 2.0 * geometry.amplitude
    if isinstance(geometry, fe.Sphere):
        return asperity.get("max_radius_fraction", 0.25) * geometry.radius
    return math.inf


def fe_levels(w_first: float, w_last: float, count: int) -> np.ndarray:
    """`count` geometric interference levels from w_first to w_last."""
    if not 0 < w_first < w_last:
        raise ValueError(f"FE levels need 0 < first < last, got {w_first:g}, {w_last:g}")
    return np.geomspace(w_first, w_last, count)


def fe_material(material_si: Config):
    from asperity import fe

    return fe.LinearElastic(material_si["youngs_modulus"], material_si["poisson"],
                            material_si.get("yield_stress", math.inf))


def solve_sample(plan: xr.Dataset, key: str, asperity: Config, material_si: Config,
                 accuracy: str) -> xr.Dataset:
    """The FE response of sample `key` of the plan (one job).

    Raises RuntimeError naming the sample (key, curvature) and the step when
    Newton fails even with step cutting.
    """
    from asperity import fe

    match = np.flatnonzero(plan["key"].values == key)
    if match.size == 0:
        raise ValueError(f"sample {key}: not in the plan")
    row = plan.isel(sample=int(match[0]))
    curvature = float(row["sample_curvature"])
    geometry = fe_geometry(asperity, curvature, plan.attrs.get("width_to_height"),
                           float(row["sample_height"]))
    grid = plan["interference"].values
    positive = grid[grid > 0]
    w_last = min(positive[-1], max_interference(geometry, asperity))
    levels = fe_levels(positive[0], w_last, asperity.get("levels", 40))
    cpu = time.process_time()
    try:
        ds = fe.solve_asperity(geometry, fe_material(material_si), levels, accuracy=accuracy,
                               contact=asperity.get("contact", "penalty"))
    except (fe.ConvergenceError, fe.ContactZoneError) as err:
        raise RuntimeError(f"sample {key} (curvature {curvature:.6g} 1/m): {err}") from err
    ds.attrs.update(key=key, model="fe", curvature=curvature, geometry=repr(geometry),
                    height=float(row["sample_height"]), cpu_time=time.process_time() - cpu)
    return ds


def _loglog(levels: np.ndarray, values: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Interpolate positive increasing `values` at `levels` to `targets` (>= 0).

    Monotone cubic in (log w, log X) inside the levels; the power law of
    the first two levels below (X -> 0 as w -> 0); the last tangent above.
    Returns the values and a flag of the targets beyond the last level.
    """
    out = np.zeros_like(targets, dtype=float)
    lw, lx = np.log(levels), np.log(np.maximum(values, np.finfo(float).tiny))
    inside = (targets >= levels[0]) & (targets <= levels[-1])
    out[inside] = np.exp(PchipInterpolator(lw, lx)(np.log(targets[inside])))
    below = (targets > 0) & (targets < levels[0])
    p = (lx[1] - lx[0]) / (lw[1] - lw[0])
    out[below] = values[0] * (targets[below] / levels[0]) ** p
    above = targets > levels[-1]
    slope = (values[-1] - values[-2]) / (levels[-1] - levels[-2])
    out[above] = values[-1] + slope * (targets[above] - levels[-1])
    return out, above


def gather(plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """FE samples onto the plan's (height, curvature, interference) grid.

    Samples that share a key (derived by a shift in height) share the
    response.  ``extrapolated`` marks grid points beyond the sample's last
    computed level.
    """
    by_key = {str(ds.attrs["key"]): ds for ds in samples.values()}
    missing = sorted(set(plan["key"].values) - set(by_key))
    if missing:
        raise ValueError(f"{len(missing)} samples missing from the gather: {', '.join(missing)}")
    heights, curvatures = plan["height"].values, plan["curvature"].values
    grid = plan["interference"].values
    unique, index = np.unique(plan["key"].values, return_inverse=True)
    curves = {name: np.empty((unique.size, grid.size)) for name in GATHERED.values()}
    beyond = np.empty((unique.size, grid.size), bool)
    for u, key in enumerate(unique):  # one curve per FE job, each vectorized over the grid
        ds = by_key[str(key)]
        for source, name in GATHERED.items():
            curves[name][u], beyond[u] = _loglog(ds["interference"].values, ds[source].values, grid)
    shape = (heights.size, curvatures.size, grid.size)
    data = {name: c[index].reshape(shape) for name, c in curves.items()}
    extrapolated = beyond[index].reshape(shape)
    units = {"force": "N", "contact_area": "m^2", "contact_radius": "m", "stiffness": "N/m"}
    long = {"force": "normal contact force", "contact_area": "real contact area",
            "contact_radius": "contact radius (edge located between nodes)",
            "stiffness": "normal stiffness dF/dw"}
    dims = ("height", "curvature", "interference")
    ds = xr.Dataset(
        {name: (dims, data[name], {"units": units[name], "long_name": long[name]}) for name in data},
        coords={
            "height": ("height", heights, {"units": "m", "long_name": "asperity peak height"}),
            "curvature": ("curvature", curvatures, {"units": "1/m", "long_name": "tip curvature"}),
            "interference": ("interference", grid, {"units": "m", "long_name": "interference"}),
        },
    )
    jobs = [by_key[str(k)] for k in unique]
    ds.attrs.update(accuracy=str(jobs[0].attrs.get("accuracy", "")), fe_jobs=len(jobs),
                    fe_cpu_time=float(sum(j.attrs.get("cpu_time", np.nan) for j in jobs)))
    for attr, var in (("max_newton_iterations", "newton_iterations"), ("max_step_cuts", "step_cuts"),
                      ("max_dofs", "dofs")):
        if all(var in j for j in jobs):
            ds.attrs[attr] = int(max(j[var].max() for j in jobs))
    ds["extrapolated"] = (dims, extrapolated, {
        "units": "1", "long_name": "beyond the largest interference the FE job computed "
        "(continued with its last tangent)"})
    return ds
