"""A body's material in SI (`Material`), and the one builder of the `asperity.fe` body.

Three sections of a scene describe a material (report 3.2: the elastic constants;
3.2.2: J2 plasticity or Bodner-Partom with its hardening, recovery and damage
constants), each parsed where its section is (`from_scene` here for ``material``,
`asperity.scene.uniaxial` for a uniaxial test, `asperity.scene.sliding` for the
sliding asperity); every one becomes a `Material`, and `build` alone turns a
`Material` into the object the finite element solvers and the uniaxial driver use.
Which mechanisms act is decided by the *effects*, not by zero constants:

- without ``plasticity`` the body is linear elastic (its ``yield_stress``, if
  given, only sets the ``elastic`` flag of report 7.3);
- with ``plasticity`` it is the material's ``model`` (``j2``: rate-independent
  J2 with linear hardening; ``bodner_partom``: the unified viscoplastic model
  3.13-3.15, from a named set of the report with any constants overridden, and
  the mechanisms listed, or the set's);
- ``damage`` switches the isotropic damage of Bodner-Partom on (3.15).

Units of a scene: stresses (E, yield stress, hardening modulus, Z0..Z3, H) in its
pressure unit, m1 and m2 in 1/(pressure unit), rates (D0, A1, A2, damage rate) in 1/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Iterable, Mapping

from asperity.scene.checks import SceneError, check_material
from asperity.scene.units import Units, parses

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
#: the damage key that is no constant: how damage softens the hardness (3.15)
SOFTENING = "softening"

BP_MECHANISMS = ("isotropic_hardening", "recovery", "directional_hardening")
#: the report's named sets (`BodnerPartom` class methods)
BP_PRESETS = ("b1900_hf_871C", "aluminum_6061_t4", "aluminum_6061_t6", "sae_1020")
MODELS = ("elastic", "j2", "bodner_partom")


@dataclass(frozen=True)
class NamedMaterial:
    """A material by name, for `asperity new-scene --material NAME`, in SI: E [Pa], nu,
    yield_stress [Pa] (None: a brittle solid, no yield) and where the numbers come from.
    `preset`: the report's Bodner-Partom set (`BP_PRESETS`) whose E and nu it takes."""

    label: str
    youngs_modulus: float
    poisson: float
    yield_stress: float | None
    source: str
    preset: str | None = None


def _preset_elastic(preset: str) -> tuple[float, float]:
    """E [Pa] and nu of one of the report's Bodner-Partom sets (`asperity.fe.materials.bodner_partom`)."""
    from asperity.fe.materials.bodner_partom import BodnerPartom

    body = getattr(BodnerPartom, preset)()
    return float(body.E), float(body.nu)


def named_materials() -> dict[str, NamedMaterial]:
    """The named materials of `asperity new-scene --material`: the report's steel and 6061
    aluminum take E and nu from its sets (8.2.1, 6.3.1); the yield stresses and the other
    materials are handbook values (each entry's `source`)."""
    steel_e, steel_nu = _preset_elastic("sae_1020")
    al_e, al_nu = _preset_elastic("aluminum_6061_t4")
    mpa, gpa = 1e6, 1e9
    return {
        "steel": NamedMaterial(
            "SAE 1020 steel, cold drawn", steel_e, steel_nu, 350 * mpa,
            "E, nu: report 8.2.1 (the sae_1020 set); yield: ASM Handbook vol. 1 (1990), AISI 1020 "
            "cold drawn", "sae_1020"),
        "aluminum": NamedMaterial(
            "aluminum 6061-T6", al_e, al_nu, 276 * mpa,
            "E, nu: report 6.3.1 (the aluminum_6061_t4 set); yield: ASM Handbook vol. 2 (1990), "
            "6061-T6", "aluminum_6061_t4"),
        "copper": NamedMaterial(
            "copper C11000 (ETP), annealed", 115 * gpa, 0.31, 69 * mpa,
            "ASM Handbook vol. 2 (1990), C11000 annealed (O60)"),
        "titanium": NamedMaterial(
            "titanium alloy Ti-6Al-4V, annealed", 114 * gpa, 0.34, 880 * mpa,
            "ASM Handbook vol. 2 (1990), Ti-6Al-4V annealed"),
        "glass": NamedMaterial(
            "soda-lime silicate glass", 70 * gpa, 0.2, None,
            "EN 572-1 (2012), soda-lime silicate glass; brittle: no yield stress"),
    }


