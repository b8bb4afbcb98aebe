"""A scene file that starts from another (`like:`, asperity.scene.files)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from asperity.scene.checks import SceneError
from asperity.scene.files import merged, read_scene

SCENES = Path(__file__).resolve().parents[1] / "config" / "scenes"


def _write(folder: Path, name: str, scene: dict) -> Path:
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(scene))
    return path


def test_merged_replaces_values_and_lists_and_merges_mappings():
    base = {"a": 1, "b": {"c": [1, 2], "d": {"e": 3, "f": 4}}, "g": "x"}
    out = merged(base, {"b": {"c": [5], "d": {"f": 6}}, "g": "y", "h": None})
    assert out == {"a": 1, "b": {"c": [5], "d": {"e": 3, "f": 6}}, "g": "y", "h": None}
    assert base["b"]["d"] == {"e": 3, "f": 4}  # the base is left as it was


def test_like_of_a_like(tmp_path):
    _write(tmp_path, "a", {"title": "A", "units": {"length": "um", "pressure": "MPa"},
                           "routes": {"one": {"route": {"kind": "persson"}}}})
    _write(tmp_path, "b", {"like": "a", "units": {"pressure": "GPa"}})
    path = _write(tmp_path, "c", {"like": "b", "title": "C",
                                  "routes": {"two": {"route": {"kind": "interacting"}}}})
    assert read_scene(path) == {
        "like": "b", "title": "C", "units": {"length": "um", "pressure": "GPa"},
        "routes": {"one": {"route": {"kind": "persson"}}, "two": {"route": {"kind": "interacting"}}}}


@pytest.mark.parametrize("scenes, words", [
    ({"a": {"like": "b"}, "b": {"like": "a"}}, "like: a -> b -> a is a circle"),
    ({"a": {"like": "nowhere"}}, "like: no scene file"),
    ({"a": {"like": 3}}, "like: 3 is not the name of a scene"),
], ids=["circle", "missing", "not-a-name"])
def test_like_errors_name_the_file_and_the_key(tmp_path, scenes, words):
    for name, scene in scenes.items():
        _write(tmp_path, name, scene)
    with pytest.raises(SceneError) as err:
        read_scene(tmp_path / "a.yaml")
    assert str(err.value).startswith(f"{tmp_path / 'a.yaml'}: ") and words in str(err.value)


def test_invalid_yaml_names_the_line(tmp_path):
    path = tmp_path / "a.yaml"
    path.write_text("title: A\nunits: {length: um\n")
    with pytest.raises(SceneError, match=rf"^{path}:\d+: \(top level\): not valid YAML"):
        read_scene(path)


def test_the_measured_map_scenes_are_afm_reference_with_their_map():
    """mi_reference and frt_reference differ from afm_reference in the title and the map
    file only: the same routes, scale and separations."""
    base = yaml.safe_load((SCENES / "afm_reference.yaml").read_text())
    for name, file in (("mi_reference", "mi-1.mi"), ("frt_reference", "frt-1.frt")):
        scene = read_scene(SCENES / f"{name}.yaml")
        assert scene["surface"]["map"]["file"] == f"data/topographies/{file}"
        assert file in scene["title"]
        rest = {k: v for k, v in scene.items() if k not in ("like", "title", "surface")}
        assert rest == {k: v for k, v in base.items() if k not in ("title", "surface")}
        assert {k: v for k, v in scene["surface"].items() if k != "map"} == \
            {k: v for k, v in base["surface"].items() if k != "map"}


@pytest.mark.parametrize("text", ["210e9", "210.0e9", "2.e9", "-3e6"])
def test_the_hint_for_a_number_read_as_text_is_read_as_a_number(text):
    """The advice of `text_number_hint` is itself a number to YAML 1.1 (PyYAML), and the
    same number."""
    from asperity.scene.checks import text_number_hint

    assert isinstance(yaml.safe_load(f"a: {text}")["a"], str)
    advice = text_number_hint(text).split("write ")[1].rstrip(")")
    assert yaml.safe_load(f"a: {advice}")["a"] == float(text)
