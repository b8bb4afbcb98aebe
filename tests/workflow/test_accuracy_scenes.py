"""The scene accuracy study (issue #6) is a named target, not part of `rule all`."""

from __future__ import annotations

import pytest
import yaml

from .conftest import planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]


def test_accuracy_scenes_target_runs_every_scene_at_every_preset(workflow_copy):
    config = yaml.safe_load((workflow_copy / "config" / "config.yaml").read_text())
    study = config["accuracy_scenes"]
    proc = snakemake(workflow_copy, "-n", "accuracy_scenes")
    jobs = planned_jobs(proc)
    assert jobs["accuracy_scenes"] == 1
    # steel_glass_bead, rough_aluminum and smooth_aluminum at draft, standard and fine, and
    # the variant with the edge band at draft and standard (compared with the scene at fine)
    assert study["variants"] == {"steel_glass_bead_edge_band": "steel_glass_bead"}
    assert jobs["interface"] == len(study["scenes"]) * len(study["presets"]) + 2 == 11
    def folder(name, preset):  # the run's own preset is the scene's own folder: not computed twice
        return f"results/{name}" if preset == config["accuracy"] else f"results/{name}@{preset}"

    assert config["accuracy"] in study["presets"]
    for name in study["scenes"]:
        for preset in study["presets"]:
            assert f"{folder(name, preset)}/interface.nc" in proc.stdout, (name, preset)
        assert f"results/{name}@{config['accuracy']}/" not in proc.stdout
    for preset in ("draft", "standard"):
        assert f"{folder('steel_glass_bead_edge_band', preset)}/interface.nc" in proc.stdout
    assert "results/steel_glass_bead_edge_band@fine/" not in proc.stdout
    # the default run leaves it out (it costs the fine runs)
    assert "accuracy_scenes" not in planned_jobs(snakemake(workflow_copy, "-n"))


def test_bad_preset_is_refused(workflow_copy):
    path = workflow_copy / "config" / "config.yaml"
    config = yaml.safe_load(path.read_text())
    config["accuracy_scenes"]["presets"] = ["draft", "coarse"]
    path.write_text(yaml.safe_dump(config))
    proc = snakemake(workflow_copy, "-n", "accuracy_scenes", check=False)
    assert proc.returncode != 0
    assert "config/config.yaml: key accuracy_scenes.presets.1: 'coarse' is not one of" in proc.stdout + proc.stderr
