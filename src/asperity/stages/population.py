"""Stage `population` (workflow/rules/population.smk): the plan of asperity samples, one
sample's response, and the gather of all samples (report 2.4, 8.2).

The plan takes the scene's sections as the scene file spells them (validated, with the
defaults of config/schema.yaml) and turns them into `asperity.scene` objects."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity import scene
from asperity.population import samples as population

Config = Mapping[str, Any]


def plan_dataset(
    surface_ds: xr.Dataset,
    population_cfg: Config,
    asperity: Config,
    material: Config | None,
    effects: list[str],
    units_cfg: Config,
    accuracy: str,
    adhesion: Config | None = None,
) -> xr.Dataset:
    """The samples a scene needs (DESIGN.md: the plan); `adhesion`: the scene's section,
    used with the effect ``adhesion``."""
    units = scene.Units.from_section(units_cfg)
    effect_set = scene.effects(effects)
    return population.scene_plan(
        surface_ds, scene.Population.from_section(population_cfg, units),
        scene.Asperity.from_section(asperity, units),
        scene.Material.from_scene(material, units) if material else None, effect_set, accuracy,
        scene.Adhesion.from_section(adhesion) if "adhesion" in effect_set else None)


def asperities_dataset(plan: xr.Dataset, samples: Mapping[str, xr.Dataset] | None = None
                       ) -> xr.Dataset:
    """Responses of all samples on (height, curvature, interference), by the plan's kind."""
    return population.gather(plan, samples)


def sample_dataset(spec: Config, key: str) -> xr.Dataset:
    """The response of one sample job from its spec (stored in the plan), or the record
    of its failure (`asperity.population.samples.solve_or_failure`)."""
    return population.solve_or_failure(spec, key)
