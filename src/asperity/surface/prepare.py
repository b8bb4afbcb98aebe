"""Preparing a measured profile or map before any statistic is taken, as ISO 16610
prescribes (report 2.3.1 assumes a stationary profile about its mean line):

1. undefined points: their share is checked against the scene's limit; islands of
   defined points (regions without an interior point, `asperity.surface.islands`) are
   marked undefined (``surface.undefined.islands: drop``); then the undefined points
   are optionally filled (harmonic in-fill);
2. form removal (least-squares mean, tilt or polynomial);
3. the Gaussian filter (lambda_c, lambda_s), and the run-in and run-out of lambda_c / 2
   dropped;
4. for a map with a lateral scale (``surface.scale``), the low pass at that scale
   (`asperity.surface.summits`), periodic over the map.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Any

import numpy as np

from asperity.scene.surface import SurfaceScene
from asperity.surface.filters import filter_heights
from asperity.surface.form import remove_form
from asperity.surface.missing import harmonic_fill, islands
from asperity.surface.statistics import DEFAULT_ORDER
from asperity.surface.summits import default_scale, lowpass_map

log = logging.getLogger("asperity")

__all__ = ["Prepared", "prepare", "lateral_scale", "check_length"]


@dataclass
class Prepared:
    """A profile or map after form removal and filtering, and what was removed."""

    raw: np.ndarray  # heights as read (m), NaN where undefined
    form: np.ndarray  # the removed polynomial plus the lambda_c mean line (m)
    roughness: np.ndarray  # what the statistics see, NaN where undefined or outside the region
    defined: np.ndarray  # the points the statistics may use: defined, and no island
    region: tuple[slice, ...]  # the evaluation region (index slices, rows first for maps)
    undefined_share: float  # of the file
    filled: int  # points filled by harmonic in-fill
    islands: int  # defined points dropped as islands (`asperity.surface.islands`)
    spacing: Any  # dx or (dx, dy)
    scale: float | None = None  # a map's lateral scale (m): its low pass and its summits; None: pixel
    scale_rule: str = ""  # how the scale was chosen
    unsmoothed: np.ndarray | None = None  # with a scale: the roughness before its low pass

    @property
    def evaluated(self) -> np.ndarray:
        """The roughness over the evaluation region."""
        return self.roughness[self.region]

    @property
    def evaluated_defined(self) -> np.ndarray:
        return np.isfinite(self.evaluated)


def prepare(heights, spacing, scene: SurfaceScene, defined=None) -> Prepared:
    """Undefined points, form removal and filtering of a measured profile or map (see module text).

    ``heights`` are in metres (1-D profile, or 2-D map ``z[i, j] = z(x = j
    dx, y = i dy)``), ``spacing`` dx or (dx, dy); ``defined`` False at
    undefined points.  Raises ValueError naming the scene key when the share
    of undefined points is above ``surface.undefined.max_share``, or when
    too little is left after filtering.
    """
    z = np.array(heights, dtype=np.float64)
    mask = np.isfinite(z) if defined is None else (np.asarray(defined, bool) & np.isfinite(z))
    if not mask.any():
        raise ValueError(f"every point of the {'profile' if z.ndim == 1 else 'map'} is undefined")
    share = 1.0 - float(np.count_nonzero(mask)) / mask.size
    if share > scene.max_undefined_share:
        raise ValueError(
            f"{100 * share:.1f} % of the points are undefined, more than the scene allows "
            f"(key surface.undefined.max_share = {scene.max_undefined_share:g}); raise it to accept the "
            "measurement, or set surface.undefined.fill: harmonic to fill them"
        )
    z[~mask] = np.nan
    raw = z.copy()
    dropped = 0
    if scene.islands == "drop":
        cut = islands(mask)
        dropped = int(np.count_nonzero(cut))
        if dropped == np.count_nonzero(mask):
            raise ValueError(
                f"no defined point of the {'profile' if z.ndim == 1 else 'map'} has all its neighbours "
                f"defined: every one lies in an island (key surface.undefined.islands = drop); set it "
                "to keep to use them"
            )
        if dropped:
            mask = mask & ~cut
            z[cut] = np.nan
            log.info("dropped %d defined points in regions without an interior point (islands; "
                     "surface.undefined.islands: keep uses them)", dropped)
    filled = 0
    if scene.fill == "harmonic" and share > 0:
        z = harmonic_fill(np.where(mask, z, 0.0), mask)
        filled = int(mask.size - np.count_nonzero(mask))
        log.info("harmonic in-fill of %d undefined points (%.2f %%)", filled, 100 * share)
    use = np.isfinite(z)
    residual, form = remove_form(z, scene.form, scene.polynomial_degree, use)
    rough, waviness, region = filter_heights(residual, spacing, scene.lambda_c, scene.lambda_s, use)
    check_length(rough, spacing, scene, region)
    outside = np.ones(rough.shape, dtype=bool)
    outside[region] = False
    rough[outside] = np.nan
    scale, rule = lateral_scale(rough, spacing, scene)
    unsmoothed = None
    if scale is not None:  # the map as one period, low-passed at its scale (no edge is cut)
        dx, dy = (float(v) for v in spacing)
        unsmoothed = rough
        rough = lowpass_map(rough, dx, dy, scale, periodic=True, defined=np.isfinite(rough))
        log.info("lateral scale %s: the map low-passed at it (periodic Gaussian, ISO 16610-61 "
                 "transmission), its summits found and fitted at it", rule)
    return Prepared(raw, form + waviness, rough, mask, region, share, filled, dropped, spacing, scale,
                    rule, unsmoothed)


def lateral_scale(rough: np.ndarray, spacing, scene: SurfaceScene) -> tuple[float | None, str]:
    """The map's lateral scale (m) and its rule: the scene's ``surface.scale``, or
    `asperity.surface.summits.default_scale` for ``auto``; (None, "") for the pixel's."""
    if scene.scale is None:
        return None, ""
    dx, dy = (float(v) for v in spacing)
    if scene.scale == "auto":
        return default_scale(dx, dy, rough, defined=np.isfinite(rough))
    return float(scene.scale), f"lambda_s = {float(scene.scale):.6g} m (surface.scale)"


def check_length(rough: np.ndarray, spacing, scene: SurfaceScene, region):
    """After filtering, at least one cut-off wavelength and a stencil's worth of points must remain."""
    steps = np.atleast_1d(np.asarray(spacing, dtype=np.float64))
    axis_steps = [float(steps[0])] if rough.ndim == 1 else [float(steps[-1]), float(steps[0])]
    names = ["x"] if rough.ndim == 1 else ["y", "x"]
    what = "profile" if rough.ndim == 1 else "map"
    need_points = DEFAULT_ORDER + 2
    for sl, n, h, name in zip(region, rough.shape, axis_steps, names):
        kept = max(0, sl.stop - sl.start)
        widest = scene.lambda_c if scene.lambda_c is not None else scene.lambda_s
        if widest is None:
            continue
        if kept * h < widest or kept < need_points:
            raise ValueError(
                f"{what} too short after filtering: {n} points ({n * h:.6g} m) along {name}; the filter "
                f"(key surface.filter, cut-off {widest:.6g} m) drops {widest / 2:.6g} m at each end and "
                f"leaves {kept} points ({kept * h:.6g} m), less than one cut-off wavelength or the "
                f"{need_points} points the statistics need. Use a shorter cut-off or a longer record"
            )
