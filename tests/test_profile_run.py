"""Where a run's time goes (`make bench CASE=profile`): the jobs' profiles and their sums."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

from asperity.io.joblog import PROFILE_ENV, job_log, process_age
from benchmarks import profile_run

FE = ("/x/asperity/fe/solvers/newton.py", 1, "newton")
FIGURE = ("/x/matplotlib/figure.py", 1, "savefig")
NUMPY = ("~", 0, "<method 'reduce' of 'numpy.ufunc' objects>")
HELPER = ("/x/numpy/_core/_methods.py", 1, "_sum")


def edge(ct: float, calls: int = 1) -> tuple:
    """A caller edge of pstats: (primitive calls, calls, own time, cumulative time)."""
    return (calls, calls, 0.0, ct)


def test_shared_time_follows_its_callers_in_proportion_of_their_time():
    # numpy's reduce (2 s own) called through _sum (1 s own): _sum is called by the
    # FE driver for 3 s and by a figure for 1 s of cumulative time, so 3/4 and 1/4
    # (to 1e-9: an edge's weight adds 1e-9 s a call, so that calls of no measured time count)
    stats = {
        FE: (1, 1, 5.0, 8.0, {}),
        FIGURE: (1, 1, 1.0, 2.0, {}),
        HELPER: (2, 2, 1.0, 3.0, {FE: edge(3.0), FIGURE: edge(1.0)}),
        NUMPY: (2, 2, 2.0, 2.0, {HELPER: edge(2.0, 2)}),
    }
    got = profile_run.split_by_concern(stats)
    assert got["finite element drivers, Newton, contact"] == pytest.approx(5.0 + 0.75 * 3.0, rel=1e-9)
    assert got["figures"] == pytest.approx(1.0 + 0.25 * 3.0, rel=1e-9)
    assert sum(got.values()) == pytest.approx(9.0, rel=1e-12)  # every second counted once


def test_recursion_and_top_level_calls_keep_every_second():
    # a shared function that calls itself (own edge) and is called from the FE driver,
    # and one called from the script's top level (no caller): OTHER
    recursive = ("/x/numpy/lib.py", 1, "walk")
    top = ("/x/json/encoder.py", 1, "encode")
    stats = {
        FE: (1, 1, 1.0, 4.0, {}),
        recursive: (5, 1, 3.0, 3.0, {FE: edge(3.0), recursive: edge(2.0, 4)}),
        top: (1, 1, 0.5, 0.5, {}),
    }
    got = profile_run.split_by_concern(stats)
    assert got["finite element drivers, Newton, contact"] == pytest.approx(4.0, rel=1e-6)
    assert got[profile_run.OTHER] == pytest.approx(0.5, rel=1e-6)


@pytest.mark.parametrize("key, concern", [
    (("/v/site-packages/skfem/assembly/form.py", 1, "assemble"), "assembly and meshes"),
    (("~", 0, "<built-in method scipy.sparse.linalg._dsolve._superlu.gstrf>"),
     "factorization and linear solves"),
    (("/v/site-packages/scipy/sparse/linalg/_dsolve/linsolve.py", 1, "splu"),
     "factorization and linear solves"),
    (("/src/asperity/fe/materials/j2.py", 1, "update"), "constitutive updates"),
    (("/v/site-packages/xarray/backends/api.py", 1, "to_netcdf"), "netCDF reading and writing"),
    (("/src/asperity/fe/drivers/march.py", 1, "<module>"), "imports inside the job"),
    (("/v/site-packages/numpy/linalg/_linalg.py", 1, "solve"), None),
])
def test_concern_of_a_function(key, concern):
    assert profile_run.concern_of(key) == concern


def test_rule_of_a_job_log():
    assert profile_run.rule_of("/w/results/steel/logs/interface_figure.log") == "interface_figure"
    assert profile_run.rule_of("/w/results/samples/logs/ab12cd.log") == "sample"
    assert profile_run.rule_of("/w/results/accuracy/logs/hertz.log") == "accuracy_hertz"


def test_summary_counts_idle_cores_as_the_rest_of_wall_time():
    jobs = [{"rule": "sample", "before_job_s": 1.0, "job_s": 4.0,
             "concerns": {"constitutive updates": 3.0, "figures": 0.5}},
            {"rule": "surface", "before_job_s": 0.5, "job_s": 1.0, "concerns": {"figures": 1.0}}]
    s = profile_run.summarize(jobs, wall=5.0, cores=2)
    c = s["by_concern_s"]
    assert c[profile_run.BEFORE] == pytest.approx(1.5)
    assert c["figures"] == pytest.approx(1.5)
    assert c[profile_run.OTHER] == pytest.approx(0.5)  # job time the profile did not see
    assert sum(c.values()) == pytest.approx(10.0)      # wall x cores
    assert c[profile_run.SCHEDULER] == pytest.approx(10.0 - 6.5)
    assert s["by_rule"]["sample"] == {"jobs": 1, "before_job_s": 1.0, "job_s": 4.0}


def test_a_job_under_asperity_profile_leaves_its_profile(tmp_path, monkeypatch):
    monkeypatch.setenv(PROFILE_ENV, str(tmp_path / "profiles"))
    log = tmp_path / "results" / "scene" / "logs" / "surface.log"
    t0 = time.perf_counter()
    with job_log(log, "surface"):
        np.linalg.solve(np.eye(200) * 2.0, np.ones(200))
        time.sleep(0.2)
    took = time.perf_counter() - t0
    jobs = profile_run.read_profiles(tmp_path / "profiles")
    assert len(jobs) == 1
    job = jobs[0]
    assert job["rule"] == "surface" and job["ok"]
    assert 0.2 <= job["job_s"] <= took
    assert 0.0 < job["before_job_s"] < process_age() + 1e-9  # this process began before the job
    assert sum(job["concerns"].values()) <= job["job_s"]


def test_a_failed_job_leaves_its_profile_marked_failed(tmp_path, monkeypatch):
    monkeypatch.setenv(PROFILE_ENV, str(tmp_path))
    with pytest.raises(SystemExit):
        with job_log(tmp_path / "logs" / "plan.log", "plan"):
            raise ValueError("bad input")
    (meta,) = tmp_path.glob("*.json")
    assert json.loads(meta.read_text())["ok"] is False


def test_without_asperity_profile_a_job_writes_no_profile(tmp_path, monkeypatch):
    monkeypatch.delenv(PROFILE_ENV, raising=False)
    monkeypatch.chdir(tmp_path)
    with job_log(tmp_path / "logs" / "plan.log", "plan"):
        pass
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == ["plan.log"]
