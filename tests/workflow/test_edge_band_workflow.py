"""A scene's ``asperity: {edge_band: true}`` through the workflow (issue #14): the J2
spheres of smooth_aluminum at `draft` run on meshes refined where the plastic contact
edge goes, the files say so, and switching it off reruns exactly the FE job and what
gathers it."""

from __future__ import annotations

import pytest
import yaml

from asperity.io.netcdf import read_dataset

from .conftest import REPO, copy_workflow, planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

CONFIG = ("--config", "scenes=[eb_sphere]", "accuracy=draft", "studies=False")
TARGET = "results/eb_sphere/interface.nc"


def test_edge_band_reaches_the_jobs_and_switching_it_reruns_them(tmp_path):
    workdir = copy_workflow(tmp_path)
    scene = yaml.safe_load((REPO / "config" / "scenes" / "smooth_aluminum.yaml").read_text())
    scene.pop("compare_with")
    scene["population"]["samples"] = {"height": 11, "curvature": 3, "interference": 61}
    scene["asperity"]["edge_band"] = True
    path = workdir / "config" / "scenes" / "eb_sphere.yaml"
    path.write_text(yaml.safe_dump(scene))
    snakemake(workdir, TARGET, *CONFIG)

    samples = sorted((workdir / "results" / "samples").glob("*.nc"))
    assert len(samples) == 1  # a self-similar family: one job
    job = read_dataset(samples[0])
    interface = read_dataset(workdir / TARGET)
    for ds in (job, interface):
        assert ds.attrs["accuracy"] == "draft"
        assert ds.attrs["accuracy_overrides"] == "edge_size=0.04"
    assert "'edge_size': 0.04" in job.attrs["accuracy_parameters"]

    scene["asperity"]["edge_band"] = False
    path.write_text(yaml.safe_dump(scene))
    snakemake(workdir, "results/eb_sphere/plan.nc", *CONFIG)
    jobs = planned_jobs(snakemake(workdir, "-n", TARGET, *CONFIG))
    assert jobs == {"sample": 1, "asperities": 1, "interface": 1}, jobs
