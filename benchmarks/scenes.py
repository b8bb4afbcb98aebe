"""Wall time of each scene, and of the whole default run (`make bench CASE=scenes`).

Issue #6: `snakemake --cores 2` with the default config reproduces every scene
of the report in under 10 minutes wall on 2 cores at `standard` and under 2
minutes at `draft`, and the README gives each scene's wall time as measured by
a script in the repository.  This is that script.

Each scene runs in its own fresh copy of the workflow (benchmarks.workflow_copy:
Snakefile, config/, workflow/, data/ in a temporary directory; nothing cached
from another scene or from the repository's results/) with

    snakemake --cores 2 --config 'scenes=[<scene>]' accuracy=<preset> studies=False

which builds that scene's targets only (`studies=False` leaves the accuracy
studies of results/accuracy/ out of `rule all`; a scene with `compare_with`
also builds the scenes it draws beside itself, as it must).  The wall time is
time.perf_counter around the snakemake process, Snakemake's own start-up and
DAG building included, the copy excluded.  Jobs are counted from Snakemake's
"Finished jobid: N (Rule: name)" lines (rule `all` not counted); `FE jobs` are
the jobs of rule `sample` (one finite element asperity each).  FE work done
inside a single job (the `hertz` verification, `sliding`) is in the wall time
but not in that count.

With --full, the whole default run (every scene of config/config.yaml and the
accuracy studies) then runs in one more fresh copy:

    snakemake --cores 2 --config accuracy=<preset>

and a following `snakemake -n` there is timed and must say "Nothing to be
done" (the issue's "nothing changed: no job, in under 5 s").

Writes benchmarks/results/scenes-<preset>.json (this invocation's
measurements only; ``--out``) and prints a markdown table for the README.  Targets are
printed, never raised: speed is measured here, not asserted in the tests.  ``--keep DIR``
copies each scene's results tree into DIR after its timing, for the scripts that read
one (benchmarks/coupled_numbers.py).

    python benchmarks/scenes.py --accuracy draft --scenes profile_cosine hertz
    python benchmarks/scenes.py --accuracy standard --full      # what the README quotes
"""

from __future__ import annotations

import argparse
import collections
import datetime
import json
import os
import platform
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.workflow_copy import REPO, SNAKEMAKE, copy_workflow  # noqa: E402

OUT = Path(__file__).with_name("results")
#: the issue's wall-time targets of the whole default run on 2 cores, s
FULL_RUN_TARGET = {"draft": 120.0, "standard": 600.0}
#: the issue's target of a dry run with nothing to do, s
NOTHING_TO_DO_TARGET = 5.0
FINISHED = re.compile(r"^Finished jobid: \d+ \(Rule: (\w+)\)", flags=re.M)
STAMP = re.compile(r"^\[(\w{3} \w{3} +\d+ \d\d:\d\d:\d\d \d{4})\]$")
STARTED = re.compile(r"^(?:local)?(?:rule|checkpoint) (\w+):$")
JOBID = re.compile(r"^\s+jobid: (\d+)$")
DONE = re.compile(r"^Finished jobid: (\d+) \(Rule: (\w+)\)$")
FE_RULE = "sample"


def default_scenes() -> list[str]:
    return list(yaml.safe_load((REPO / "config" / "config.yaml").read_text())["scenes"])


def scene_info(name: str) -> dict:
    """The scene file's `title` and `report` (section and figures it reproduces)."""
    path = REPO / "config" / "scenes" / f"{name}.yaml"
    if not path.exists():
        raise SystemExit(f"no scene file {path.relative_to(REPO)}")
    scene = yaml.safe_load(path.read_text()) or {}
    return {"title": scene.get("title", ""), "report": str(scene.get("report", ""))}


def scene_command(name: str, preset: str, cores: int) -> list[str]:
    return ["snakemake", "--cores", str(cores), "--config", f"scenes=[{name}]",
            f"accuracy={preset}", "studies=False"]


def full_command(preset: str, cores: int) -> list[str]:
    return ["snakemake", "--cores", str(cores), "--config", f"accuracy={preset}"]


