"""The plans of the default scenes give the keys and job specs of the recorded run,
byte for byte (tests/data/plan_keys.json.gz, made by tests/data/make_plan_keys.py from a
default run before the asperity kinds moved into a registry).

A key is the hash of a sample job's spec: if a refactoring changed a single byte of a
spec, every finished FE sample of a user's results folder would be computed again.
Each plan is made here the way the workflow makes it: the surface statistics from the
scene's surface section (`asperity.stages.surface`), then `asperity.stages.population.
plan_dataset` with the configuration the recorded plan was made from.

The levels a plan lays out are computed with scalar C-library functions
(`asperity.population.plan.geometric_levels`), the same on every CPU. A plan drawn from a
generated map (map_hertz) inherits the map's statistics, which carry the last bits of
numpy's vectorized exp, log and FFT; those differ between CPUs with and without AVX-512,
and the record was made without. The plans are therefore made in a subprocess whose
numpy dispatches at most AVX2 kernels (NPY_ENABLE_CPU_FEATURES), as the record's machine
did; with that, every key and spec must be the recorded one byte for byte, but for the
deliberate changes since the record (`CHANGES`), each of which reruns the jobs it names.
"""

from __future__ import annotations

import gzip
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from asperity.io.topography import read_measurement
from asperity.io.writers import write_map
from asperity.population.plan import sample_key, spec_json
from asperity.stages import population, surface
from tests.scene_defaults import filled

RECORDED = json.loads(gzip.decompress((Path(__file__).parent / "data" / "plan_keys.json.gz")
                                      .read_bytes()))


def j2_band_at_standard(spec: dict) -> dict:
    """c1255d5: a J2 body's inelastic jobs at standard have the edge band (0.02 of the
    largest intersection radius; `asperity.population.kinds.inelastic.wants_band`)."""
    if (spec.get("material", {}).get("model") == "j2" and "plasticity" in spec["effects"]
            and spec["accuracy"] == "standard"):
        return {**spec, "accuracy": {"base": "standard", "edge_size": 0.02}}
    return spec


#: the deliberate changes of job specs since the record, in order
CHANGES = (j2_band_at_standard,)


def expected(scene: str) -> dict:
    """The recorded keys and specs of `scene` with `CHANGES` applied (a changed spec has
    the key of its canonical JSON, `asperity.population.plan.sample_key`)."""
    new_key, specs = {}, {}
    for key, text in RECORDED[scene]["specs"].items():
        spec = json.loads(text)
        for change in CHANGES:
            spec = change(spec)
        new_key[key] = sample_key(spec) if spec != json.loads(text) else key
        specs[new_key[key]] = spec_json(spec) if new_key[key] != key else text
    return {"keys": [new_key[k] for k in RECORDED[scene]["keys"]], "specs": specs}


def surface_dataset(section: dict, units: dict, tmp_path: Path):
    """surface.nc of a scene whose surface is given statistics or a generated map
    (the surfaces of the scenes with a plan), as workflow/scripts/surface.py makes it."""
    if "map" in section:
        # the scene (map_hertz) now says form: none, a synthetic surface having no form to remove
        section = filled("surface", {**section, "form": "none"})
        path = write_map(tmp_path / "map.npy", surface.synthetic_map(section["map"]["generate"]))
        data = read_measurement(path, **surface.reading(section, units))
        return surface.surface_from_data(data.heights, data.spacing, section, units, defined=data.defined)
    return surface.surface_from_statistics(filled("surface", section), units)


def plans(folder: Path) -> dict:
    """Scene -> keys and specs of the plan made now from its recorded inputs."""
    out = {}
    for scene, record in sorted(RECORDED.items()):
        cfg = record["config"]
        surface_ds = surface_dataset(record["surface"], cfg["units"], folder)
        plan = population.plan_dataset(surface_ds, cfg["population"], cfg["asperity"], cfg["material"],
                                       cfg["effects"], cfg["units"], cfg["accuracy"],
                                       cfg.get("adhesion"))
        keys = [str(k) for k in plan["key"].values]
        out[scene] = {"keys": keys, "specs": {k: str(s) for k, s in zip(keys, plan["spec"].values)}}
    return out


#: numpy's dispatch of x86 kernels up to AVX2 (those of the record's machine)
RECORD_FEATURES = ("SSE", "SSE2", "SSE3", "SSSE3", "SSE41", "POPCNT", "SSE42", "AVX", "F16C", "FMA3", "AVX2")


@pytest.fixture(scope="module")
def made_now(tmp_path_factory):
    from numpy._core._multiarray_umath import __cpu_features__ as cpu

    env = dict(os.environ)
    if cpu.get("AVX512F"):
        env["NPY_ENABLE_CPU_FEATURES"] = " ".join(f for f in RECORD_FEATURES if cpu.get(f))
    folder = tmp_path_factory.mktemp("plan_keys")
    code = ("import json, sys; from pathlib import Path; from tests.test_plan_keys import plans; "
            "json.dump(plans(Path(sys.argv[1])), sys.stdout)")
    root = Path(__file__).resolve().parents[1]
    proc = subprocess.run([sys.executable, "-c", code, str(folder)], cwd=root, env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.mark.parametrize("scene", sorted(RECORDED))
def test_plan_keys_and_specs_are_the_recorded_ones(scene, made_now):
    want = expected(scene)
    assert made_now[scene]["keys"] == want["keys"]
    assert made_now[scene]["specs"] == want["specs"]


def test_the_changes_since_the_record_touch_the_j2_scene_only():
    """Only smooth_aluminum (J2 spheres, one job) changes its key; every other plan keeps
    its keys, so no other finished FE sample reruns."""
    changed = {scene for scene in RECORDED if expected(scene)["keys"] != RECORDED[scene]["keys"]}
    assert changed == {"smooth_aluminum"}
    assert len(set(expected("smooth_aluminum")["keys"])) == 1
