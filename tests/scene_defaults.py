"""Scene sections with the defaults of config/schema.yaml filled in, as the workflow's
validation (snakemake.utils.validate) fills them before a rule sees a section: the
library's scene layer (`asperity.scene`) has no defaults of its own."""

from __future__ import annotations

import copy
from pathlib import Path

from snakemake.utils import validate

SCHEMA = Path(__file__).resolve().parents[1] / "config" / "schema.yaml"


def filled_scene(scene: dict) -> dict:
    """A copy of `scene` (a scene file's content) validated, with every default filled;
    title, report and units are added where the scene lacks them."""
    scene = {"title": "test", "report": "-", "units": {"length": "m"}, **copy.deepcopy(scene)}
    config = {"scenes": ["test"], "accuracy": "standard", "results": "results",
              "scene_dir": "config/scenes", "scene_definitions": {"test": scene}}
    validate(config, str(SCHEMA))
    return copy.deepcopy(config["scene_definitions"]["test"])


def filled(section: str, value) -> dict:
    """One section of a scene, validated, with the schema's defaults."""
    return filled_scene({section: value})[section]


def filled_config(section: str, value) -> dict:
    """A section of config/config.yaml (e.g. ``accuracy_bodner_partom``), with its defaults."""
    config = {"scenes": ["test"], "accuracy": "standard", "results": "results",
              "scene_dir": "config/scenes", section: copy.deepcopy(value)}
    validate(config, str(SCHEMA))
    return copy.deepcopy(config[section])
