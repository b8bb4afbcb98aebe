"""Nothing changed, nothing runs: after a finished run `snakemake -n` plans no
job and says so (issue #6).  How long it takes (the issue's 5 s) is measured by
`benchmarks/scenes.py` (``nothing_to_do_s``), not asserted here: a wall-time bound
in a test fails on a busy machine (5.27 s once while another job ran), and speed
targets live in benchmarks."""

from __future__ import annotations

import pytest

from .conftest import planned_jobs, run_scenes, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

#: a Hertz FE verification and a Greenwood-Williamson interface (plan checkpoint,
#: asperities, interface, verification, figures), without the accuracy studies
RUN = ("--config", "scenes=[hertz,greenwood_williamson]", "accuracy=draft", "studies=False")


def test_dry_run_after_a_finished_run_plans_nothing(tmp_path_factory):
    """The issue's "Nothing changed: no job, and `snakemake -n` says so": exit
    status 0 (`snakemake` checks it), Snakemake's own "Nothing to be done"
    message, and no job in its job table, with the plan checkpoint re-evaluated
    from plan.nc."""
    run = run_scenes(tmp_path_factory, "nothing_to_do", *RUN)
    proc = snakemake(run, "-n", *RUN)
    text = proc.stdout + proc.stderr
    assert "Nothing to be done" in text, text[-3000:]
    assert planned_jobs(proc) == {}, text[-3000:]
