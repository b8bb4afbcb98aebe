"""Running the real workflow on a copy of the repository's workflow files."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

# one copy helper for the tests and benchmarks/scenes.py, one comparison of results trees
from benchmarks.compare_results import differences, nc_files  # noqa: F401
from benchmarks.workflow_copy import REPO, SNAKEMAKE, copy_workflow  # noqa: F401


def snakemake(workdir: Path, *args: str, check: bool = True,
              env: dict | None = None) -> subprocess.CompletedProcess:
    """`snakemake --cores 2 *args` in `workdir` (`env`: its environment, default ours)."""
    proc = subprocess.run(
        [str(SNAKEMAKE), "--cores", "2", *args],
        cwd=workdir, capture_output=True, text=True, timeout=900, env=env,
    )
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{proc.stdout}\n{proc.stderr}")
    return proc


def planned_jobs(proc: subprocess.CompletedProcess) -> dict[str, int]:
    """Rule -> count from the 'Job stats' table of a dry run ({} if nothing to do)."""
    text = proc.stdout + proc.stderr
    if "Job stats:" not in text:
        return {}
    table = text.split("Job stats:", 1)[1]
    jobs = {}
    for line in table.splitlines()[3:]:
        m = re.match(r"^(\w+)\s+(\d+)$", line.strip())
        if not m:
            break
        if m.group(1) != "total":
            jobs[m.group(1)] = int(m.group(2))
    return jobs


@pytest.fixture
def workflow_copy(tmp_path):
    return copy_workflow(tmp_path)


def run_scenes(tmp_path_factory, name: str, *args: str) -> Path:
    """A workflow copy with `args` (e.g. --config scenes=[...]) run to completion."""
    workdir = copy_workflow(tmp_path_factory.mktemp(name))
    snakemake(workdir, *args)
    return workdir


def result(run: Path, scene: str, name: str):
    """A result file of a run, read through the netCDF contract."""
    from asperity.io.netcdf import read_dataset

    return read_dataset(run / "results" / scene / name)


def assert_same_results(got: Path, reference: Path, names: list[str], rtol: float = 1e-12) -> int:
    """Every file of `names` holds the same variables, dimensions, attributes and values
    (floats to `rtol` relative) in both trees, timings and the write date aside
    (`benchmarks.compare_results.differences`); returns the number of values compared."""
    compared = 0
    for name in names:
        data, attrs, count = differences(got / name, reference / name, rtol, attributes=True)
        assert not data and not attrs, (name, data, attrs)
        compared += count
    return compared
