"""What a run tells the user (asperity.io.run_report): the warnings of its jobs grouped at
the end, a failed job's error in one line, and throttled progress lines of the FE
time-marching drivers, checked with a fake clock."""

from __future__ import annotations

import logging
import math
import os
import re

import pytest

from asperity.io import run_report
from asperity.io.run_report import (StepProgress, failure_lines, logs_since, read_job_log,
                                    warning_summary)

STAMP = "2026-12-06 05:00:00,123"


def _log(root, scene, job, *lines):
    path = root / scene / "logs" / f"{job}.log"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("".join(f"{line}\n" for line in lines))
    return path


# --- the end-of-run summary ---------------------------------------------------------------

def test_warnings_grouped_by_message_with_scene_and_job(tmp_path):
    gauss = "the heights are not Gaussian (skewness 1.2, kurtosis 7.2): use a sampled density"
    a = _log(tmp_path, "map_a", "surface", f"{STAMP} INFO start surface statistics",
             f"{STAMP} WARNING {gauss}", f"{STAMP} WARNING {gauss}",  # twice in one job: once
             f"{STAMP} INFO done surface statistics in 0.1 s")
    b = _log(tmp_path, "map_b", "surface", f"{STAMP} WARNING {gauss}")
    # a captured Python warning: its location dropped, its source line skipped
    c = _log(tmp_path, "samples", "0123456789ab",
             f"{STAMP} WARNING /x/y/asperity/fe/z.py:12: RuntimeWarning: divide by zero",
             "  q = a / b")
    d = _log(tmp_path, "map_c", "interface", f"{STAMP} INFO nothing to say")
    lines = warning_summary([a, b, c, d], "results")
    assert lines == [
        "Warnings of this run: 2 distinct, from 3 jobs "
        "(whole lines in results/<scene>/logs/<job>.log):",
        f"  map_a surface, map_b surface: {gauss}",
        "  sample 0123456789ab: RuntimeWarning: divide by zero",
    ]
    assert warning_summary([d], "results") == []


def test_many_warnings_cut_to_max_lines_with_the_rest_counted(tmp_path):
    logs = [_log(tmp_path, f"s{i}", "surface", f"{STAMP} WARNING message {i}") for i in range(30)]
    logs += [_log(tmp_path, f"t{i}", "plan", f"{STAMP} WARNING message 0") for i in range(5)]
    lines = warning_summary(logs, "out", max_lines=20)
    assert len(lines) == 1 + 20  # heading, 19 messages, the count of the rest
    assert lines[-1] == "and 11 more in out/*/logs"
    # the jobs of one message: three named, then how many more
    first = next(line for line in lines if line.endswith(": message 0"))
    assert first.startswith("  s0 surface, t0 plan, t1 plan and 3 more jobs")


def test_failure_in_one_line_and_logs_of_this_run_only(tmp_path):
    failed = _log(tmp_path, "scene_x", "surface", f"{STAMP} INFO start surface statistics",
                  f"{STAMP} ERROR failed surface statistics: data/p.csv:4: column 2: 'abc' "
                  "is not a number", "Traceback (most recent call last):",
                  '  File "x.py", line 1', "InputError: ...")
    ok = _log(tmp_path, "scene_y", "plan", f"{STAMP} INFO done")
    assert read_job_log(failed).error.startswith("failed surface statistics: data/p.csv:4")
    assert failure_lines([failed, ok]) == [
        "scene_x surface failed: data/p.csv:4: column 2: 'abc' is not a number "
        f"(traceback in {failed})"]
    os.utime(ok, (1000.0, 1000.0))  # written long before the run
    assert logs_since(tmp_path, 2000.0) == [failed]
    assert sorted(logs_since(tmp_path, 0.0)) == sorted([failed, ok])


# --- throttled progress -------------------------------------------------------------------

class FakeClock:
    """Advances `tick` seconds at every read."""

    def __init__(self, tick=1.0):
        self.now, self.tick = 0.0, tick

    def __call__(self):
        self.now += self.tick
        return self.now


def test_progress_lines_at_the_steady_rate_with_time_left_linear(caplog):
    log = logging.getLogger("asperity.test_progress")
    clock = FakeClock(0.5)  # 0.5 s per step
    ticker = StepProgress(log, "run: ", clock=clock)
    with caplog.at_level(logging.INFO, logger=log.name):
        shown = [ticker.update(n, n / 200, f"load {n} N", 3) for n in range(1, 201)]
    steps = [n for n, line in zip(range(1, 201), shown) if line]
    # elapsed at step n is n / 2 s: first line past 5 s (step 11), then every 5 s (10 steps)
    assert steps == list(range(11, 201, 10))
    assert [r.getMessage() for r in caplog.records] == [line for line in shown if line]
    line = shown[50]  # step 51: 25.5 s gone for 51/200: 74.5 s left, 200 steps in all
    assert line == ("run: step 51 of about 200 (26 %), load 51 N, 3 Newton iterations in the "
                    "last step, about 74 s left")