def unit_scale(kind: str, pressure: float) -> float:
    """SI factor of a constant of `kind` given the scene's pressure unit [Pa]."""
    return {"pressure": pressure, "compliance": 1.0 / pressure, "plain": 1.0}[kind]


@dataclass(frozen=True)
class Material:
    """A material in SI, as a scene gives it (None: not given).

    model: ``elastic``, ``j2`` or ``bodner_partom`` (the body under the effect
    ``plasticity``); youngs_modulus [Pa] and poisson (None only for a Bodner-Partom
    set that brings its own); yield_stress [Pa]; hardening_modulus [Pa] (J2);
    preset: a Bodner-Partom set of the report; constants: Bodner-Partom constants
    by name (`CONSTANTS`), SI; mechanisms: the Bodner-Partom mechanisms that act
    (None: the set's); damage: damage constants by name (`DAMAGE_CONSTANTS`, and
    ``softening``), SI; name: what the body is called in result files; hardness
    [Pa]: the indentation hardness a scene gives, which only judges the validity of an
    interface (`asperity.homogenize.validity`) and is no part of a job's spec.
    """

    model: str
    youngs_modulus: float | None = None
    poisson: float | None = None
    yield_stress: float | None = None
    hardening_modulus: float | None = None
    preset: str | None = None
    constants: Mapping[str, float] = field(default_factory=dict)
    mechanisms: tuple[str, ...] | None = None
    damage: Mapping[str, Any] = field(default_factory=dict)
    name: str | None = None
    hardness: float | None = None

    def __post_init__(self):
        if self.model not in MODELS:
            raise SceneError("material.model", f"unknown model {self.model!r}", f"known: {', '.join(MODELS)}")

    @classmethod
    @parses("material")
    def from_scene(cls, section: Config, units: Units) -> "Material":
        """A scene's ``material`` section (its pressure unit) in SI."""
        check_material(section, units.pressure)  # sizes that say the unit is wrong
        p = units.pressure_factor
        bp = dict(section.get("bodner_partom") or {})
        return cls(
            model=section["model"],
            youngs_modulus=section["youngs_modulus"] * p,
            poisson=section["poisson"],
            yield_stress=section["yield_stress"] * p if "yield_stress" in section else None,
            hardening_modulus=(section["hardening_modulus"] * p
                               if "hardening_modulus" in section else None),
            preset=bp.pop("preset", None),
            mechanisms=tuple(bp.pop("mechanisms")) if "mechanisms" in bp else None,
            constants={k: v * unit_scale(CONSTANTS[k][1], p) for k, v in bp.items()},
            damage={k: v * unit_scale(DAMAGE_CONSTANTS[k][1], p)
                    for k, v in (section.get("damage") or {}).items()},
            hardness=section["hardness"] * p if "hardness" in section else None,
        )

    def spec(self) -> dict[str, Any]:
        """The material as a sample job's spec holds it (SI; what its key hashes):
        the elastic constants, the yield stress and hardening modulus if given, the
        model unless elastic, the Bodner-Partom set, constants and mechanisms, and the
        damage constants, each only if given."""
        out: dict[str, Any] = {"youngs_modulus": self.youngs_modulus, "poisson": self.poisson}
        if self.yield_stress is not None:
            out["yield_stress"] = self.yield_stress
        if self.model != "elastic":
            out["model"] = self.model
        if self.hardening_modulus is not None:
            out["hardening_modulus"] = self.hardening_modulus
        if self.preset is not None or self.constants or self.mechanisms is not None:
            bp: dict[str, Any] = dict(self.constants)
            if self.preset is not None:
                bp["preset"] = self.preset
            if self.mechanisms is not None:
                bp["mechanisms"] = list(self.mechanisms)
            out["bodner_partom"] = bp
        if self.damage:
            out["damage"] = dict(self.damage)
        return out

    @classmethod
    def from_spec(cls, spec: Config) -> "Material":
        """The material of a sample job's spec (`spec`)."""
        bp = dict(spec.get("bodner_partom") or {})
        return cls(
            model=spec.get("model", "elastic"),  # the spec leaves an elastic model out
            youngs_modulus=spec["youngs_modulus"], poisson=spec["poisson"],
            yield_stress=spec.get("yield_stress"), hardening_modulus=spec.get("hardening_modulus"),
            preset=bp.pop("preset", None),
            mechanisms=tuple(bp.pop("mechanisms")) if "mechanisms" in bp else None,
            constants=bp, damage=dict(spec.get("damage") or {}),
        )

    def rate_independent(self, effects: Iterable[str] = ()) -> bool:
        """The response does not depend on the loading rate (elastic or J2)."""
        return "plasticity" not in set(effects) or self.model in ("elastic", "j2")


