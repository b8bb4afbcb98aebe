"""The material of a result file, for figure titles and closed-form curves.

A result file of the pipeline keeps the scene's config that made it in its
``config`` attribute (`asperity.io.netcdf.scene_config`): its ``material`` section
in the scene's pressure unit (``units.pressure``) and, for asperities.nc, the
``asperity`` model and ``effects``.  The interface's validity adds the hardness H
it used, with its rule (`asperity.homogenize.validity`, variable ``hardness``).
"""

from __future__ import annotations

import math

import xarray as xr

from asperity import units
from asperity.io.netcdf import scene_config

__all__ = ["scene_material", "material_title", "is_elastic_fe"]

#: the material's entries that are stresses (scene pressure unit in the config)
STRESSES = ("youngs_modulus", "yield_stress", "hardness")


def scene_material(ds: xr.Dataset) -> dict:
    """The material of `ds` in SI: ``model``, ``youngs_modulus`` [Pa], ``poisson``,
    ``yield_stress`` [Pa], ``hardness`` [Pa] and ``hardness_rule`` where the file says
    them (the ``hardness`` variable first, then the config), ``preset`` (a Bodner-Partom
    set); empty if the file has no material."""
    cfg = scene_config(ds)
    section = cfg.get("material") or {}
    scale = units.pressure_scale((cfg.get("units") or {}).get("pressure", "Pa"))
    out = {k: float(section[k]) * scale for k in STRESSES if section.get(k) is not None}
    if section.get("poisson") is not None:
        out["poisson"] = float(section["poisson"])
    if section:
        out["model"] = str(section.get("model", "elastic"))
    preset = (section.get("bodner_partom") or {}).get("preset")
    if preset:
        out["preset"] = str(preset)
    if "hardness" in ds and math.isfinite(float(ds["hardness"])):
        out["hardness"] = float(ds["hardness"])
        out["hardness_rule"] = ds["hardness"].attrs.get("long_name", "").partition("hardness H: ")[2]
    elif "hardness" in out:
        out["hardness_rule"] = "given in the scene"
    return out


def material_title(ds: xr.Dataset, pressure_unit: str = "Pa") -> str:
    """"material: <model>, E = ..., ν = ..., yield stress ..., hardness H = ... (rule)",
    stresses in `pressure_unit`; "" if the file has no material."""
    m = scene_material(ds)
    if not m:
        return ""
    ps = units.pressure_scale(pressure_unit)
    parts = [m["model"] + (f" ({m['preset']})" if "preset" in m else "")] if "model" in m else []
    if "youngs_modulus" in m:
        parts.append(f"E = {m['youngs_modulus'] / ps:.6g} {pressure_unit}")
    if "poisson" in m:
        parts.append(f"ν = {m['poisson']:.4g}")
    if "yield_stress" in m:
        parts.append(f"yield stress {m['yield_stress'] / ps:.6g} {pressure_unit}")
    if "hardness" in m:
        rule = f" ({m['hardness_rule']})" if m.get("hardness_rule") else ""
        parts.append(f"hardness H = {m['hardness'] / ps:.4g} {pressure_unit}{rule}")
    return "material: " + ", ".join(parts)


def is_elastic_fe(ds: xr.Dataset) -> bool:
    """Whether `ds` (asperities.nc) holds finite element asperities of a linear elastic
    body: the config's ``asperity.model`` is ``fe`` and its effects are of the kind
    ``elastic`` (`asperity.population.kinds.kind_of`: no plasticity, no adhesion)."""
    cfg = scene_config(ds)
    if (cfg.get("asperity") or {}).get("model") != "fe":
        return False
    effects = set(cfg.get("effects") or ())
    return not effects & {"plasticity", "adhesion"}
