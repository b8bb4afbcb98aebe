"""The one preset registry (`asperity.fe.presets.resolve(kind, accuracy)`)."""

import pytest

from asperity.fe.presets import (ACCURACY, ADHESIVE_ACCURACY, EDGE_SIZE, INELASTIC_ACCURACY,
                                 KINDS, SLIDING_ACCURACY, resolve)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("name", ["draft", "standard", "fine"])
def test_a_preset_and_its_resolved_dict_resolve_alike(kind, name):
    p = resolve(kind, name)
    assert resolve(kind, p) == p
    assert resolve(kind, dict(base=name)) == p
    p["tolerance"] = -1.0  # a copy: the tables stay as they are
    assert resolve(kind, name)["tolerance"] > 0


def test_the_tables_of_each_kind():
    assert resolve("elastic", "fine") == ACCURACY["fine"]
    # the inelastic histories: the elastic presets, but fine's one mesh adapted to the
    # elastic solutions only as far as standard's (sweeps and target error) and refined
    # where the plastic edge goes
    for name in ("draft", "standard"):
        assert resolve("inelastic", name) == ACCURACY[name]
    adapt = {k: ACCURACY["standard"][k] for k in ("sweeps", "target_error")}
    assert resolve("inelastic", "fine") == {**ACCURACY["fine"], **adapt,
                                            "edge_size": EDGE_SIZE["fine"]}
    assert all(set(p) <= set(ACCURACY[p["base"]]) | {"base"} for p in INELASTIC_ACCURACY.values())
    assert resolve("sliding", "draft") == SLIDING_ACCURACY["draft"]
    # the adhesive keys on top of the elastic preset of the same name
    adh = resolve("adhesive", "draft")
    extra = {k: v for k, v in ADHESIVE_ACCURACY["draft"].items() if k != "base"}
    assert adh == {**ACCURACY["draft"], **extra} and "base" not in adh


def test_overrides_of_a_base():
    p = resolve("adhesive", dict(base="draft", max_iterations=0, min_step=1e-4))
    assert (p["max_iterations"], p["min_step"]) == (0, 1e-4)
    assert p["steps_per_d"] == ADHESIVE_ACCURACY["draft"]["steps_per_d"]
    assert resolve("sliding", dict(normal_steps=1))["tangential_steps"] == \
        SLIDING_ACCURACY["standard"]["tangential_steps"]


def test_unknown_names_keys_and_kinds_are_refused():
    with pytest.raises(ValueError, match="unknown accuracy 'rough'; known: draft, standard, fine"):
        resolve("sliding", "rough")
    with pytest.raises(ValueError,
                       match=r"unknown accuracy keys of the elastic model: \['min_step'\]"):
        resolve("elastic", dict(min_step=1e-3))  # an adhesive key
    with pytest.raises(ValueError, match="unknown accuracy keys of the sliding model"):
        resolve("sliding", dict(base="draft", sweeps=2))
    with pytest.raises(ValueError, match="unknown kind of model 'plastic'"):
        resolve("plastic", "draft")
