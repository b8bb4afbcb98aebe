"""The plane-strain scene truncated_v (report 6.3.3) run through Snakemake at draft on a
copy of the workflow: its targets, the netCDF contract of its file, its numbers."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.io.netcdf import missing_attributes, read_dataset, scene_config

from .conftest import copy_workflow, planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

SCENE = "truncated_v"
CONFIG = ("--config", f"scenes=[{SCENE}]", "accuracy=draft", "studies=False")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    workdir = copy_workflow(tmp_path_factory.mktemp("plane_strain"))
    snakemake(workdir, *CONFIG)  # rule all: the scene's targets
    return workdir


def test_scene_targets_are_the_plane_strain_file_and_figure(run):
    out = run / "results" / SCENE
    assert (out / "plane_strain.nc").exists() and (out / "figures" / "plane_strain.png").exists()
    assert (out / "figures" / "plane_strain_meshes.png").exists()
    assert (out / "logs" / "plane_strain.log").exists()
    assert not (out / "surface.nc").exists()
    assert planned_jobs(snakemake(run, "-n", *CONFIG)) == {}  # nothing left to do


def test_file_carries_units_scene_and_version(run):
    ds = read_dataset(run / "results" / SCENE / "plane_strain.nc")
    assert missing_attributes(ds) == []
    assert ds.attrs["scene"] == SCENE and ds.attrs["code_version"] == "plane_strain 3"
    config = scene_config(ds)
    assert config["accuracy"] == "draft" and config["plane_strain"]["section"]["shape"] == SCENE
    assert config["material"]["bodner_partom"]["preset"] == "aluminum_6061_t4"
    assert config["plane_strain"]["meshes"] == {"coarse": {"sweeps": 0}, "refined": {}}
    assert list(ds["mesh"].values) == ["coarse", "refined"]
    assert list(ds["body"].values) == ["elastic", "viscoplastic"]
    assert ds["force"].attrs["units"] == "N/m" and ds["interference"].attrs["units"] == "m"
    assert ds.attrs["report"].startswith("6.3.3")


def test_numbers_of_the_run(run):
    """The ridge's top flows (force about a fifth of the elastic one at 30 um, levelled off
    near the test's load per ridge) and its largest nonelastic strain is of the report's
    order (tests/test_plane_strain_study.py says why a factor of two)."""
    ds = read_dataset(run / "results" / SCENE / "plane_strain.nc")
    end = ds.isel(interference=-1)
    ratio = (end["force"].sel(body="viscoplastic") / end["force"].sel(body="elastic")).values
    assert np.all((0.15 < ratio) & (ratio < 0.3)), ratio
    f = end["force"].sel(body="viscoplastic").values
    assert np.all(np.abs(f / ds.attrs["test_load"] - 1) < 0.1), f
    assert np.all((0.4 < ds["largest_inelastic_strain"].values)
                  & (ds["largest_inelastic_strain"].values < 2.0))


def test_the_plane_strain_table_reads_the_run(run):
    """Rule plane_strain_table on this run's scene at draft: nothing computed again, the
    forces and strains of its plane_strain.nc, with units on every variable."""
    study = "plane_strain_table={'scenes': ['truncated_v'], 'presets': ['draft']}"
    jobs = planned_jobs(snakemake(run, "-n", "results/studies/plane_strain_table.nc", "--config",
                                  "accuracy=draft", study))
    assert jobs == {"plane_strain_table": 1}, jobs
    snakemake(run, "results/studies/plane_strain_table.nc", "--config", "accuracy=draft", study)
    ds = read_dataset(run / "results" / "studies" / "plane_strain_table.nc")
    assert missing_attributes(ds) == [] and list(ds["run"].values) == ["truncated_v@draft"]
    source = read_dataset(run / "results" / SCENE / "plane_strain.nc").isel(interference=-1)
    np.testing.assert_array_equal(ds["viscoplastic_force"].isel(run=0), source["force"].sel(body="viscoplastic"))
    np.testing.assert_array_equal(ds["largest_inelastic_strain"].isel(run=0), source["largest_inelastic_strain"])
