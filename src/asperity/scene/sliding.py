"""One 3-D asperity pressed and slid by a rigid flat (report 9.2): a scene's
``sliding`` section in SI, and the `asperity.fe.drivers.solid3d` objects it describes."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from asperity.scene.materials import Material, build
from asperity.scene.units import Units, parses

Config = Mapping[str, Any]

#: mesh sizes a scene may override (relative to the contact radius estimate)
MESH_KEYS = ("tip_fraction", "refine_fraction", "grading", "coarse_fraction", "depth_grading")


@dataclass(frozen=True)
class Sliding:
    """The cosine hill of report 9.2 (peak-to-valley ``height`` [m], valley-to-valley
    ``base_diameter`` [m]) of ``material``; the flat's motion (``approach`` [m] during
    ``press_time`` [s], then ``slide`` [m] along x during ``slide_time`` [s]); the
    shear resistance tau_s = c0 + c1 sigma_n + c2 sigma_n^2 of 3.21 (c0 [Pa], c1,
    c2 [1/Pa], the c0 ramp ``onset_pressure`` [Pa]) regularized over
    ``slip_regularization`` eps_b [m] (3.25), ``penalty_factor``; and what overrides
    the accuracy preset (``max_inelastic_step``, ``normal_steps``, ``tangential_steps``,
    ``mesh``)."""

    height: float
    base_diameter: float
    material: Material
    approach: float
    press_time: tuple[float, float]
    slide: float
    slide_time: tuple[float, float]
    c0: float
    c1: float
    c2: float
    onset_pressure: float
    slip_regularization: float
    penalty_factor: float
    max_inelastic_step: float | None
    normal_steps: int | None
    tangential_steps: int | None
    mesh: Mapping[str, float]

    @classmethod
    @parses("sliding")
    def from_section(cls, section: Config, units: Units) -> "Sliding":
        length, p = units.length_factor, units.pressure_factor
        a, mo, s = section["asperity"], section["motion"], section["shear_resistance"]
        steps = section.get("steps") or {}
        return cls(
            height=a["height"] * length, base_diameter=a["base_diameter"] * length,
            material=sliding_material(section["material"], units),
            approach=mo["approach"] * length, press_time=tuple(mo["press_time"]),
            slide=mo["slide"] * length, slide_time=tuple(mo["slide_time"]),
            c0=s["c0"] * p, c1=s["c1"], c2=s["c2"] / p, onset_pressure=s["onset_pressure"] * p,
            slip_regularization=section["slip_regularization"] * length,
            penalty_factor=float(section["penalty_factor"]),
            max_inelastic_step=(float(section["max_inelastic_step"])
                                if "max_inelastic_step" in section else None),
            normal_steps=int(steps["normal"]) if "normal" in steps else None,
            tangential_steps=int(steps["tangential"]) if "tangential" in steps else None,
            mesh={k: float(v) for k, v in (section.get("mesh") or {}).items() if k in MESH_KEYS},
        )

    def geometry(self):
        """The `CosineHill`: amplitude height / 2, wavenumber 2 pi / base_diameter."""
        from asperity.fe.discretization.geometry import CosineHill

        return CosineHill(0.5 * self.height, 2.0 * math.pi / self.base_diameter)

    def body(self):
        """The body of `material` (`asperity.scene.materials.build`): inelastic unless
        the section's model is elastic."""
        return build(self.material, () if self.material.model == "elastic" else ("plasticity",))

    def motion(self):
        from asperity.fe.drivers.flat_motion import FlatMotion

        return FlatMotion.press_and_slide(self.approach, self.slide, self.press_time, self.slide_time)

    def friction(self):
        """The `FrictionLaw` (3.21, 3.24, 3.25)."""
        from asperity.fe.contact.sliding import FrictionLaw, ShearResistance

        law = ShearResistance(c0=self.c0, c1=self.c1, c2=self.c2, onset_pressure=self.onset_pressure)
        return FrictionLaw(law, self.slip_regularization)

    def preset(self, accuracy: str) -> dict:
        """The sliding preset `accuracy` (`asperity.fe.presets.resolve("sliding", ...)`) with the
        section's steps, mesh sizes and inelastic step limit instead of the preset's."""
        from asperity.fe.presets import resolve

        preset = resolve("sliding", accuracy)
        if self.normal_steps is not None:
            preset["normal_steps"] = self.normal_steps
        if self.tangential_steps is not None:
            preset["tangential_steps"] = self.tangential_steps
        preset.update(self.mesh)
        if self.max_inelastic_step is not None:
            preset["max_inelastic_step"] = self.max_inelastic_step
        return preset


def sliding_material(section: Config, units: Units) -> Material:
    """The ``sliding.material`` section: Bodner-Partom (3.2.2) with D0, n, Z0, and Z1
    and m1 for isotropic hardening (on where m1 > 0; without Z1 the hardness stays at
    Z0), or elastic."""
    p = units.pressure_factor
    E, nu = float(section["youngs_modulus"]) * p, float(section["poisson"])
    if section["model"] == "elastic":
        return Material(model="elastic", youngs_modulus=E, poisson=nu)
    m1 = float(section["m1"])
    return Material(
        model="bodner_partom", youngs_modulus=E, poisson=nu,
        constants={"D0": float(section["D0"]), "n": float(section["n"]),
                   "Z0": float(section["Z0"]) * p,
                   "Z1": float(section["Z1"] if "Z1" in section else section["Z0"]) * p,
                   "m1": m1 / p},
        mechanisms=("isotropic_hardening",) if m1 > 0 else (), name=section["name"])
