"""Nothing changed, nothing runs: after a finished run `snakemake -n` plans no
job, says so, and answers within 5 s (issue #6)."""

from __future__ import annotations

import time

import pytest

from .conftest import planned_jobs, run_scenes, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

#: a Hertz FE verification and a Greenwood-Williamson interface (plan checkpoint,
#: asperities, interface, verification, figures), without the accuracy studies
RUN = ("--config", "scenes=[hertz,greenwood_williamson]", "accuracy=draft", "studies=False")
#: the issue's bound on a dry run with nothing to do, s
BOUND = 5.0


def test_dry_run_after_a_finished_run_plans_nothing_within_5_s(tmp_path_factory):
    """A behavioural check of the issue's requirement "Nothing changed: no job,
    and `snakemake -n` says so in under 5 s", not a speed benchmark: the wall
    time is time.perf_counter around the whole `snakemake -n` subprocess
    (interpreter start-up, parsing the Snakefile and the scenes, validation,
    the DAG with the plan checkpoint re-evaluated from plan.nc), measured once
    on the test machine, bound 5 s. Also: exit status 0, Snakemake's own
    "Nothing to be done" message, and no job in its job table."""
    run = run_scenes(tmp_path_factory, "nothing_to_do", *RUN)
    t0 = time.perf_counter()
    proc = snakemake(run, "-n", *RUN)
    elapsed = time.perf_counter() - t0
    text = proc.stdout + proc.stderr
    assert "Nothing to be done" in text, text[-3000:]
    assert planned_jobs(proc) == {}, text[-3000:]
    assert elapsed < BOUND, f"`snakemake -n` with nothing to do took {elapsed:.2f} s (bound {BOUND} s)"
