"""The plans of the default scenes give the keys and job specs of the recorded run,
byte for byte (tests/data/plan_keys.json.gz, made by tests/data/make_plan_keys.py from a
default run before the asperity kinds moved into a registry).

A key is the hash of a sample job's spec: if a refactoring changed a single byte of a
spec, every finished FE sample of a user's results folder would be computed again.
Each plan is made here the way the workflow makes it: the surface statistics from the
scene's surface section (`asperity.stages.surface`), then `asperity.stages.population.
plan_dataset` with the configuration the recorded plan was made from. The levels a plan
lays out are computed with scalar C-library functions, so they are the same on every
CPU; a plan drawn from a generated map's statistics agrees to rounding only.
"""

from __future__ import annotations

import gzip
import json
from pathlib import Path

import numpy as np
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
    specs = {key: str(spec) for key, spec in zip(keys, plan["spec"].values)}
    if "map" not in record["surface"]:
        assert keys == record["keys"]
        assert specs == record["specs"]
        return
    # A plan drawn from a generated map inherits the map's statistics, and those carry
    # the last bits of numpy's vectorized exp, log and FFT, which differ between CPUs
    # with and without AVX-512: the specs agree to rounding, their hashes need not.
    recorded = [json.loads(record["specs"][k]) for k in record["keys"]]
    made = [json.loads(specs[k]) for k in keys]
    assert len(made) == len(recorded)
    for new, old in zip(made, recorded):
        assert new.keys() == old.keys()
        for name in new:
            if isinstance(old[name], (float, list)):
                np.testing.assert_allclose(new[name], old[name], rtol=1e-12, atol=0, err_msg=name)
            else:
                assert new[name] == old[name], name
    assert len(set(keys)) == len(set(record["keys"]))
