"""A scene's sections as objects in SI.

`materials`: the scene's material in SI and the constitutive body it names
(report 3.2.2). The functions here turn other scene values into SI.
"""

from __future__ import annotations

from typing import Any, Mapping

from asperity import units
from asperity.scene import materials

Config = Mapping[str, Any]


def length_factor(units_cfg: Config) -> float:
    return units.length_scale(units_cfg["length"])


def material_si(material: Config, units_cfg: Config) -> dict[str, Any]:
    """The scene's material in SI (`asperity.scene.materials.material_si`)."""
    return materials.material_si(material, units_cfg)


def hardness_si(material: Config, units_cfg: Config) -> float | None:
    """The material's hardness [Pa] if the scene gives one (``material.hardness``; it
    enters no job's key: only the validity of the interface uses it)."""
    h = material.get("hardness")
    return None if h is None else float(h) * units.pressure_scale(units_cfg.get("pressure", "Pa"))


def velocity_si(asperity: Config, units_cfg: Config) -> float | None:
    """The flat's loading velocity [m/s] (report 8.2.2), None if the scene gives none."""
    v = asperity.get("velocity")
    return None if v is None else float(v) * length_factor(units_cfg)
