"""A scene's material section: SI conversion and the body the effects ask for
(asperity.scene.materials: `Material` and the one builder `build`)."""

from __future__ import annotations

import math

import pytest

from tests.scene_defaults import filled

from asperity.scene import Material, Units, build
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.materials.j2 import J2Plasticity
from asperity.fe.materials.elastic import LinearElastic

UNITS = Units("um", "MPa")


def material_si(section: dict, units: Units):
    """A scene's material section (the schema's defaults filled, as the workflow's
    validation does) in SI."""
    return Material.from_scene(filled("material", section), units)


def test_bodner_partom_constants_convert_by_kind():
    mat = {"youngs_modulus": 209000.0, "poisson": 0.3, "model": "bodner_partom",
           "bodner_partom": {"preset": "sae_1020", "Z0": 600.0, "m1": 0.05, "D0": 1.0e4, "n": 2.28}}
    si = material_si(mat, UNITS)
    bp = si.spec()["bodner_partom"]
    assert si.youngs_modulus == pytest.approx(209e9, rel=1e-15)
    assert bp["Z0"] == pytest.approx(600e6, rel=1e-15)      # stress: x 1e6
    assert bp["m1"] == pytest.approx(0.05e-6, rel=1e-15)    # compliance: / 1e6
    assert bp["D0"] == 1.0e4 and bp["n"] == 2.28            # rate, exponent: as given
    body = build(si, ["plasticity"])
    assert isinstance(body, BodnerPartom)
    # the scene's values equal the report's set of 8.2.1 (BodnerPartom.sae_1020)
    ref = BodnerPartom.sae_1020()
    for name in ("E", "nu", "D0", "n", "Z0", "Z1", "m1"):
        assert getattr(body, name) == pytest.approx(getattr(ref, name), rel=1e-12), name
    assert body.isotropic_hardening and not body.damage


def test_effects_choose_the_body():
    si = material_si({"youngs_modulus": 65000.0, "poisson": 0.33, "model": "j2",
                                "yield_stress": 320.0}, UNITS)
    elastic = build(si, [])
    assert isinstance(elastic, LinearElastic) and elastic.yield_stress == pytest.approx(320e6)
    plastic = build(si, ["plasticity"])
    assert isinstance(plastic, J2Plasticity) and plastic.H == 0.0
    assert si.rate_independent(["plasticity"])
    bp = material_si({"youngs_modulus": 65000.0, "poisson": 0.33, "model": "bodner_partom",
                                "bodner_partom": {"preset": "aluminum_6061_t4"}}, UNITS)
    assert not bp.rate_independent(["plasticity"])
    assert bp.rate_independent([])  # without the effect the body is elastic


def test_mechanisms_and_damage_follow_the_scene():
    si = material_si({"youngs_modulus": 132000.0, "poisson": 0.0805, "model": "bodner_partom",
                                "bodner_partom": {"preset": "b1900_hf_871C", "mechanisms": ["isotropic_hardening"]},
                                "damage": {"H": 2000.0}}, UNITS)
    body = build(si, ["plasticity", "damage"])
    assert body.isotropic_hardening and not body.recovery and not body.directional_hardening
    assert body.damage and body.damage_H == pytest.approx(2e9)
    assert not build(si, ["plasticity"]).damage


@pytest.mark.parametrize("material, effects, message", [
    ({"youngs_modulus": 1.0, "poisson": 0.3}, ["plasticity"], "plasticity"),
    ({"youngs_modulus": 1.0, "poisson": 0.3, "model": "j2"}, ["plasticity"], "yield_stress"),
    ({"youngs_modulus": 1.0, "poisson": 0.3, "model": "j2", "yield_stress": 1e-3}, ["plasticity", "damage"], "damage"),
    ({"youngs_modulus": 1.0, "poisson": 0.3, "model": "bodner_partom", "bodner_partom": {"preset": "sae_1020"}},
     ["plasticity", "damage"], "damage.H"),
])
def test_inconsistent_material_and_effects_are_clear_errors(material, effects, message):
    with pytest.raises(ValueError, match=message):
        build(material_si(material, UNITS), effects)


def test_no_yield_stress_means_never_yields():
    body = build(material_si({"youngs_modulus": 1.0, "poisson": 0.3}, UNITS))
    assert math.isinf(body.yield_stress)
