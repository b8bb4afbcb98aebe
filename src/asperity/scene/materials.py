"""A scene's `material` section: to SI, and to the `asperity.fe` material object.

One place converts what a scene says about its material (report 3.2: the
elastic constants; 3.2.2: J2 plasticity or Bodner-Partom with its
hardening, recovery and damage constants) into SI and into the object the
finite element solvers and the uniaxial driver use.  Which mechanisms act
is decided by the scene's *effects*, not by zero constants:

- without ``plasticity`` the body is linear elastic (its ``yield_stress``,
  if given, only sets the ``elastic`` flag of report 7.3);
- with ``plasticity`` it is the scene's ``model`` (``j2``: rate-independent
  J2 with linear hardening; ``bodner_partom``: the unified viscoplastic
  model 3.13-3.15, starting from a named set of the report and any
  constants overridden);
- ``damage`` switches the isotropic damage of Bodner-Partom on (its
  constants in ``damage``).

Units: stresses (E, yield stress, hardening modulus, Z0..Z3, H) in the
scene's pressure unit, m1 and m2 in 1/(pressure unit), rates (D0, A1, A2,
damage rate) in 1/s.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from asperity import units

Config = Mapping[str, Any]

#: constant -> (dataclass field, kind, unit in the file, long name)
#: kind: "pressure" (scene pressure unit), "compliance" (1 / pressure unit),
#: "plain" (SI as given: 1/s or dimensionless)
CONSTANTS = {
    "E": ("E", "pressure", "Pa", "Young's modulus E"),
    "nu": ("nu", "plain", "1", "Poisson's ratio nu"),
    "D0": ("D0", "plain", "s-1", "limiting shear strain rate D0"),
    "n": ("n", "plain", "1", "rate sensitivity exponent n"),
    "Z0": ("Z0", "pressure", "Pa", "initial hardness Z0 (3.13)"),
    "Z1": ("Z1", "pressure", "Pa", "saturation hardness Z1 (3.13)"),
    "Z2": ("Z2", "pressure", "Pa", "minimum (recovered) hardness Z2 (3.13)"),
    "Z3": ("Z3", "pressure", "Pa", "directional saturation hardness Z3 (3.14)"),
    "m1": ("m1", "compliance", "Pa-1", "isotropic hardening rate m1 (3.13)"),
    "m2": ("m2", "compliance", "Pa-1", "directional hardening rate m2 (3.14)"),
    "A1": ("A1", "plain", "s-1", "isotropic recovery coefficient A1 (3.13)"),
    "A2": ("A2", "plain", "s-1", "directional recovery coefficient A2 (3.14)"),
    "r1": ("r1", "plain", "1", "isotropic recovery exponent r1 (3.13)"),
    "r2": ("r2", "plain", "1", "directional recovery exponent r2 (3.14)"),
}
DAMAGE_CONSTANTS = {
    "H": ("damage_H", "pressure", "Pa", "damage stress H_hat (rescaled 3.15)"),
    "nu": ("damage_nu", "plain", "1", "damage exponent nu (3.15)"),
    "p": ("damage_p", "plain", "1", "damage exponent p (3.15)"),
    "A": ("damage_A", "plain", "1", "weight A of the largest tensile principal stress (3.15)"),
    "B": ("damage_B", "plain", "1", "weight B of the Mises stress (3.15)"),
    "C": ("damage_C", "plain", "1", "weight C of the tensile first invariant (3.15)"),
    "rate": ("damage_rate", "plain", "s-1", "damage rate p_hat / p (rescaled 3.15)"),
    "omega_rupture": ("omega_rupture", "plain", "1", "damage w at which rupture is declared"),
    "rupture_strain_rate": ("rupture_strain_rate", "plain", "s-1",
                            "inelastic strain rate at which rupture (creep runaway) is declared"),
}


def unit_scale(kind: str, pressure: float) -> float:
    """SI factor of a constant of `kind` given the scene's pressure unit [Pa]."""
    return {"pressure": pressure, "compliance": 1.0 / pressure, "plain": 1.0}[kind]


