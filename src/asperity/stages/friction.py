"""Stage `friction` (workflow/rules/friction.smk): the static coefficient of friction of
the interface (report 9.1) and analytic laws fitted to its loading curve (section 10),
with their figures."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity import friction, laws, scene

Config = Mapping[str, Any]
# the figure functions import their plots (matplotlib) themselves: the data jobs start without


def friction_dataset(interface: xr.Dataset, surface: xr.Dataset, friction_cfg: Config,
                     material: Config | None, units_cfg: Config) -> xr.Dataset:
    """`asperity.friction.friction_dataset` of the scene's ``friction`` and ``material``
    sections (None: no material)."""
    units = scene.Units.from_section(units_cfg)
    mat = scene.Material.from_scene(material, units) if material else None
    return friction.friction_dataset(interface, surface, scene.Friction.from_section(friction_cfg, units),
                                     mat)


def laws_dataset(interface: xr.Dataset, laws_cfg: Config, units_cfg: Config) -> xr.Dataset:
    """`asperity.laws.laws_dataset`: Oden-Martins (10.42) and exponential fits."""
    return laws.laws_dataset(interface, scene.Laws.from_section(laws_cfg, scene.Units.from_section(units_cfg)))


def friction_figure(friction_ds: xr.Dataset, units_cfg: Config,
                    others: Mapping[str, xr.Dataset] | None = None):
    from asperity.plots import friction as friction_plots

    return friction_plots.friction_figure(friction_ds, others or {},
                                          pressure_unit=units_cfg["pressure"],
                                          length_unit=units_cfg["length"])


def laws_figure(laws_ds: xr.Dataset, units_cfg: Config):
    from asperity.plots import friction as friction_plots

    return friction_plots.laws_figure(laws_ds, pressure_unit=units_cfg["pressure"],
                                      length_unit=units_cfg["length"])
