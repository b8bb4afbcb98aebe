"""Checks of a scene that its schema (config/schema.yaml) cannot make, each a one-line error.

A scene's values pass the schema one by one; these checks look at what the schema
does not: keys that one value makes necessary (an FE asperity needs a geometry), and
sizes that say the unit is wrong.  Every error is a `SceneError`,
``<file>: <key>: <what> (<likely fix>)``.

Unit sanity (`check_material`), in SI whatever the scene's pressure unit:

- a Young's modulus between 1 kPa (1e-3 MPa: the softest gels) and 2000 GPa (above
  diamond's 1050-1220 GPa, the stiffest solid);
- a yield stress, hardening modulus or hardness below the Young's modulus (a metal
  yields at 1e-3 to 1e-2 of E; the hardness of the hardest solids is a tenth of E);
- a yield stress above 1e-5 E (annealed pure lead and indium, the softest metals,
  yield at about 3e-4 E);
- a hardness at or above the yield stress (Tabor: H = 2.8 to 3 Y for a metal).

A value outside these is taken as given in another unit, and the error names the unit
that puts it in range, nearest a metal's (E 100 GPa, a stress 2e-3 E): "youngs_modulus
2.1e+11 MPa is 2.1e+08 GPa: ... (did you give Pa? write 2.1e5 in MPa, ...)".  Dimensionless scenes (pressure unit ``1``) are not checked.
"""

from __future__ import annotations

import math
import os
import re
from typing import Any, Mapping

from asperity import units as unit_table

__all__ = ["SceneError", "GEOMETRIES", "E_RANGE", "YIELD_OVER_E_MIN", "require_geometry",
           "require_elliptic_route",
           "check_material", "check_scene", "text_number_hint"]

GEOMETRIES = ("sphere", "paraboloid", "cosine", "elliptic")
#: the Young's moduli a solid has [Pa]
E_RANGE = (1e3, 2e12)
#: the smallest yield stress over Young's modulus of a metal
YIELD_OVER_E_MIN = 1e-5
#: where a misplaced number most likely belongs: a metal's Young's modulus [Pa], and a yield
#: stress over the modulus (steel: 350 MPa / 209 GPa)
TYPICAL_E = 1e11
TYPICAL_STRESS_OVER_E = 2e-3
#: pressure units a misplaced number is tried in, to name the likely one
_TRY_UNITS = ("Pa", "kPa", "MPa", "GPa")


class SceneError(ValueError):
    """A scene a user must change: ``<file>: <key>: <what> (<fix>)`` (no file: ``<key>: ...``).

    Attributes ``file`` (or None), ``key`` (dotted), ``what`` and ``fix`` (or None)."""

    def __init__(self, key: str, what: str, fix: str | None = None, file=None):
        self.key, self.what, self.fix = key, what, fix
        self.file = None if file is None else os.fspath(file)
        text = f"{key}: {what}" + (f" ({fix})" if fix else "")
        super().__init__(text if self.file is None else f"{self.file}: {text}")

    def in_file(self, file) -> "SceneError":
        """The same error naming the scene file."""
        return SceneError(self.key, self.what, self.fix, file)


def require_geometry(section: Mapping[str, Any] | None, key: str = "asperity") -> None:
    """An FE asperity (``model: fe``) names its geometry, one of `GEOMETRIES` (2.5.1, 6.1)."""
    if not section or section.get("model") != "fe":
        return
    geometry = section.get("geometry")
    if geometry is None:  # elliptic summits serve one route alone (`require_elliptic_route`)
        raise SceneError(f"{key}.geometry", "an FE asperity (model: fe) needs its geometry",
                         f"add geometry: {' | '.join(g for g in GEOMETRIES if g != 'elliptic')}")
    if geometry not in GEOMETRIES:
        raise SceneError(f"{key}.geometry", f"unknown geometry {geometry!r}",
                         f"use one of {' | '.join(GEOMETRIES)}")


def require_elliptic_route(asperity: Mapping[str, Any] | None, route: Mapping[str, Any] | None,
                           key: str = "asperity") -> None:
    """Elliptic FE summits (``geometry: elliptic``) serve the anisotropic route's ``law: fe``
    alone: the isotropic homogenization has no curvature ratio to integrate over."""
    if not asperity or asperity.get("geometry") != "elliptic":
        return
    route = route or {}
    if route.get("kind") != "anisotropic" or route.get("law") != "fe":
        raise SceneError(f"{key}.geometry", "elliptic summits serve the anisotropic route alone",
                         "add route: {kind: anisotropic, law: fe}, or use geometry: sphere")


def _likely_unit(value: float, ok, typical: float) -> str | None:
    """Of `_TRY_UNITS` in which `value` passes `ok` (an SI predicate), the one that puts it
    nearest `typical` [Pa] on a log scale; None if none does."""
    fits = [u for u in _TRY_UNITS if ok(value * unit_table.PRESSURE[u])]
    return min(fits, key=lambda u: abs(math.log(value * unit_table.PRESSURE[u] / typical)), default=None)