BP_MECHANISMS = ("isotropic_hardening", "recovery", "directional_hardening")
#: the report's named sets (`BodnerPartom` class methods)
BP_PRESETS = ("b1900_hf_871C", "aluminum_6061_t4", "aluminum_6061_t6", "sae_1020")


def material_si(material: Config, units_cfg: Config) -> dict[str, Any]:
    """The scene's material section in SI (everything a job's key depends on)."""
    p = units.pressure_scale(units_cfg.get("pressure", "Pa"))
    out: dict[str, Any] = {"youngs_modulus": material["youngs_modulus"] * p,
                           "poisson": material["poisson"]}
    if "yield_stress" in material:
        out["yield_stress"] = material["yield_stress"] * p
    model = material.get("model", "elastic")
    if model != "elastic":
        out["model"] = model
    if "hardening_modulus" in material:
        out["hardening_modulus"] = material["hardening_modulus"] * p
    bp = material.get("bodner_partom")
    if bp is not None:  # preset and mechanisms pass as they are
        out["bodner_partom"] = {k: v * unit_scale(CONSTANTS[k][1], p) if k in CONSTANTS else v
                                for k, v in bp.items()}
    dmg = material.get("damage")
    if dmg is not None:
        out["damage"] = {k: v * unit_scale(DAMAGE_CONSTANTS[k][1], p) for k, v in dmg.items()}
    return out


def build(material: Config, effects=()):
    """The `asperity.fe` material of an SI material dict (`material_si`) under `effects`."""
    from asperity.fe.bodner_partom import BodnerPartom
    from asperity.fe.j2 import J2Plasticity
    from asperity.fe.material import LinearElastic

    effects = set(effects)
    E, nu = float(material["youngs_modulus"]), float(material["poisson"])
    yield_stress = float(material.get("yield_stress", math.inf))
    model = material.get("model", "elastic")
    if "plasticity" not in effects or model == "elastic":
        if "plasticity" in effects:
            raise ValueError("effect `plasticity` needs material.model j2 or bodner_partom")
        if "damage" in effects:
            raise ValueError("effect `damage` needs effect `plasticity` with material.model bodner_partom")
        return LinearElastic(E, nu, yield_stress)
    if model == "j2":
        if not math.isfinite(yield_stress):
            raise ValueError("material.model j2 needs material.yield_stress")
        if "damage" in effects:
            raise ValueError("effect `damage` needs material.model bodner_partom (J2 has no damage)")
        return J2Plasticity(E, nu, yield_stress, float(material.get("hardening_modulus", 0.0)))
    if model != "bodner_partom":
        raise ValueError(f"unknown material.model {model!r}")
    bp = dict(material.get("bodner_partom", {}))
    preset = bp.pop("preset", None)
    mechanisms = bp.pop("mechanisms", None)
    constants = {k: float(v) for k, v in bp.items()}
    constants.update(E=E, nu=nu)
    if math.isfinite(yield_stress):
        constants["yield_stress"] = yield_stress
    if mechanisms is not None:
        constants.update({m: m in mechanisms for m in BP_MECHANISMS})
    if preset is None:
        mat = BodnerPartom(**constants)
    elif preset in BP_PRESETS:
        mat = getattr(BodnerPartom, preset)(**constants)
    else:
        raise ValueError(f"unknown Bodner-Partom set {preset!r}; known: {', '.join(BP_PRESETS)}")
    if "damage" in effects:
        dmg = dict(material.get("damage", {}))
        if "H" not in dmg:
            raise ValueError("effect `damage` needs material.damage.H")
        mat = mat.with_damage(**dmg)
    return mat


def rate_independent(material: Config, effects=()) -> bool:
    """The response does not depend on the loading rate (elastic or J2)."""
    return "plasticity" not in set(effects) or material.get("model", "elastic") in ("elastic", "j2")