def kinematics(effects: Iterable[str]) -> str:
    """The kinematics of an inelastic body under `effects`: ``"finite"`` with the effect
    ``finite_strain`` (`asperity.fe.discretization.kinematics`), else ``"small"`` (the report's theory)."""
    return "finite" if "finite_strain" in set(effects) else "small"


def build(material: Material, effects: Iterable[str] = ()):
    """The `asperity.fe` body of `material` under `effects` (module docstring):
    `LinearElastic`, `J2Plasticity` or `BodnerPartom`."""
    from asperity.fe.materials.bodner_partom import BodnerPartom
    from asperity.fe.materials.j2 import J2Plasticity
    from asperity.fe.materials.elastic import LinearElastic

    effects = set(effects)
    yield_stress = math.inf if material.yield_stress is None else float(material.yield_stress)
    if "plasticity" not in effects or material.model == "elastic":
        if "plasticity" in effects:
            raise ValueError("effect `plasticity` needs material.model j2 or bodner_partom")
        if "damage" in effects:
            raise ValueError("effect `damage` needs effect `plasticity` with material.model bodner_partom")
        return LinearElastic(float(material.youngs_modulus), float(material.poisson), yield_stress)
    if material.model == "j2":
        if not math.isfinite(yield_stress):
            raise ValueError("material.model j2 needs material.yield_stress")
        if "damage" in effects:
            raise ValueError("effect `damage` needs material.model bodner_partom (J2 has no damage)")
        hardening = {} if material.hardening_modulus is None else {"H": float(material.hardening_modulus)}
        return J2Plasticity(float(material.youngs_modulus), float(material.poisson), yield_stress,
                            **hardening)
    constants: dict[str, Any] = {k: float(v) for k, v in material.constants.items()}
    if material.youngs_modulus is not None:
        constants.update(E=float(material.youngs_modulus), nu=float(material.poisson))
    if math.isfinite(yield_stress):
        constants["yield_stress"] = yield_stress
    if material.mechanisms is not None:
        constants.update({m: m in material.mechanisms for m in BP_MECHANISMS})
    if "damage" in effects:
        if "H" not in material.damage:
            raise ValueError("effect `damage` needs material.damage.H (damage_H, the H_hat of 3.15)")
        constants["damage"] = True
    for key, value in material.damage.items():
        constants["damage_softening" if key == SOFTENING else DAMAGE_CONSTANTS[key][0]] = value
    if material.name is not None:
        constants["name"] = material.name
    if material.preset is None:
        return BodnerPartom(**constants)
    if material.preset not in BP_PRESETS:
        raise ValueError(f"unknown Bodner-Partom set {material.preset!r}; known: {', '.join(BP_PRESETS)}")
    return getattr(BodnerPartom, material.preset)(**constants)
