"""The plans of the default scenes give the keys and job specs of the recorded run,
byte for byte (tests/data/plan_keys.json.gz, made by tests/data/make_plan_keys.py from a
default run before the asperity kinds moved into a registry).

A key is the hash of a sample job's spec: if a refactoring changed a single byte of a
spec, every finished FE sample of a user's results folder would be computed again.
Each plan is made here the way the workflow makes it: the surface statistics from the
scene's surface section (`asperity.stages.surface`), then `asperity.stages.population.
plan_dataset` with the configuration the recorded plan was made from.
"""

from __future__ import annotations

import gzip
import json
from pathlib import Path

import pytest

from asperity.io.topography import read_measurement
from asperity.io.writers import write_map
from asperity.stages import population, surface
from tests.scene_defaults import filled

RECORDED = json.loads(gzip.decompress((Path(__file__).parent / "data" / "plan_keys.json.gz")
                                      .read_bytes()))


def surface_dataset(section: dict, units: dict, tmp_path: Path):
    """surface.nc of a scene whose surface is given statistics or a generated map
    (the surfaces of the scenes with a plan), as workflow/scripts/surface.py makes it."""
    if "map" in section:
        # the scene (map_hertz) now says form: none, a synthetic surface having no form to remove
        section = filled("surface", {**section, "form": "none"})
        path = write_map(tmp_path / "map.npy", surface.synthetic_map(section["map"]["generate"]))
        data = read_measurement(path, **surface.reading(section, units))
        return surface.surface_from_data(data.heights, data.spacing, section, units, defined=data.defined)
    return surface.surface_from_statistics(section, units)


@pytest.mark.parametrize("scene", sorted(RECORDED))
def test_plan_keys_and_specs_are_the_recorded_ones(scene, tmp_path):
    record = RECORDED[scene]
    cfg = record["config"]
    surface_ds = surface_dataset(record["surface"], cfg["units"], tmp_path)
    plan = population.plan_dataset(surface_ds, cfg["population"], cfg["asperity"], cfg["material"],
                                   cfg["effects"], cfg["units"], cfg["accuracy"],
                                   cfg.get("adhesion"))
    keys = [str(k) for k in plan["key"].values]
    assert keys == record["keys"]
    specs = {key: str(spec) for key, spec in zip(keys, plan["spec"].values)}
    assert specs == record["specs"]
