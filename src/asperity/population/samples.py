"""The samples of a scene: the plan (DESIGN.md: which asperities to compute), the
response of one sample, and the gather of all of them (report 2.4, 2.5.1, 8.2, 8.3).

The plan lays samples on a grid over the effective support of the peak density
(2.5.1, assumption (a)) or the scene's ranges; the asperity's kind
(`asperity.population.kinds`) gives the interference grid, each sample's unloading
levels and the spec of its job, whose hash is its key. Where the physics makes the
samples one self-similar family (the same shape scaled, a scale-free body) one job
computes the asperity of a reference curvature and the others are derived by scaling;
coupled hills (2.5.1) under ``scaling: self_similar`` are scaled from a few jobs at
fixed aspects and interpolated between them (`asperity.population.plan.make_aspect_plan`).
"""

from __future__ import annotations

import json
import logging
from typing import Mapping

import numpy as np
import xarray as xr

from asperity import peaks
from asperity.population.density import bounds, population_density, population_stat
from asperity.population.geometry import representative_width_to_height
from asperity.population.kinds import Planning, SampleFailed, kind_of, kind_of_plan, kind_of_spec
from asperity.population.plan import interference_grid, make_aspect_plan, make_plan, sample_grid
from asperity.scene import Adhesion, Asperity, Material, Population
from asperity.units import attrs

log = logging.getLogger("asperity")


def scene_plan(surface_ds: xr.Dataset, population: Population, asperity: Asperity,
               material: Material | None, effects: frozenset[str], accuracy: str,
               adhesion: Adhesion | None = None) -> xr.Dataset:
    """The samples a scene needs (DESIGN.md: the plan): heights x curvatures (x the
    unloading levels of each), their keys and specs, which are derived, and the
    attributes the later stages need (``kind``, ``support``, ...); `adhesion` is used
    with the effect ``adhesion``. Elliptic summits (``geometry: elliptic``) are planned
    over their curvature ratio instead (`elliptic_plan`)."""
    kind = kind_of(asperity.model, effects, asperity.geometry)
    kind.check(asperity, material, effects)
    if kind.name == "elliptic":
        return elliptic_plan(surface_ds, asperity, material, accuracy)
    density = population_density(surface_ds, population)
    threshold = population.support_threshold
    z0, z1, k0, k1 = bounds(density, population.height_range, population.curvature_range, threshold)
    if asperity.coupled:  # hills exist above the mean plane only (2.5.1)
        heights = sample_grid(0.0, z1, population.heights, positive=True)
    else:
        heights = sample_grid(z0, z1, population.heights)
    curvatures = (
        np.array([density.curvature])
        if isinstance(density, peaks.FixedCurvatureDensity)
        else sample_grid(k0, k1, population.curvatures, positive=True)
    )
    count = population.interferences
    grid = kind.grid(interference_grid(z1 - z0, count), z1 - z0, count, adhesion)
    width_to_height = None
    if asperity.geometry == "cosine" and asperity.width_to_height is None:
        width_to_height = representative_width_to_height(population_stat(surface_ds, "sigma_slope"))
    scaled = kind.scalable(asperity, material, effects) and curvatures.size > 1
    family = asperity.aspect_family and kind.job  # coupled hills scaled from a few aspects
    reference = None
    if scaled or family:
        reference = (asperity.reference_curvature if asperity.reference_curvature
                     else float(np.sqrt(curvatures[0] * curvatures[-1])))
    planning = Planning(asperity=asperity, material=material, effects=effects, accuracy=accuracy,
                        adhesion=adhesion, grid=grid, family=curvatures if scaled else None,
                        width_to_height=width_to_height)
    levels_of, check_of = None, None
    if kind.unloads(effects):

        def levels_of(h, k):
            levels, check = kind.levels(planning, h, k)
            return np.sort(np.append(levels, check)) if np.isfinite(check) else levels

        def check_of(h, k):
            return kind.levels(planning, h, k)[1]

    if family:  # (2.5.1, 8.2.2)
        if "adhesion" in effects:
            raise ValueError("effect `adhesion` has a length of its own (the range d): its coupled "
                             "hills are no family of aspects (asperity.scaling: auto)")
        if kind.unloads(effects):
            raise ValueError("effect `unloading` is not available for the coupled hills' family of "
                             "aspects (asperity.mapping coupled with scaling self_similar)")
        out = make_aspect_plan(heights, curvatures, grid, model=asperity.model,
                               job_spec=lambda h, k, level: kind.spec(planning, h, k, level),
                               aspects=asperity.aspects, check=asperity.aspect_check,
                               reference_curvature=reference)
        scaled = True
    else:
        out = make_plan(heights, curvatures, grid, model=asperity.model,
                        job_spec=lambda h, k, level: kind.spec(planning, h, k, level),
                        shift_invariant=asperity.shift_invariant, analytic=not kind.job,
                        unloading_levels=levels_of, reference_curvature=reference)
    out.attrs["kind"] = kind.name
    if scaled and not material.rate_independent(effects):
        out.attrs["scaling_assumption"] = (
            "self-similar scaling of a rate-dependent body (asperity.scaling: self_similar): "
            "rate effects of the scaled strain rates ignored, as the report does in 8.2.2")
    out.attrs["shift_invariant"] = int(asperity.shift_invariant)
    if check_of is not None:
        check = np.array([check_of(h, k) for h, k in
                          zip(out["sample_height"].values, out["job_curvature"].values)])
        out["left_out"] = ("sample", out["unloading_level"].values == check, attrs(
            "1", "unloading path computed to check the blend, left out of it (report 8.3, gamma_0)"))
    if width_to_height is not None:
        out.attrs["width_to_height"] = width_to_height
    out.attrs["support"] = f"height [{z0:.6g}, {z1:.6g}] m, curvature [{k0:.6g}, {k1:.6g}] 1/m"
    out.attrs["support_threshold"] = threshold
    out.attrs.update(kind.plan_attrs(planning))
    log.info("plan: %d samples, %s", out.sizes["sample"], out.attrs["derived"])
    return out


