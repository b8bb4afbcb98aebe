"""The uniaxial scene and the Bodner-Partom accuracy study run through snakemake.

One run of the real workflow on a copy, with only the scene
bodner_partom_uniaxial configured, targeting the scene (rule all's scene
targets) and results/accuracy/bodner_partom.nc.
"""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from asperity.io.netcdf import missing_attributes, read_dataset, scene_config

from .conftest import copy_workflow, planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

SCENE = "bodner_partom_uniaxial"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    workdir = copy_workflow(tmp_path_factory.mktemp("uniaxial"))
    snakemake(workdir, f"results/{SCENE}/uniaxial.nc", f"results/{SCENE}/figures/uniaxial.png",
              "results/accuracy/bodner_partom.nc", "--config", f"scenes=[{SCENE}]")
    return workdir


def test_scene_targets_are_the_uniaxial_file_and_figure(run):
    """A scene with a `uniaxial` section targets uniaxial.nc and its figure, nothing else."""
    proc = snakemake(run, "-n", "--config", f"scenes=[{SCENE}]")      # rule all
    jobs = planned_jobs(proc)
    assert not {"uniaxial", "uniaxial_figure", "surface", "accuracy_bodner_partom"} & set(jobs)
    out = run / "results" / SCENE
    assert (out / "uniaxial.nc").exists() and (out / "figures" / "uniaxial.png").exists()
    assert not (out / "surface.nc").exists()
    assert (out / "logs" / "uniaxial.log").exists()


def test_uniaxial_file_carries_units_and_the_scene(run):
    ds = read_dataset(run / "results" / SCENE / "uniaxial.nc")
    assert missing_attributes(ds) == []
    assert ds.attrs["scene"] == SCENE and "uniaxial" in scene_config(ds)
    assert set(ds.dims) == {"test", "step"}
    assert ds.stress.attrs["units"] == "Pa" and ds.time.attrs["units"] == "s"
    assert "b1900_cyclic" in ds["test"].values and ds.sizes["test"] == 9
    # the cyclic test ends back at zero strain after ten cycles of +-0.8 %
    cyc = ds.sel(test="b1900_cyclic")
    n = int(cyc.records)
    assert float(cyc.time[n - 1]) == pytest.approx(3200.0)
    assert abs(float(cyc.strain[n - 1])) < 1e-12
    assert np.nanmax(cyc.strain.values) == pytest.approx(0.008)
    # B1900+Hf at E = 132 GPa (the report's correction), in Pa
    assert float(ds.E.sel(test="b1900_cyclic")) == 132e9
    assert bool(ds.ruptured.sel(test="b1900_creep_damage"))


def test_accuracy_file_pairing_and_units(run):
    """results/accuracy/bodner_partom.nc: dims (integrator, test,
    indicator_tolerance); the issue's pairing within 1 % and at least 20x."""
    ds = read_dataset(run / "results" / "accuracy" / "bodner_partom.nc")
    assert missing_attributes(ds) == []
    assert list(ds["integrator"].values) == ["implicit", "explicit"]
    assert ds.wall_time.attrs["units"] == "s" and ds.steps.attrs["units"] == "1"
    assert "accuracy_bodner_partom" in scene_config(ds)
    assert ds.sizes["test"] == 6
    assert np.all(ds.steps_ratio_reference.values >= 20), ds.steps_ratio_reference.values
    imp = ds.sel(integrator="implicit", indicator_tolerance=ds.attrs["pairing_implicit_tolerance"])
    assert np.all(imp.error.values < ds.attrs["target"])
    # both regimes are in the file: matched accuracy is close on B1900+Hf,
    # far apart on the stiff sets
    matched = ds.steps_ratio_matched
    b1900 = ds["material"].values == "b1900_hf_871C"
    assert np.all(matched.values[b1900] < 10) and np.all(matched.values[~b1900] > 20)
    assert (run / "results" / "accuracy" / "bodner_partom.png").exists()


def test_bad_uniaxial_test_names_file_and_key(workflow_copy):
    """An unknown mechanism in a test stops the run before any job, naming the key."""
    path = workflow_copy / "config" / "scenes" / f"{SCENE}.yaml"
    scene = yaml.safe_load(path.read_text())
    scene["uniaxial"]["tests"][1]["effects"] = ["kinematic_hardening"]
    path.write_text(yaml.safe_dump(scene))
    proc = snakemake(workflow_copy, "-n", "--config", f"scenes=[{SCENE}]", check=False)
    assert proc.returncode != 0
    text = proc.stdout + proc.stderr
    assert f"config/scenes/{SCENE}.yaml: key uniaxial.tests.1.effects.0" in text, text
    assert "is not one of" in text
    assert planned_jobs(proc) == {}
