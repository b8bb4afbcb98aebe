"""A scene's ``asperity: {edge_band: true}`` (issue #14): the inelastic jobs refine their
one mesh where the plastic contact edge goes, at the preset's size
(`asperity.fe.presets.EDGE_SIZE`); the key changes with it, and elsewhere it is an error.
Without the key a rate-independent body has the band at standard and fine, a
rate-dependent one at fine only (`asperity.population.kinds.inelastic.wants_band`)."""

from __future__ import annotations

import math

import pytest

from asperity.fe.contact.penalty import EDGE_FROM_PRESSURES
from asperity.fe.presets import EDGE_SIZE
from asperity.population import samples as population
from asperity.population.kinds import KINDS, Planning
from asperity.population.plan import interference_grid, sample_key
from asperity.scene import Asperity, Material, Units
from tests.scene_defaults import filled

J2 = Material(model="j2", youngs_modulus=65e9, poisson=0.33, yield_stress=320e6)
ELASTIC = Material(model="elastic", youngs_modulus=65e9, poisson=0.33)
BODNER_PARTOM = Material(model="bodner_partom", youngs_modulus=68.9e9, poisson=0.33,
                         preset="aluminum_6061_t4")


def asperity(**section) -> Asperity:
    return Asperity.from_section(filled("asperity", {"model": "fe", "geometry": "sphere", **section}),
                                 Units("m", "Pa"))


def spec(edge_band: bool | None, accuracy: str = "draft", material: Material = J2) -> dict:
    """The job of a J2 sphere of radius 100 um pressed to 0.3 um (about 25 times its
    critical interference, 0.012 um); edge_band None: the scene does not set it."""
    section = {} if edge_band is None else {"edge_band": edge_band}
    planning = Planning(asperity=asperity(**section), material=material,
                        effects=frozenset({"plasticity"}), accuracy=accuracy, adhesion=None,
                        grid=interference_grid(0.3e-6, 20), family=None, width_to_height=None)
    return KINDS["inelastic"].spec(planning, None, 1e4, math.nan)


@pytest.mark.parametrize("preset", sorted(EDGE_SIZE))
def test_the_band_reaches_the_job_spec_at_the_presets_size_and_changes_its_key(preset):
    band, plain = spec(True, preset), spec(False, preset)
    assert plain["accuracy"] == preset
    assert band["accuracy"] == {"base": preset, "edge_size": EDGE_SIZE[preset]}
    assert {k: v for k, v in band.items() if k != "accuracy"} == \
        {k: v for k, v in plain.items() if k != "accuracy"}
    assert sample_key(band) != sample_key(plain)


@pytest.mark.parametrize("preset", sorted(EDGE_SIZE))
def test_without_the_key_a_j2_body_has_the_band_at_standard_and_fine_a_rate_dependent_one_at_fine(
        preset):
    """J2: the band at standard as with ``edge_band: true``, fine's own (which has it)
    and draft's default mesh with their keys unchanged; Bodner-Partom: the preset as with
    ``false``."""
    j2 = spec(None, preset)
    assert j2["accuracy"] == (spec(True, preset)["accuracy"] if preset == "standard" else preset)
    assert spec(None, preset, BODNER_PARTOM)["accuracy"] == preset
    assert spec(False, preset, BODNER_PARTOM)["accuracy"] == preset


@pytest.mark.parametrize("kind, material, effects", [("elastic", ELASTIC, set()),
                                                     ("adhesive", ELASTIC, {"adhesion"}),
                                                     ("hertz", ELASTIC, set())])
def test_the_band_is_refused_without_plasticity(kind, material, effects):
    with pytest.raises(ValueError, match=r"asperity\.edge_band needs an FE asperity with "
                                         r"effect `plasticity`"):
        KINDS[kind].check(asperity(edge_band=True), material, frozenset(effects))
    KINDS["inelastic"].check(asperity(edge_band=True), J2, frozenset({"plasticity"}))


def test_a_job_with_the_band_runs_on_the_refined_mesh_and_says_so():
    """The job solved from the spec: more dofs than without the band (the surface from
    0.25 to 1.1 intersection radii at 0.04 of it, against the elastic adaptation's
    grading), and the attributes name the preset and the override."""
    band = population.solve(spec(True), "band")
    plain = population.solve(spec(False), "plain")
    assert band.attrs["accuracy"] == plain.attrs["accuracy"] == "draft"
    assert band.attrs["accuracy_overrides"] == "edge_size=0.04"
    assert "accuracy_overrides" not in plain.attrs
    assert int(band["dofs"].max()) > 1.2 * int(plain["dofs"].max())
    # the mesh and the edge locator as they were: the band and its size, the pressures
    assert band.attrs["mesh_strategy"].startswith(plain.attrs["mesh_strategy"])
    assert band.attrs["mesh_strategy"].endswith(
        ", then refined along the surface where the plastic contact edge goes (0.25 to 1.1 "
        "times the intersection radius at the largest interference, to 0.04 of it)")
    assert "refined along" not in plain.attrs["mesh_strategy"]
    assert band.attrs["contact_edge_method"] == plain.attrs["contact_edge_method"] \
        == EDGE_FROM_PRESSURES


def test_a_scene_without_the_key_validates_as_before():
    """The key has no schema default: a scene that does not set it validates to the
    asperity section it had before the key existed, so the plan's params are unchanged
    and an upgrade reruns none of its stages (with a default of false every scene's plan
    and everything after it reran: measured with a run made before the key and a dry run
    after, on smooth_aluminum and greenwood_williamson)."""
    assert "edge_band" not in filled("asperity", {"model": "fe", "geometry": "sphere"})
    assert asperity().edge_band is None
