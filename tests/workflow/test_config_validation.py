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
        (lambda s: s.update(validity={"contact_area_ratio": 1.5}), "validity.contact_area_ratio",
         "is greater than the maximum of 1"),
    ],
    ids=["negative-roughness", "unknown-key", "wrong-type", "unknown-unit", "validity-share"],
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


@pytest.mark.parametrize(
    "content, message",
    [
        ("# x z\n0 1\n0.2 2\n0.4 abc\n", "profile.csv:4: column 2: 'abc' is not a number"),
        ("0 1\n0.2 nan\n0.4 3\n", "profile.csv:2: column 2 is nan"),
        ("0 1\n0.2 2\n0.4 1\n0.6 2\n0.8 1\n",
         "data/profile.csv: sampling method with order-8 differences needs at least 10 points"),
    ],
    ids=["non-numeric", "nan", "too-few-points"],
)
def test_bad_profile_file_fails_its_job_and_writes_nothing(workflow_copy, content, message):
    data = workflow_copy / "data"
    data.mkdir(exist_ok=True)
    (data / "profile.csv").write_text(content)

    def change(scene):
        scene["surface"]["profile"] = {"file": "data/profile.csv", "unit": "m"}

    _edit(workflow_copy, "profile_cosine", change)
    proc = snakemake(workflow_copy, "results/profile_cosine/surface.nc", check=False)
    assert proc.returncode != 0
    log = (workflow_copy / "results" / "profile_cosine" / "logs" / "surface.log").read_text()
    assert message in log, log
    assert not (workflow_copy / "results" / "profile_cosine" / "surface.nc").exists()
