"""The first hour of a user: what the console says at the end of a run, any scene file
runnable by its target, and a target the scene does not make refused in one line.

- The warnings of the jobs of a run are summed up on the console where the run ends
  (the Snakefile's onsuccess/onerror, asperity.io.run_report), naming scene and job: a
  measured AFM map (di-3.di, skewness -0.40, kurtosis 5.66) is not Gaussian.
- A scene file of config/scenes/ runs by its target without being listed in
  config/config.yaml (whose `scenes` only choose what `rule all` runs).
- A target the scene does not make fails before any job, in one line naming the scene
  file and the key that would make it; a job that fails is told in one line at the end
  of the run with the file and key of its error, the traceback left in its log.
"""

from __future__ import annotations

import pytest
import yaml

from .conftest import planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

#: a measured map with Hertz asperities on its own peaks: seconds at draft
MAP_SCENE = {
    "title": "Peaks of the measured AFM map di-3.di, Hertz asperities",
    "report": "2.4.3, 2.5.3",
    "units": {"length": "um", "pressure": "MPa"},
    "surface": {"form": "tilt", "map": {"file": "data/topographies/di-3.di"}},
    "population": {"density": "sampled", "histogram_bins": [20, 20],
                   "samples": {"height": 11, "curvature": 21, "interference": 241}},
    "asperity": {"model": "hertz"},
    "material": {"youngs_modulus": 70000.0, "poisson": 0.33},
    "homogenization": {"rule": "peaks",
                       "separations": {"start": 0.0, "stop": 3.0, "count": 31, "unit": "sigma"}},
}
SCENE = "first_hour_map"
SMALL = ("--config", "accuracy=draft", "studies=False")


def _summary(text: str) -> list[str]:
    """The lines of the end-of-run warning summary (heading included)."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("Warnings of this run"))
    end = start + 1
    while end < len(lines) and (lines[end].startswith("  ") or lines[end].startswith("and ")):
        end += 1
    return lines[start:end]


def test_unlisted_scene_runs_by_target_and_its_warnings_end_the_run(workflow_copy):
    listed = yaml.safe_load((workflow_copy / "config" / "config.yaml").read_text())["scenes"]
    assert SCENE not in listed
    (workflow_copy / "config" / "scenes" / f"{SCENE}.yaml").write_text(yaml.safe_dump(MAP_SCENE))
    proc = snakemake(workflow_copy, f"results/{SCENE}/interface.nc", *SMALL)
    assert (workflow_copy / "results" / SCENE / "interface.nc").exists()
    text = proc.stdout + proc.stderr
    summary = _summary(text)
    # after the last job, at most ~20 lines, the map's non-Gaussian heights named with
    # the scene and the job that found them
    assert text.index(summary[0]) > text.rindex("steps (100%) done")
    assert len(summary) <= 21, summary
    gauss = [line for line in summary if "the heights are not Gaussian" in line]
    assert len(gauss) == 1 and gauss[0].startswith(f"  {SCENE} surface: "), summary
    assert "skewness -0.4" in gauss[0] and "kurtosis 5.66" in gauss[0]
    # the same warning is in the job's log
    log = (workflow_copy / "results" / SCENE / "logs" / "surface.log").read_text()
    assert "WARNING the heights are not Gaussian" in log
    # a run with nothing to do ran no job: no warnings of earlier runs repeated
    again = snakemake(workflow_copy, f"results/{SCENE}/interface.nc", *SMALL)
    assert "Nothing to be done" in again.stdout + again.stderr
    assert "Warnings of this run" not in again.stdout + again.stderr


def test_unlisted_reference_scene_plans_its_routes_by_target(workflow_copy):
    """afm_reference (not in config.yaml): its routes load with it, each a scene."""
    listed = yaml.safe_load((workflow_copy / "config" / "config.yaml").read_text())["scenes"]
    assert "afm_reference" not in listed
    scene = yaml.safe_load((workflow_copy / "config" / "scenes" / "afm_reference.yaml").read_text())
    proc = snakemake(workflow_copy, "-n", "results/afm_reference/comparison.nc", *SMALL)
    jobs = planned_jobs(proc)
    assert jobs["reference_comparison"] == 1 and jobs["reference"] == 1
    for route in scene["routes"]:  # each route's interface law, planned as a scene
        assert f"results/afm_reference+{route}/interface.nc" in proc.stdout, route


@pytest.mark.parametrize("target, message", [
    ("results/greenwood_williamson/unloading.nc",
     "results/greenwood_williamson/unloading.nc: scene config/scenes/greenwood_williamson.yaml "
     "does not unload (add `effects: [unloading]`, or `unloading` to its `effects:` list)"),
    ("results/greenwood_williamson/figures/unloading.png",
     "results/greenwood_williamson/figures/unloading.png: scene "
     "config/scenes/greenwood_williamson.yaml does not unload"),
    ("results/map_hertz/friction.nc",
     "results/map_hertz/friction.nc: scene config/scenes/map_hertz.yaml has no `friction:` "
     "section"),
    ("results/hertz/asperities.nc",
     "results/hertz/asperities.nc: scene config/scenes/hertz.yaml has no asperity population "
     "(key `asperity.model`: hertz or fe)"),
    ("results/no_such_scene/interface.nc",
     "results/no_such_scene/interface.nc: no scene file config/scenes/no_such_scene.yaml"),
], ids=["unloading", "unloading-figure", "friction", "no-population", "no-scene-file"])
def test_target_the_scene_does_not_make_fails_in_one_line(workflow_copy, target, message):
    proc = snakemake(workflow_copy, target, *SMALL, check=False)
    assert proc.returncode != 0
    text = proc.stdout + proc.stderr
    assert message in text, text[-3000:]
    assert "KeyError" not in text
    assert not (workflow_copy / "results").exists()  # no job ran


def test_failed_job_told_in_one_line_at_the_end(workflow_copy):
    data = workflow_copy / "data"
    (data / "profile.csv").write_text("# x z\n0 1\n0.2 2\n0.4 abc\n")
    path = workflow_copy / "config" / "scenes" / "profile_cosine.yaml"
    scene = yaml.safe_load(path.read_text())
    scene["surface"]["profile"] = {"file": "data/profile.csv", "unit": "m"}
    path.write_text(yaml.safe_dump(scene))
    proc = snakemake(workflow_copy, "results/profile_cosine/surface.nc", check=False)
    assert proc.returncode != 0
    text = proc.stdout + proc.stderr
    line = ("profile_cosine surface failed: data/profile.csv:4: column 2: 'abc' is not a number "
            "(traceback in results/profile_cosine/logs/surface.log)")
    assert line in text, text[-3000:]
    # where the run ends, after anything the job printed; no traceback on the console (the
    # job itself prints one line and exits), it stays in the job's log
    assert text.index(line) > text.rfind("Error in rule surface")
    assert "Traceback" not in text
    assert ("error: surface statistics: data/profile.csv:4: column 2: 'abc' is not a number "
            "(traceback in results/profile_cosine/logs/surface.log)") in text
    assert "Traceback" in (workflow_copy / "results" / "profile_cosine" / "logs" /
                           "surface.log").read_text()
