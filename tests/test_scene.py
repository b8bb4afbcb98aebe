"""The scene layer (asperity.scene): sections in SI, one material builder, clear errors."""

from __future__ import annotations

import math

import pytest

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.materials.elastic import LinearElastic
from asperity.scene import Asperity, Material, Sliding, UniaxialTest, Units, build
from tests.scene_defaults import filled, filled_scene

UNITS = Units("um", "MPa")


def test_a_missing_key_names_the_section_and_the_key():
    with pytest.raises(ValueError, match=r"scene section `asperity`: no key 'value'"):
        Asperity.from_section({"model": "fe"}, UNITS)
    with pytest.raises(ValueError, match=r"scene section `units`: no key 'pressure'"):
        Units.from_section({"length": "um"})


def test_material_spec_round_trips_and_builds_the_same_body():
    """The spec a job's key hashes holds the material as given, in SI; the job rebuilds
    exactly the scene's body from it."""
    section = filled("material", {"youngs_modulus": 209000.0, "poisson": 0.3, "model": "bodner_partom",
                                  "bodner_partom": {"preset": "sae_1020", "Z0": 600.0, "m1": 0.05,
                                                    "mechanisms": ["isotropic_hardening"]},
                                  "damage": {"H": 2000.0}})
    material = Material.from_scene(section, UNITS)
    assert material.spec() == {"youngs_modulus": 209000.0 * 1e6, "poisson": 0.3, "model": "bodner_partom",
                               "bodner_partom": {"preset": "sae_1020", "Z0": 600.0 * 1e6,
                                                 "m1": 0.05 * (1 / 1e6),
                                                 "mechanisms": ["isotropic_hardening"]},
                               "damage": {"H": 2000.0 * 1e6}}
    assert Material.from_spec(material.spec()) == material
    for effects in ([], ["plasticity"], ["plasticity", "damage"]):
        assert build(Material.from_spec(material.spec()), effects) == build(material, effects)


def test_the_sliding_and_uniaxial_materials_are_the_bodies_their_sections_describe():
    """One builder for the three sections: the sliding asperity's Bodner-Partom body is
    the one its constants give (Z1 = Z0 without hardening), the uniaxial test's the
    report's set with its constants and exactly its mechanisms."""
    sliding = filled_scene({"units": {"length": "um", "pressure": "MPa"}, "sliding": {
        "asperity": {"height": 2.0, "base_diameter": 10.0},
        "material": {"model": "bodner_partom", "youngs_modulus": 209000.0, "poisson": 0.3,
                     "D0": 1e4, "n": 2.28, "Z0": 600.0},
        "motion": {"approach": 0.125, "press_time": [0.0, 1.0], "slide": 1.0, "slide_time": [1.0, 2.0]},
        "shear_resistance": {"c1": 0.5}, "slip_regularization": 0.01}})["sliding"]
    body = Sliding.from_section(sliding, UNITS).body()
    assert body == BodnerPartom(E=209000.0 * 1e6, nu=0.3, D0=1e4, n=2.28, Z0=600.0 * 1e6, Z1=600.0 * 1e6,
                                m1=0.0, isotropic_hardening=False, name="scene material")
    elastic = Sliding.from_section({**sliding, "material": {"model": "elastic", "youngs_modulus": 1.0,
                                                            "poisson": 0.25, "name": "x", "m1": 0.0}},
                                   UNITS).body()
    assert elastic == LinearElastic(1e6, 0.25) and math.isinf(elastic.yield_stress)
    test = filled("uniaxial", {"tests": [{"name": "t", "material": "b1900_hf_871C",
                                          "constants": {"Z0": 2000.0}, "effects": ["recovery"],
                                          "control": "strain",
                                          "history": {"kind": "constant_rate", "rate": 1e-3,
                                                      "value": 0.01}}]})["tests"][0]
    point = UniaxialTest.from_section(test, UNITS).body()
    assert point == BodnerPartom.b1900_hf_871C(Z0=2000.0 * 1e6, isotropic_hardening=False,
                                               recovery=True, directional_hardening=False,
                                               damage=False)


