"""Stage `figures` (workflow/rules/figures.smk): the figures of a scene, drawn from its
datasets (`asperity.plots`); each function returns a matplotlib Figure that the
script saves through `asperity.io.figures`."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import plots, scene
from asperity.plots import adhesion as adhesion_plots
from asperity.population.density import population_density

Config = Mapping[str, Any]


def surface_figure(kind: str, surface: xr.Dataset, units_cfg: Config,
                   convergence: xr.Dataset | None = None):
    """The surface figure of a scene, from its surface.nc: `kind` is the scene's surface
    source (profile, profiles, map, statistics, gaussian_heights)."""
    length_unit = units_cfg["length"]
    if kind == "profiles":
        return plots.directional_figure(surface, length_unit=length_unit)
    if kind == "map":
        return plots.map_figure(surface, length_unit=length_unit)
    return plots.surface_figure(surface, convergence, length_unit=length_unit)


def density_on_grid(surface_ds: xr.Dataset, population: Config, units_cfg: Config, rect,
                    n: int = 200):
    """The joint peak density on an n x n grid over `rect` (for figures)."""
    units = scene.Units.from_section(units_cfg)
    density = population_density(surface_ds, scene.Population.from_section(population, units))
    z = np.linspace(rect[0], rect[1], n)
    kappa = np.linspace(rect[2], rect[3], n)
    return z, kappa, density.pdf(z[:, None], kappa[None, :])


def expectation_figure(surface: xr.Dataset, expectation: xr.Dataset, population: Config,
                       units_cfg: Config):
    """The peak density over the integration rectangle, and E(X) (report Fig. 2.13)."""
    z, kappa, f = density_on_grid(surface, population, units_cfg, expectation["rectangle"].values)
    return plots.expectation_figure(f, z, kappa, expectation)


def interface_figure(interface: xr.Dataset, units_cfg: Config, verification: xr.Dataset | None = None,
                     others: Mapping[str, xr.Dataset] | None = None):
    return plots.interface_figure(interface, verification, length_unit=units_cfg["length"],
                                  pressure_unit=units_cfg["pressure"], others=others or {})


def adhesion_figure(interface: xr.Dataset, asperities: xr.Dataset, units_cfg: Config,
                    others: Mapping[str, xr.Dataset] | None = None):
    return adhesion_plots.adhesion_figure(interface, asperities, others or {},
                                          length_unit=units_cfg["length"],
                                          pressure_unit=units_cfg["pressure"])


def asperities_figure(asperities: xr.Dataset, units_cfg: Config,
                      others: Mapping[str, xr.Dataset] | None = None):
    """Single asperities against Hertz (report 6.1, 7.2), lengths and the material's
    stresses in the scene's units."""
    return plots.asperities_figure(asperities, others or {}, length_unit=units_cfg["length"],
                                   pressure_unit=units_cfg.get("pressure", "Pa"))


def verification_figure(verification: xr.Dataset):
    return plots.hertz_verification_figure(verification)


def unloading_figure(unloading: xr.Dataset, units_cfg: Config):
    return plots.unloading_figure(unloading, length_unit=units_cfg["length"])