def elliptic_plan(surface_ds: xr.Dataset, asperity: Asperity, material: Material,
                  accuracy: str) -> xr.Dataset:
    """The jobs of the elliptic summits of the Gaussian anisotropic surface of surface.nc's
    spectral moments (`asperity.population.kinds.elliptic`): `Asperity.ratios` curvature
    ratios geometrically spaced from the 5 % quantile of t = kappa_2 / kappa_1 over the
    summits (at least `SMALLEST_RATIO`) to 1, at the reference curvature (the scene's, or
    the summits' median kappa_1); each job's range reaches the deepest interference of
    any summit of the density's support (its height span times its largest kappa_1, in
    the reference curvature's units), or `Asperity.yield_multiple` times first yield."""
    from asperity.peaks.anisotropic import AnisotropicDensity
    from asperity.population.kinds.elliptic import ELLIPTIC, RATIO_QUANTILE, SMALLEST_RATIO
    from asperity.population.plan import geometric_levels, make_ratio_plan

    density = AnisotropicDensity.from_surface(surface_ds)
    _, k1, t, weight = density.nodes()

    def quantile(values, share, q):
        cumulative = np.cumsum(share) / np.sum(share)
        return float(values[min(int(np.searchsorted(cumulative, q)), values.size - 1)])

    smallest = max(quantile(t, weight.sum(axis=(0, 1)), RATIO_QUANTILE), SMALLEST_RATIO)
    ratios = geometric_levels(smallest, 1.0, asperity.ratios) if smallest < 1.0 else np.array([1.0])
    reference = asperity.reference_curvature or quantile(k1, weight.sum(axis=(0, 2)), 0.5)
    z_lo, z_hi, k_max = density.support()
    deepest = (z_hi - z_lo) * k_max / reference
    out = make_ratio_plan(ratios, model=asperity.model, reference_curvature=reference,
                          job_spec=lambda r: ELLIPTIC.ratio_spec(material, accuracy, reference, r, deepest,
                                                                 asperity.yield_multiple))
    out.attrs.update(kind=ELLIPTIC.name, shift_invariant=1,
                     support=f"kappa_2 / kappa_1 [{smallest:.4g}, 1] (the {RATIO_QUANTILE:.0%} quantile "
                             f"of the summits, at least {SMALLEST_RATIO:.4g})")
    log.info("plan: %d elliptic jobs, %s", out.sizes["sample"], out.attrs["derived"])
    return out


def solve(spec: Mapping, key: str) -> xr.Dataset:
    """The response of one sample job (DESIGN.md: samples/<key>.nc) from its spec
    (stored in the plan: everything it depends on), by the spec's kind."""
    return kind_of_spec(spec).solve(spec, key)


def solve_or_failure(spec: Mapping, key: str) -> xr.Dataset:
    """`solve`, or, when the job fails (`SampleFailed`), a record of the failure
    (attrs ``status`` "failed" and ``error`` naming sample and step): the other
    samples go on, and the gather refuses to homogenize over the hole and names it
    (`asperity.population.gather.samples_by_key`)."""
    try:
        ds = solve(spec, key)
    except SampleFailed as err:
        log.error("%s", err)
        return xr.Dataset(attrs={"key": key, "status": "failed", "error": str(err),
                                 "curvature": float(spec["curvature"])})
    ds.attrs["status"] = "ok"
    return ds


def solve_planned(plan_ds: xr.Dataset, key: str) -> xr.Dataset:
    """The response of sample `key` of a plan: `solve` of its stored spec."""
    match = np.flatnonzero(plan_ds["key"].values == key)
    if match.size == 0:
        raise ValueError(f"sample {key}: not in the plan")
    return solve(json.loads(str(plan_ds["spec"].values[int(match[0])])), key)


def gather(plan_ds: xr.Dataset, samples: Mapping[str, xr.Dataset] | None = None) -> xr.Dataset:
    """The responses of all samples on (height, curvature, interference), by the
    plan's kind."""
    return kind_of_plan(plan_ds).gather(plan_ds, samples or {})
