"""What each Snakemake job pays before it computes anything (`make bench CASE=jobs`).

The README explains why the draft run misses its 2-minute target by what
the 188 jobs of the default run cost as processes.  This script measures
the two parts of that cost on this machine:

1. Snakemake's own cost of a `script:` job: a workflow of N jobs whose
   script only writes its output, on 2 cores, against the same workflow
   with nothing to do (Snakemake's start-up and DAG building).  The
   difference over N, times the cores, is the job time Snakemake and a
   bare interpreter add per job.
2. The imports of each script of workflow/scripts/ (or of ``--scripts``): its
   top-level import lines run in a fresh interpreter (median of 3, ``--repeats``),
   which is what every job of that rule pays before its first line of work;
   beside them, the least a job could import (numpy, xarray and netCDF4; with
   matplotlib for a figure).

Writes benchmarks/results/job-overhead.json and prints a table.  Nothing
is asserted: speed is measured here, not in the tests.

    python benchmarks/job_overhead.py            # N = 100
"""

from __future__ import annotations

import argparse
import json
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import _commit, _env  # noqa: E402
from benchmarks.workflow_copy import REPO, SNAKEMAKE  # noqa: E402

SCRIPTS = REPO / "workflow" / "scripts"
RESULTS = Path(__file__).with_name("results")

SNAKEFILE = """
rule all:
    input: expand("out/{{i}}.txt", i=range({n}))
rule one:
    output: "out/{{i}}.txt"
    script: "write.py"
"""


def _wall(command: list[str], cwd: Path) -> float:
    t0 = time.perf_counter()
    subprocess.run(command, cwd=cwd, env=_env(), check=True, capture_output=True, text=True)
    return time.perf_counter() - t0


def snakemake_per_job(n: int, cores: int) -> dict:
    """Job time Snakemake and a bare interpreter add per `script:` job."""
    with tempfile.TemporaryDirectory(prefix="job-overhead-") as tmp:
        work = Path(tmp)
        (work / "Snakefile").write_text(SNAKEFILE.format(n=n))
        (work / "write.py").write_text('open(snakemake.output[0], "w").write("x")\n')
        run = _wall([str(SNAKEMAKE), "--cores", str(cores), "--quiet"], work)
        idle = _wall([str(SNAKEMAKE), "--cores", str(cores), "--quiet"], work)  # nothing to do
    return dict(jobs=n, cores=cores, wall_time_s=run, nothing_to_do_s=idle,
                job_seconds_per_job=(run - idle) * cores / n)


def import_lines(script: Path) -> str:
    return "\n".join(line for line in script.read_text().splitlines()
                     if re.match(r"(from \S+ import |import )", line))


def interpreter_seconds(code: str, repeats: int = 3) -> float:
    """Median wall time of a fresh interpreter running `code`."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], env=_env(), check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=100, help="trivial jobs of the Snakemake part")
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3, help="interpreters per import time (median)")
    ap.add_argument("--scripts", nargs="+", metavar="NAME",
                    help="these scripts of workflow/scripts (default: every one)")
    ap.add_argument("--out", type=Path, default=RESULTS / "job-overhead.json")
    args = ap.parse_args(argv)

    n = args.repeats
    base = interpreter_seconds("pass", n)
    # the least a job can import: what reads and writes netCDF through xarray,
    # and that with matplotlib for a figure
    floor = interpreter_seconds("import numpy, xarray, netCDF4", n)
    floor_figure = interpreter_seconds("import numpy, xarray, netCDF4, matplotlib.pyplot", n)
    paths = ([SCRIPTS / f"{name}.py" for name in args.scripts] if args.scripts
             else sorted(SCRIPTS.glob("*.py")))
    scripts = {p.stem: interpreter_seconds(import_lines(p), n) for p in paths}
    snake = snakemake_per_job(args.jobs, args.cores)
    commit, dirty = _commit()
    record = dict(date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), commit=commit, uncommitted_changes=dirty,
                  machine=dict(platform=platform.platform(), python=platform.python_version()),
                  bare_interpreter_s=base, xarray_netcdf_imports_s=floor,
                  xarray_netcdf_matplotlib_imports_s=floor_figure,
                  snakemake=snake, script_imports_s=scripts)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1) + "\n")

    print(f"bare interpreter: {base:.3f} s; numpy, xarray, netCDF4: {floor:.2f} s; "
          f"with matplotlib.pyplot: {floor_figure:.2f} s")
    print(f"Snakemake, {snake['jobs']} trivial script jobs on {snake['cores']} cores: "
          f"{snake['wall_time_s']:.1f} s ({snake['nothing_to_do_s']:.1f} s with nothing to do), "
          f"{snake['job_seconds_per_job']:.2f} s of job time per job")
    print("\n| script | imports |\n|---|---|")
    for name, s in sorted(scripts.items(), key=lambda kv: -kv[1]):
        print(f"| `{name}.py` | {s:.2f} s |")
    values = list(scripts.values())
    print(f"\nimports per job: median {statistics.median(values):.2f} s, "
          f"{min(values):.2f}-{max(values):.2f} s")
    print(f"written: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
