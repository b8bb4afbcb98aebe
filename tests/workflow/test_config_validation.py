"""A bad scene stops the run before any job starts, naming the scene file and the key."""

from __future__ import annotations

import pytest
import yaml

from .conftest import planned_jobs, snakemake

pytestmark = pytest.mark.workflow


def _edit(workdir, scene, change):
    path = workdir / "config" / "scenes" / f"{scene}.yaml"
    data = yaml.safe_load(path.read_text())
    change(data)
    path.write_text(yaml.safe_dump(data))
    return path


@pytest.mark.parametrize(
    "change, key, words",
    [
        (lambda s: s["surface"]["statistics"].update(sigma=-1.0), "surface.statistics.sigma",
         "less than or equal to the minimum"),
        (lambda s: s["homogenization"].update(colls=[3, 3]), "homogenization",
         "'colls' was unexpected"),
        (lambda s: s["homogenization"].update(cells="twenty"), "homogenization.cells",
         "is not of type 'array'"),
        (lambda s: s["units"].update(length="furlong"), "units.length", "is not one of"),
    ],
    ids=["negative-roughness", "unknown-key", "wrong-type", "unknown-unit"],
)
def test_bad_scene_names_file_and_key(workflow_copy, change, key, words):
    path = _edit(workflow_copy, "expectation_unit", change)
    proc = snakemake(workflow_copy, "-n", check=False)
    assert proc.returncode != 0
    text = proc.stdout + proc.stderr
    assert f"{path.relative_to(workflow_copy)}: key {key}" in text, text
    assert words in text
    assert planned_jobs(proc) == {}
    assert not (workflow_copy / "results").exists()


def test_missing_profile_file(workflow_copy):
    def change(scene):
        scene["surface"]["profile"] = {"file": "data/no_such_profile.txt", "spacing": 0.1}

    path = _edit(workflow_copy, "profile_cosine", change)
    proc = snakemake(workflow_copy, "-n", check=False)
    assert proc.returncode != 0
    text = proc.stdout + proc.stderr
    assert f"{path.relative_to(workflow_copy)}: key surface.profile.file: no such file" in text, text
