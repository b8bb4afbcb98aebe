"""Uniaxial material-point tests (report 5, 6.3.1, 8.2.1): a scene's ``uniaxial``
section, and the tests of the Bodner-Partom accuracy study, in SI.

A test names a constant set of the report (``material``), overrides any constant
in the scene's units (``constants``; damage constants under ``damage``), lists the
mechanisms that are on (``effects``: isotropic_hardening, recovery,
directional_hardening, damage; every other one is switched off by `BodnerPartom`
flags, never by a zero constant), the ``control`` (strain or stress), the
``history`` and the integrator. Units: stresses, moduli, hardnesses and H_hat in the
scene's pressure unit, m1 and m2 in 1 / (pressure unit), rates in 1/s, times in s,
strains dimensionless.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from asperity.scene.materials import (BP_MECHANISMS, BP_PRESETS, CONSTANTS, DAMAGE_CONSTANTS,
                                      SOFTENING, Material, build, unit_scale)
from asperity.scene.units import Units, parses

Config = Mapping[str, Any]

#: mechanisms a test switches on by name (flags of `BodnerPartom`)
EFFECTS = BP_MECHANISMS + ("damage",)
#: what a figure panel plots: plot name -> (x, y)
PLOTS = {
    "strain-stress": ("strain", "stress"),
    "time-stress": ("time", "stress"),
    "time-strain": ("time", "strain"),
    "time-damage": ("time", "damage"),
    "time-hardness": ("time", "hardness"),
}


@dataclass(frozen=True)
class UniaxialTest:
    """One test: its name and title; material (a Bodner-Partom `Material`, the set
    ``preset`` with the test's constants and exactly its mechanisms) and effects;
    control (``strain`` or ``stress``); the history as (time [s], value) points from
    rest, values strains or stresses [Pa], and its kind, rate [1/s] and value as the
    scene wrote them; integrator, tolerance, outputs; the figure panel and plot."""

    name: str
    title: str
    preset: str
    material: Material
    effects: tuple[str, ...]
    control: str
    history: tuple[tuple[float, float], ...]
    history_kind: str
    rate: float | None
    value: float | None
    integrator: str
    tolerance: float
    outputs: int
    panel: str
    plot: str

    @classmethod
    @parses("uniaxial")
    def from_section(cls, test: Config, units: Units) -> "UniaxialTest":
        name = test["name"]
        control = test["control"]
        if control not in ("strain", "stress"):
            raise ValueError(f"test {name}: control is 'strain' or 'stress'")
        h = test["history"]
        return cls(
            name=name, title=test.get("title", name), preset=test["material"],
            material=test_material(test, units), effects=tuple(test["effects"]),
            control=control, history=tuple(history_points(test, units)),
            history_kind=h["kind"], rate=h.get("rate"), value=h.get("value"),
            integrator=test["integrator"], tolerance=float(test["tolerance"]),
            outputs=int(test["outputs"]), panel=test.get("panel", name),
            plot=test.get("plot", "strain-stress" if control == "strain" else "time-strain"),
        )

    def body(self):
        """The `BodnerPartom` material point of the test (`asperity.scene.materials.build`)."""
        effects = {"plasticity"} | ({"damage"} if "damage" in self.effects else set())
        try:
            return build(self.material, effects)
        except ValueError as err:
            raise ValueError(f"test {self.name}: {err}") from None


def tests(section: Config, units: Units) -> list[UniaxialTest]:
    """The tests of a ``uniaxial`` section (or of the accuracy study's ``tests``)."""
    return [UniaxialTest.from_section(t, units) for t in section]


def test_material(test: Config, units: Units) -> Material:
    """The material of one test: the set ``test["material"]``, its constants
    overridden by ``test["constants"]`` and ``test["damage"]`` (scene units), and
    exactly the mechanisms of ``test["effects"]`` switched on. An unknown set,
    effect or constant raises ValueError naming the test."""
    name = test["name"]
    preset = test["material"]
    if preset not in BP_PRESETS:
        raise ValueError(f"test {name}: unknown material {preset!r}; known: {', '.join(BP_PRESETS)}")
    effects = list(test["effects"])
    unknown = sorted(set(effects) - set(EFFECTS))
    if unknown:
        raise ValueError(f"test {name}: unknown effects {unknown}; known: {', '.join(EFFECTS)}")
    p = units.pressure_factor
    constants = {}
    for key, value in (test.get("constants") or {}).items():
        if key not in CONSTANTS:
            raise ValueError(f"test {name}: unknown constant {key!r}; known: {', '.join(CONSTANTS)}")
        constants[CONSTANTS[key][0]] = float(value) * unit_scale(CONSTANTS[key][1], p)
    damage = {}
    for key, value in (test.get("damage") or {}).items():
        if key == SOFTENING:
            damage[key] = str(value)
            continue
        if key not in DAMAGE_CONSTANTS:
            raise ValueError(f"test {name}: unknown damage constant {key!r}; "
                             f"known: {', '.join(DAMAGE_CONSTANTS)}, {SOFTENING}")
        damage[key] = float(value) * unit_scale(DAMAGE_CONSTANTS[key][1], p)
    return Material(model="bodner_partom", preset=preset, constants=constants,
                    mechanisms=tuple(m for m in effects if m in BP_MECHANISMS), damage=damage)


def history_points(test: Config, units: Units) -> list[tuple[float, float]]:
    """``[(time [s], value), ...]`` of one test from rest, value in SI.

    History kinds (values are strains under strain control, stresses in the
    scene's pressure unit under stress control; rates per second):

    - ``ramp_hold``: ``value`` reached linearly in ``ramp_time``, then held
      for ``hold_time`` (creep 5.1, relaxation 5.3, load-creep 5.4);
    - ``constant_rate``: to ``value`` at ``rate`` (tension 6.14, 8.13),
      then held for ``hold_time``;
    - ``cyclic``: ``cycles`` triangles 0 -> +amplitude -> -amplitude -> 0 at
      ``rate`` (5.2);
    - ``points``: the (time, value) pairs given, from (0, 0).
    """
    h = test["history"]
    scale = units.pressure_factor if test["control"] == "stress" else 1.0
    kind = h["kind"]
    if kind == "ramp_hold":
        v = float(h["value"]) * scale
        pts = [(0.0, 0.0), (float(h["ramp_time"]), v)]
        if float(h["hold_time"]) > 0:
            pts.append((pts[-1][0] + float(h["hold_time"]), v))
    elif kind == "constant_rate":
        v = float(h["value"]) * scale
        pts = [(0.0, 0.0), (abs(float(h["value"]) / float(h["rate"])), v)]
        if float(h["hold_time"]) > 0:
            pts.append((pts[-1][0] + float(h["hold_time"]), v))
    elif kind == "cyclic":
        a = float(h["amplitude"]) * scale
        quarter = float(h["amplitude"]) / float(h["rate"])
        pts = [(0.0, 0.0)]
        for i in range(int(h["cycles"])):
            t = 4.0 * quarter * i
            pts += [(t + quarter, a), (t + 3 * quarter, -a), (t + 4 * quarter, 0.0)]
    elif kind == "points":
        pts = [(float(t), float(v) * scale) for t, v in h["points"]]
        if pts[0] != (0.0, 0.0):
            pts.insert(0, (0.0, 0.0))
    else:
        raise ValueError(f"test {test['name']}: unknown history kind {kind!r}")
    return pts


@dataclass(frozen=True)
class IntegratorStudy:
    """Implicit against explicit integration of the Bodner-Partom material point
    (config/config.yaml: ``accuracy_bodner_partom``): the tests; the tolerance sweep
    of each integrator (``implicit``, ``explicit``) and the pairing compared; the
    relative end error counted as the same answer (``target``); the outputs of each
    integrator; the ODE reference's rtol and method."""

    tests: tuple[UniaxialTest, ...]
    tolerances: Mapping[str, tuple[float, ...]]
    pairing: Mapping[str, float]
    target: float
    implicit_outputs: int
    explicit_outputs: int
    reference_rtol: float
    reference_method: str

    @classmethod
    @parses("accuracy_bodner_partom")
    def from_section(cls, section: Config) -> "IntegratorStudy":
        if not section.get("tests"):
            raise ValueError("config/config.yaml: key accuracy_bodner_partom.tests: no tests given")
        units = Units.from_section(section["units"])
        return cls(
            tests=tuple(tests(section["tests"], units)),
            tolerances={k: tuple(v) for k, v in section["tolerances"].items()},
            pairing=dict(section["pairing"]), target=section["target"],
            implicit_outputs=section["implicit_outputs"], explicit_outputs=section["explicit_outputs"],
            reference_rtol=section["reference"]["rtol"], reference_method=section["reference"]["method"])