def _progress_lines(monkeypatch, caplog, run):
    """The progress lines of `run()` with a clock that advances 1 s at every read."""
    monkeypatch.setattr(run_report, "CLOCK", FakeClock(1.0))
    with caplog.at_level(logging.INFO, logger="asperity"):
        ds = run()
    lines = [r.getMessage() for r in caplog.records if "Newton iterations in the last" in r.getMessage()]
    return ds, lines


PATTERN = re.compile(r"step (\d+) of (about )?(\d+) \((\d+) %\), (.*), (\d+) Newton iterations in "
                     r"the last step, about (\d+) s left$")


def test_inelastic_history_progress(monkeypatch, caplog):
    from asperity.fe import History, J2Plasticity, Paraboloid, solve_asperity_history

    history = History.load_unload(0.01, 1.0)
    ds, lines = _progress_lines(monkeypatch, caplog, lambda: solve_asperity_history(
        Paraboloid(1.0), J2Plasticity(1000.0, 0.3, 30.0, H=50.0), history, accuracy="draft"))
    n_steps = ds.sizes["step"] - 1
    # one clock read per accepted step: a line at step 6 (6 s > 5 s), then every 5 steps
    got = [PATTERN.search(line) for line in lines]
    assert all(got), lines
    assert [int(m.group(1)) for m in got] == list(range(6, n_steps + 1, 5))
    t = ds["time"].values
    for m in got:
        n = int(m.group(1))
        f = (t[n] - t[0]) / (history.end - t[0])  # the share of the history's time
        assert int(m.group(3)) == max(n, round(n / f))
        assert abs(int(m.group(7)) - n * (1 - f) / f) <= 0.5  # %.0f of elapsed (1 - f) / f
        assert int(m.group(6)) == int(ds["newton_iterations"].values[n])
        w = float(re.search(r"interference (\S+) m", m.group(5)).group(1))
        assert math.isclose(w, float(ds["interference"].values[n]), rel_tol=1e-3)  # %.4g
        assert re.search(r"force \S+ N", m.group(5))


def test_sliding_progress(monkeypatch, caplog):
    from asperity.fe import (FlatMotion, FrictionLaw, LinearElastic, Paraboloid,
                             ShearResistance, solve_sliding)
    from asperity.fe.discretization.half_model_mesh import MeshSpec

    a = math.sqrt(0.005)
    spec = MeshSpec(half_width=8 * a, depth=8 * a, coarse_size=8 * a / 3, tip_size=a,
                    grading=1.0, refine_radius=1.1 * a)
    motion = FlatMotion.press_and_slide(0.005, 0.5 * a, (0.0, 1.0), (1.0, 2.0))
    ds, lines = _progress_lines(monkeypatch, caplog, lambda: solve_sliding(
        Paraboloid(1.0), LinearElastic(1000.0, 0.3), motion,
        FrictionLaw(ShearResistance.coulomb(0.3), 1e-3 * a), accuracy="draft", mesh=spec,
        contact_radius=3 * a))
    got = [PATTERN.search(line) for line in lines]
    assert all(got) and got, lines
    assert [int(m.group(1)) for m in got] == list(range(6, ds.sizes["step"], 5))
    for m in got:
        n = int(m.group(1))
        slide = float(re.search(r"slide (\S+) m", m.group(5)).group(1))
        assert math.isclose(slide, float(ds["tangential_displacement"].values[n]),
                            rel_tol=1e-3, abs_tol=1e-12)  # %.4g of the recorded slide
        assert re.search(r"approach \S+ m", m.group(5))
        assert int(m.group(6)) == int(ds["newton_iterations"].values[n])


def test_adhesive_path_progress(monkeypatch, caplog):
    from asperity.fe import LennardJones, LinearElastic, Paraboloid, solve_asperity_adhesive

    d, radius, nu, mu = 0.3e-9, 15e-6, 0.3, 1.0
    e_star = math.sqrt(radius / d**3) / mu**1.5
    ds, lines = _progress_lines(monkeypatch, caplog, lambda: solve_asperity_adhesive(
        Paraboloid(radius), LinearElastic(e_star * (1 - nu**2), nu), LennardJones(1.0, d),
        w_max=d, accuracy="draft"))
    got = [PATTERN.search(line) for line in lines]
    assert all(got) and got, lines
    total = int(got[0].group(3))
    assert got[0].group(2) is None  # the levels of the path are known: no estimate
    assert total == int(ds["requested"].values.sum()) - 1  # the path's levels after the first
    assert [int(m.group(1)) for m in got] == list(range(6, total + 1, 5))
    for m in got:
        n = int(m.group(1))
        assert int(m.group(7)) == total - n  # elapsed n s x (1 - n/total) / (n/total)
        assert re.search(r"flat at w = \S+ m \((approach|retract)\), force \S+ N", m.group(5))