def job_seconds_by_rule(text: str) -> dict[str, float]:
    """Summed wall time of the jobs of each rule, from the timestamps Snakemake
    prints before each job's start and finish (1 s resolution): where the time goes."""
    stamp, rule, started, total = None, None, {}, collections.Counter()
    for line in text.splitlines():
        if m := STAMP.match(line):
            stamp = datetime.datetime.strptime(m.group(1), "%a %b %d %H:%M:%S %Y")
        elif m := STARTED.match(line):
            rule = m.group(1)
        elif (m := JOBID.match(line)) and rule and stamp:
            started[m.group(1)] = (rule, stamp)
            rule = None
        elif (m := DONE.match(line)) and stamp and m.group(1) in started:
            name, t0 = started.pop(m.group(1))
            total[name] += (stamp - t0).total_seconds()
    return {k: v for k, v in total.most_common() if k != "all"}


def _env(extra: dict | None = None) -> dict:
    env = {**os.environ, **(extra or {})}
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"  # parallel jobs share the cores; BLAS threads slow FE many-fold
    return env


def run_snakemake(workdir: Path, command: list[str], timeout: float | None,
                  env: dict | None = None) -> dict:
    """Run `command` (starting with 'snakemake') in `workdir`, with `env` added to the
    environment; wall time, jobs, outcome."""
    argv = [str(SNAKEMAKE), *command[1:]]
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(argv, cwd=workdir, capture_output=True, text=True,
                              timeout=timeout, env=_env(env))
        returncode, stdout, stderr = proc.returncode, proc.stdout, proc.stderr
    except subprocess.TimeoutExpired as err:
        returncode = None
        stdout = err.stdout.decode() if isinstance(err.stdout, bytes) else (err.stdout or "")
        stderr = err.stderr.decode() if isinstance(err.stderr, bytes) else (err.stderr or "")
    wall = time.perf_counter() - t0
    text = stdout + stderr
    jobs = collections.Counter(r for r in FINISHED.findall(text) if r != "all")
    record = {
        "command": shlex.join(command),
        "wall_time_s": round(wall, 2),
        "status": "ok" if returncode == 0 else ("timeout" if returncode is None else "failed"),
        "jobs": sum(jobs.values()),
        "fe_jobs": jobs.get(FE_RULE, 0),
        "jobs_by_rule": dict(sorted(jobs.items())),
        "job_seconds_by_rule": job_seconds_by_rule(text),
    }
    if record["status"] != "ok":
        record["error_tail"] = "\n".join(text.strip().splitlines()[-25:])
    return record


def time_scene(name: str, preset: str, cores: int, timeout: float | None,
               keep: Path | None = None) -> dict:
    """One scene from an empty copy; with `keep`, its results tree then copied into `keep`
    (untimed; the trees of several scenes merge there)."""
    with tempfile.TemporaryDirectory(prefix=f"scene-{name}-") as tmp:
        workdir = copy_workflow(Path(tmp))
        record = run_snakemake(workdir, scene_command(name, preset, cores), timeout)
        if keep is not None and (workdir / "results").is_dir():
            shutil.copytree(workdir / "results", keep, dirs_exist_ok=True)
    return {"scene": name, **scene_info(name), **record}


def time_full(preset: str, cores: int, timeout: float | None) -> dict:
    with tempfile.TemporaryDirectory(prefix="scenes-full-") as tmp:
        workdir = copy_workflow(Path(tmp))
        record = run_snakemake(workdir, full_command(preset, cores), timeout)
        if record["status"] == "ok":
            dry = ["snakemake", "-n", *full_command(preset, cores)[1:]]
            t0 = time.perf_counter()
            proc = subprocess.run([str(SNAKEMAKE), *dry[1:]], cwd=workdir, capture_output=True,
                                  text=True, env=_env())
            record["nothing_to_do_s"] = round(time.perf_counter() - t0, 2)
            record["nothing_to_do"] = (proc.returncode == 0
                                       and "Nothing to be done" in proc.stdout + proc.stderr)
    return record


def _seconds(t: float) -> str:
    return f"{t:.1f} s" if t < 100 else f"{t:.0f} s ({t / 60:.1f} min)"