def test_the_sliding_section_mesh_overrides_the_preset_through_the_schema():
    """A scene's ``sliding.mesh`` (every key of `MESH_KEYS`, depth_grading included)
    passes the schema (filled_scene validates) and replaces the preset's value; the
    preset's other keys are kept."""
    from asperity.fe.presets import resolve
    from asperity.scene.sliding import MESH_KEYS

    mesh = {"tip_fraction": 0.3, "refine_fraction": 0.6, "grading": 0.4, "coarse_fraction": 0.3,
            "depth_grading": 0.9}
    assert set(mesh) == set(MESH_KEYS)
    sliding = filled_scene({"units": {"length": "um", "pressure": "MPa"}, "sliding": {
        "asperity": {"height": 2.0, "base_diameter": 10.0},
        "material": {"model": "elastic", "youngs_modulus": 1.0, "poisson": 0.25},
        "motion": {"approach": 0.125, "press_time": [0.0, 1.0], "slide": 1.0, "slide_time": [1.0, 2.0]},
        "shear_resistance": {"c1": 0.5}, "slip_regularization": 0.01, "mesh": mesh}})["sliding"]
    preset = Sliding.from_section(sliding, UNITS).preset("draft")
    assert preset == {**resolve("sliding", "draft"), **mesh}
    with pytest.raises(Exception, match="depth_grading"):
        filled_scene({"units": {"length": "um", "pressure": "MPa"},
                      "sliding": {**sliding, "mesh": {"depth_grading": -1.0}}})


def test_the_sliding_junction_is_the_report_hill_sheared_at_the_steel_shear_strength():
    """`asperity_sliding_junction` is `asperity_sliding` with tau_s = c0 = k (3.21) and
    nothing else changed (the benchmark's ``--shear-strength 280`` runs exactly it), its
    onset ramp no steeper than a friction coefficient of 1, and
    its k is the steel's shear flow stress q / sqrt 3 at the saturated hardness Z1 at
    an inelastic rate between 1e-4 and 1e-2 1/s (Bodner-Partom, report 3.2.2:
    p_dot = 2 / sqrt 3 D0 exp[-1/2 (Z / q)^2n] in uniaxial flow)."""
    import yaml
    from pathlib import Path

    scenes = Path(__file__).resolve().parents[1] / "config" / "scenes"
    report = yaml.safe_load((scenes / "asperity_sliding.yaml").read_text())["sliding"]
    junction = yaml.safe_load((scenes / "asperity_sliding_junction.yaml").read_text())["sliding"]
    law = junction.pop("shear_resistance")
    report.pop("shear_resistance")
    assert junction == report
    assert law["c1"] == 0.0 and law["c2"] == 0.0
    # the onset ramp phi(p / p_o) of 3.25 starts at the slope 2 c0 / p_o: a friction
    # coefficient of 1, as the benchmark's --shear-strength k (onset 2 k)
    assert 2.0 * law["c0"] / law["onset_pressure"] == pytest.approx(1.0)
    m = junction["material"]

    def k(rate):  # MPa
        q = m["Z1"] / (2.0 * math.log(2.0 / math.sqrt(3.0) * m["D0"] / rate)) ** (1 / (2 * m["n"]))
        return q / math.sqrt(3.0)

    assert k(1e-4) < law["c0"] < k(1e-2)
    assert k(1e-4) == pytest.approx(274.0, abs=1.0) and k(1e-2) == pytest.approx(292.0, abs=1.0)


@pytest.mark.slow
def test_the_report_sliding_scene_completes_at_draft():
    """`asperity_sliding` (report 9.2, mu = 20) at draft through its stage, as
    ``snakemake --config 'scenes=[asperity_sliding]' accuracy=draft`` runs it.  With the
    contact on the facets' P2 nodes the junction is past its critical coefficient from
    the start of sliding (6.1), and the steps where touching nodes let go converge after
    cuts.  (With the contact on the vertices, 07f898e to the P2 nodes, its tangent was
    regular at every accepted step, critical factor inf, and at 0.083 um the cut below
    the stall fraction went through the slip; until a8b372c that run failed with a
    ConvergenceError.)  It completes and ends in full slip, F_T = 20 F_N (1e-6) with
    every touching node slipping."""
    import yaml
    from pathlib import Path

    from asperity.stages.sliding import sliding_dataset

    path = Path(__file__).resolve().parents[1] / "config" / "scenes" / "asperity_sliding.yaml"
    scene = filled_scene(yaml.safe_load(path.read_text()))
    ds = sliding_dataset("asperity_sliding", scene["sliding"], scene["units"], "draft")
    assert ds.attrs["completed"] == 1 and ds.attrs["stop_reason"] == ""
    assert ds.attrs["critical_shear_factor"] < 1.0
    last = ds.isel(step=-1)
    assert float(last["slip_fraction"]) == 1.0
    assert float(last["tangential_force"]) == pytest.approx(20 * float(last["normal_force"]),
                                                             rel=1e-6)
