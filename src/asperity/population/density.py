"""The peak density of a scene's population (2.4.1, 7.1, 2.4.3) and the statistics it draws
on: which estimator of `surface.nc` feeds it, and the rectangle of its effective support."""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr

from asperity import peaks
from asperity.scene import Population
from asperity.surface.distribution import bearing_heights

log = logging.getLogger("asperity")


def default_density(surface_ds: xr.Dataset) -> str:
    estimator = surface_ds.attrs.get("population_estimator")
    return {"gaussian_heights": "fixed_curvature", "map": "sampled"}.get(estimator, "nayak")


def population_density(surface_ds: xr.Dataset, population: Population):
    """The peak density of a scene: Nayak/Francis, fixed curvature, or sampled."""
    kind = population.density or default_density(surface_ds)
    estimator = surface_ds.attrs.get("population_estimator")
    if kind == "fixed_curvature":
        if "sigma_peak_height" not in surface_ds:
            raise ValueError("population.density fixed_curvature needs surface.gaussian_heights")
        return peaks.FixedCurvatureDensity(
            sigma_p=float(surface_ds["sigma_peak_height"]),
            curvature=float(surface_ds["tip_curvature"]),
        )
    if kind == "sampled":
        if "peak" not in surface_ds.dims:
            raise ValueError("population.density sampled needs a 2-D map (surface.map)")
        return peaks.SampledDensity.from_peaks(
            surface_ds["height"].values, surface_ds["curvature"].values,
            bins=population.histogram_bins)
    stats = surface_ds.sel(estimator=estimator) if "estimator" in surface_ds.dims else surface_ds
    return peaks.JointDensity(
        sigma=float(stats["sigma"]),
        sigma_slope=float(stats["sigma_slope"]),
        sigma_curvature=float(stats["sigma_curvature"]),
    )


def peak_density(surface_ds: xr.Dataset) -> float:
    """Peaks per unit area (1/m^2) from the surface dataset."""
    return population_stat(surface_ds, "peak_density")


def population_stat(surface_ds: xr.Dataset, name: str) -> float:
    """A statistic of the estimator that feeds the population."""
    value = surface_ds[name]
    if "estimator" in value.dims:
        value = value.sel(estimator=surface_ds.attrs["population_estimator"])
    return float(value)


def heights_at_ratios(surface_ds: xr.Dataset):
    """``f(ratios)`` -> the heights [m] above which those shares of the prepared map lie
    (its bearing-area curve in surface.nc, `asperity.surface.distribution.bearing_heights`):
    the separations of unit ``bearing``; None where surface.nc has no curve."""
    if "bearing_height" not in surface_ds:
        return None
    ratio, height = surface_ds["material_ratio"].values, surface_ds["bearing_height"].values
    return lambda ratios: bearing_heights(ratio, height, ratios)


def scene_separations(homogenization, surface_ds: xr.Dataset) -> np.ndarray:
    """The separations [m] of a scene's `asperity.scene.Homogenization` on its surface."""
    return homogenization.separations(height_scale(surface_ds), heights_at_ratios(surface_ds))


def height_scale(surface_ds: xr.Dataset) -> float:
    """The standard deviation that `sigma` units of separation refer to."""
    if "sigma_peak_height" in surface_ds:
        return float(surface_ds["sigma_peak_height"])
    return population_stat(surface_ds, "sigma")


def bounds(density, height_range: tuple[float, float] | None,
           curvature_range: tuple[float, float] | None, threshold: float
           ) -> tuple[float, float, float, float]:
    """Integration/sampling rectangle: the effective support, or the scene's ranges
    (height [m], curvature [1/m]; None: the support's)."""
    z0, z1, k0, k1 = density.support(threshold)
    if height_range is not None:
        z0, z1 = height_range
    if curvature_range is not None:
        k0, k1 = curvature_range
    return float(z0), float(z1), float(k0), float(k1)