def markdown(result: dict) -> str:
    rows = ["| scene | report | command | jobs | FE jobs | wall time |",
            "|---|---|---|---|---|---|"]
    for r in result["scenes"]:
        wall = _seconds(r["wall_time_s"]) + ("" if r["status"] == "ok" else f" ({r['status']})")
        report = r["report"].replace("|", "/")
        rows.append(f"| `{r['scene']}` | {report} | `{r['command']}` | {r['jobs']} | "
                    f"{r['fe_jobs']} | {wall} |")
    lines = ["\n".join(rows)]
    if result["scenes"]:
        total = sum(r["wall_time_s"] for r in result["scenes"])
        lines.append(f"Sum over scenes, each from an empty copy: {_seconds(total)}.")
    full = result.get("full")
    if full:
        target = FULL_RUN_TARGET.get(result["accuracy"])
        verdict = ""
        if target is not None and full["status"] == "ok":
            verdict = (f" (target {target:.0f} s: "
                       f"{'met' if full['wall_time_s'] <= target else 'MISSED'})")
        lines.append(f"Whole default run `{full['command']}`: {_seconds(full['wall_time_s'])}, "
                     f"{full['jobs']} jobs, {full['fe_jobs']} FE jobs, status "
                     f"{full['status']}{verdict}.")
        busiest = ", ".join(f"{rule} {secs:.0f} s" for rule, secs
                            in list(full.get("job_seconds_by_rule", {}).items())[:6])
        if busiest:
            lines.append(f"Summed job wall time by rule (largest first): {busiest}.")
        if "nothing_to_do_s" in full:
            ok = full["nothing_to_do"] and full["nothing_to_do_s"] <= NOTHING_TO_DO_TARGET
            lines.append(f"Then `snakemake -n`: {full['nothing_to_do_s']:.2f} s, "
                         f"{'Nothing to be done' if full['nothing_to_do'] else 'JOBS PLANNED'} "
                         f"(target {NOTHING_TO_DO_TARGET:.0f} s: {'met' if ok else 'MISSED'}).")
    return "\n\n".join(lines)


def _commit() -> tuple[str, bool]:
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = bool(subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                                    cwd=REPO, capture_output=True, text=True).stdout.strip())
        return head, dirty
    except (OSError, subprocess.CalledProcessError):
        return "unknown", True


def provenance(accuracy: str, cores: int) -> dict:
    """What a measurement of a run was made on: preset, cores, date, commit, machine (with
    the 1-min load average before: other work on the machine skews the times)."""
    commit, dirty = _commit()
    return {
        "accuracy": accuracy,
        "cores": cores,
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "commit": commit,
        "uncommitted_changes": dirty,
        "machine": {"platform": platform.platform(), "cpu_count": os.cpu_count(),
                    "python": platform.python_version(),
                    "load_average_before": round(os.getloadavg()[0], 2)},
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="+", metavar="NAME",
                        help="scenes to time (default: those of config/config.yaml)")
    parser.add_argument("--no-scenes", action="store_true", help="time no single scene (with --full)")
    parser.add_argument("--accuracy", choices=["draft", "standard", "fine"], default="standard")
    parser.add_argument("--full", action="store_true",
                        help="then the whole default run in one fresh copy, and a dry run after it")
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=None, help="per snakemake run, s")
    parser.add_argument("--out", type=Path, help="JSON file (default benchmarks/results/scenes-<preset>.json)")
    parser.add_argument("--keep", type=Path, metavar="DIR",
                        help="copy each scene's results tree into DIR (a results folder)")
    args = parser.parse_args(argv)

    names = [] if args.no_scenes else (args.scenes or default_scenes())
    for name in names:
        scene_info(name)  # a missing scene file stops before any run
    result = {
        **provenance(args.accuracy, args.cores),
        "scenes": [],
        "full": None,
    }
    for name in names:
        print(f"{name} ...", end=" ", flush=True)
        record = time_scene(name, args.accuracy, args.cores, args.timeout, args.keep)
        result["scenes"].append(record)
        print(f"{record['status']}, {_seconds(record['wall_time_s'])}, {record['jobs']} jobs "
              f"({record['fe_jobs']} FE)", flush=True)
        if record["status"] != "ok":
            print(record["error_tail"], file=sys.stderr)
    if args.full:
        print("whole default run ...", end=" ", flush=True)
        result["full"] = time_full(args.accuracy, args.cores, args.timeout)
        print(f"{result['full']['status']}, {_seconds(result['full']['wall_time_s'])}", flush=True)
        if result["full"]["status"] != "ok":
            print(result["full"]["error_tail"], file=sys.stderr)
    result["machine"]["load_average_after"] = round(os.getloadavg()[0], 2)
    out = args.out or OUT / f"scenes-{args.accuracy}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=1) + "\n")
    print()
    print(markdown(result))
    print(f"\nload average (1 min) before {result['machine']['load_average_before']}, after "
          f"{result['machine']['load_average_after']}, on {os.cpu_count()} cores")
    print(f"written: {out}")
    failed = [r for r in result["scenes"] + ([result["full"]] if result["full"] else [])
              if r["status"] != "ok"]
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
