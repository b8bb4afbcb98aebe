"""How a sample of the plan becomes the body of a finite element job (report 2.5.1, 8.2).

An FE asperity (``asperity.model: fe``) has a geometry:

- ``sphere`` / ``paraboloid`` of radius 1/kappa (the paraboloid is Hertz's
  idealization: a half space with a paraboloidal gap);
- ``cosine`` with the ``representative`` mapping of report 8.2: every hill has the
  width-to-height ratio of a cosine whose rms slope is the surface's,
  pi / (sqrt(2) sigma_slope), and the sample's tip curvature kappa = C k^2 (2.5.1);
  its peak height only shifts the interference;
- ``cosine`` with the ``coupled`` mapping of 2.5.1: the hill z = C cos(k r) of the
  sample has amplitude C = z_p (its peak height above the mean plane) and tip
  curvature kappa = C k^2. Only peaks above the mean plane are hills; they touch a
  flat at separation h >= 0 with w = z_p - h <= C, half their height.

Sphere, paraboloid and the representative hill respond to the interference alone
(shift invariant in height): one job per curvature. The coupled hill depends on both:
one job per (height, curvature), or, with ``scaling: self_similar``, a family of
aspects: its shape in units of 1/kappa depends on the aspect q = kappa z_p = (k C)^2
alone, so a few jobs at aspects q_j give every sample by the scaling of 8.2.2 and an
interpolation in log q (`asperity.population.plan.aspect_jobs`, `aspect_weights`). An FE job computes the
interferences up to the largest the geometry admits (`max_interference`).
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from asperity.population.plan import geometric_levels
from asperity.scene import Asperity, Material


def representative_width_to_height(sigma_slope: float) -> float:
    """Width/height of a cosine hill whose rms slope k C / sqrt(2) is sigma_slope (8.2).

    Width (valley to valley) 2 pi / k, height (peak to valley) 2 C, so the
    ratio is pi / (k C) = pi / (sqrt(2) sigma_slope).
    """
    return math.pi / (math.sqrt(2.0) * sigma_slope)


def fe_geometry(geometry: str, coupled: bool, curvature: float, width_to_height: float | None,
                height: float | None = None):
    """The `asperity.fe` profile ``sphere``, ``paraboloid`` or ``cosine`` of tip curvature
    `curvature` [1/m]; a `coupled` cosine hill has the peak height `height` [m] above
    the mean plane as its amplitude, a representative one the ratio `width_to_height`."""
    from asperity import fe

    if coupled:
        if not height or height <= 0:
            raise ValueError(f"coupled cosine hill needs a peak height above the mean plane, got {height}")
        return fe.CosineHill(height, math.sqrt(curvature / height))
    if geometry == "sphere":
        return fe.Sphere(1.0 / curvature)
    if geometry == "paraboloid":
        return fe.Paraboloid(1.0 / curvature)
    if geometry == "cosine":
        # kappa = C k^2 with pi / (k C) = ratio  ->  C = pi^2 / (ratio^2 kappa)
        amplitude = math.pi**2 / (width_to_height**2 * curvature)
        return fe.CosineHill.from_aspect(width_to_height, 2.0 * amplitude)
    raise ValueError(f"unknown asperity geometry {geometry!r}")


def sample_geometry(asperity: Asperity, curvature: float, width_to_height: float | None,
                    height: float | None = None):
    """The FE profile of a sample: `fe_geometry` of the scene's asperity, its own
    ``width_to_height`` or the representative one `width_to_height`."""
    ratio = asperity.width_to_height if asperity.width_to_height is not None else width_to_height
    return fe_geometry(asperity.geometry, asperity.coupled, curvature, ratio, height)


def spec_geometry(spec: Mapping[str, Any]):
    """The FE profile of a sample job's spec."""
    coupled = spec["geometry"] == "cosine" and spec["mapping"] == "coupled"
    return fe_geometry(spec["geometry"], coupled, float(spec["curvature"]),
                       spec.get("width_to_height"), spec.get("height"))


def max_interference(geometry, asperity: Asperity) -> float:
    """Largest interference an FE job computes for `geometry` [m].

    A cosine hill up to ``max_height_fraction`` of its height (report 7.3's
    small-strain range is reached well before); a sphere up to
    ``max_radius_fraction`` of its radius (contact radius about 0.7 R at a quarter,
    inside the modelled 45-degree cap), a paraboloid likewise; either capped at 0.9
    of the modelled cap's height (0.293 R for the sphere, R / 8 for the paraboloid),
    where the flat would reach its foot.
    """
    from asperity import fe

    if isinstance(geometry, fe.CosineHill):
        return asperity.max_height_fraction * 2.0 * geometry.amplitude
    if isinstance(geometry, (fe.Sphere, fe.Paraboloid)):
        return min(asperity.max_radius_fraction * geometry.radius, 0.9 * geometry.height)
    return math.inf


def fe_levels(w_first: float, w_last: float, count: int) -> np.ndarray:
    """`count` geometric interference levels from w_first to w_last."""
    if not 0 < w_first < w_last:
        raise ValueError(f"FE levels need 0 < first < last, got {w_first:g}, {w_last:g}")
    return geometric_levels(w_first, w_last, count)


def job_range(geometry, asperity: Asperity, grid: np.ndarray, curvature: float,
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


def self_similar(asperity: Asperity, material: Material | None, effects) -> bool:
    """Whether the samples of an FE asperity form a self-similar family (one job, the
    others scaled).

    Every asperity must be the same shape scaled (sphere, paraboloid, the
    representative cosine of fixed width-to-height ratio) and the body scale free:
    elastic or rate-independent plastic. ``scaling: self_similar`` forces it for a
    rate-dependent body (the report's assumption in 8.2.2: "due to absence of
    rate-dependent effects ... simple rescaling"), ``none`` forbids it.
    """
    if asperity.scaling == "none" or not asperity.shift_invariant:
        return False
    if asperity.scaling == "self_similar":
        return True
    return material.rate_independent(effects)


def unloading_levels(top: float, asperity: Asperity) -> tuple[np.ndarray, float]:
    """The interferences from which an asperity is unloaded (report 8.3), and the check level.

    ``unloading_levels`` levels (the report's "three to four") spread geometrically
    from ``unloading_smallest`` x `top` to `top`; below the smallest the asperity is
    taken to unload along its loading curve (elastic rebound of a barely yielded
    tip). With ``unloading_check`` one more level, the geometric mean of the second
    and third, is computed and left out of the blend to measure its error (the
    report's gamma_0 of Fig. 8.27); NaN otherwise.
    """
    count = int(asperity.unloading_levels)
    levels = geometric_levels(asperity.unloading_smallest * top, top, count)
    check = math.sqrt(levels[1] * levels[2]) if asperity.unloading_check and count >= 3 \
        else math.nan
    return levels, check


def aspect_job_range(geometry, asperity: Asperity, grid: np.ndarray) -> tuple[float, float]:
    """Smallest and largest interference [m] of an FE job of the aspect family.

    Up to `max_interference` (``max_height_fraction`` of the hill's height 2 C: with
    0.5 its amplitude, the deepest a hill is pressed at separations >= 0), from the
    same fraction of it as the plan's grid spans (its first positive level over its
    last): scale free, so that the jobs of two equal aspects are scaled copies and a
    sample's range in w / C is that of its neighbouring jobs.
    """
    pos = grid[grid > 0]
    top = max_interference(geometry, asperity)
    return float(top * pos[0] / pos[-1]), float(top)