def _rewrite(value: float, unit: str, scene_unit: str) -> str:
    return f"{value * unit_table.PRESSURE[unit] / unit_table.PRESSURE[scene_unit]:.3g}".replace("e+0", "e")\
        .replace("e+", "e").replace("e-0", "e-")


def _magnitude_error(key: str, name: str, value: float, scene_unit: str, ok, why: str,
                     typical: float) -> SceneError:
    si = value * unit_table.PRESSURE[scene_unit]
    likely = _likely_unit(value, ok, typical)
    what = f"{name} {value:.3g} {scene_unit} is {si / 1e9:.3g} GPa: {why}"
    if likely is None or likely == scene_unit:
        return SceneError(key, what, "check the value and units.pressure")
    return SceneError(key, what, f"did you give {likely}? write {_rewrite(value, likely, scene_unit)} "
                                 f"in {scene_unit}, or set units.pressure: {likely}")


def check_material(section: Mapping[str, Any] | None, pressure_unit: str, key: str = "material") -> None:
    """Unit sanity of a ``material`` section in the pressure unit `pressure_unit` (module text)."""
    if not section or pressure_unit not in unit_table.PRESSURE or pressure_unit == "1":
        return
    p = unit_table.PRESSURE[pressure_unit]
    E = section.get("youngs_modulus")
    lo, hi = E_RANGE
    if isinstance(E, (int, float)) and not lo <= E * p <= hi:
        raise _magnitude_error(f"{key}.youngs_modulus", "youngs_modulus", E, pressure_unit,
                               lambda si: lo <= si <= hi,
                               f"a Young's modulus is {lo / 1e6:g} MPa to {hi / 1e9:g} GPa", TYPICAL_E)
    if not isinstance(E, (int, float)) or E <= 0:
        return
    yield_stress = section.get("yield_stress")
    for name in ("yield_stress", "hardening_modulus", "hardness"):
        v = section.get(name)
        if isinstance(v, (int, float)) and v >= E:
            raise _magnitude_error(f"{key}.{name}", name, v, pressure_unit, lambda si: si < E * p,
                                   f"at or above youngs_modulus {E:.3g} {pressure_unit}",
                                   TYPICAL_STRESS_OVER_E * E * p)
    if isinstance(yield_stress, (int, float)) and yield_stress < YIELD_OVER_E_MIN * E:
        raise _magnitude_error(f"{key}.yield_stress", "yield_stress", yield_stress, pressure_unit,
                               lambda si: YIELD_OVER_E_MIN * E * p <= si < E * p,
                               f"below {YIELD_OVER_E_MIN:g} youngs_modulus (the softest metals yield "
                               f"at 3e-4 E)", TYPICAL_STRESS_OVER_E * E * p)
    hardness = section.get("hardness")
    if isinstance(hardness, (int, float)) and isinstance(yield_stress, (int, float)) \
            and hardness < yield_stress:
        raise SceneError(f"{key}.hardness", f"hardness {hardness:.3g} {pressure_unit} is below "
                                            f"yield_stress {yield_stress:.3g} {pressure_unit}",
                         f"a hardness is about 2.8 yield stresses (Tabor); a Vickers number HV is in "
                         f"kgf/mm^2: H = {9.80665:.4g} HV MPa")


def check_scene(scene: Mapping[str, Any], file=None) -> None:
    """The checks of this module on a scene (a scene file's content, with or without the
    schema's defaults; its statistical routes too); a `SceneError` names `file`."""
    try:
        pressure = (scene.get("units") or {}).get("pressure", "MPa")
        require_geometry(scene.get("asperity"))
        require_elliptic_route(scene.get("asperity"), scene.get("route"))
        check_material(scene.get("material"), pressure)
        for name, route in (scene.get("routes") or {}).items():
            if isinstance(route, Mapping):
                require_geometry(route.get("asperity"), f"routes.{name}.asperity")
                require_elliptic_route(route.get("asperity"), route.get("route"), f"routes.{name}.asperity")
    except SceneError as err:
        raise err.in_file(file) if file is not None else err from None


#: a number PyYAML (YAML 1.1) reads as text: an exponent without its sign ("210e9", "70.0e9";
#: YAML 1.1 wants a decimal point and a signed exponent, "210.0e+9")
_TEXT_NUMBER = re.compile(r"^[+-]?\d+(\.\d*)?[eE]\d+$")


def text_number_hint(value) -> str:
    """For a schema error on `value`: " (YAML reads 210e9 as text: write 210.0e+9)" where
    `value` is such a number read as text, else ""."""
    if not isinstance(value, str) or not _TEXT_NUMBER.match(value.strip()):
        return ""
    mantissa, exponent = re.split("[eE]", value.strip())
    if "." not in mantissa:
        mantissa += ".0"
    elif mantissa.endswith("."):
        mantissa += "0"
    return f" (YAML reads {value} as text: write {mantissa}e+{exponent})"
