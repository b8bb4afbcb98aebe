"""Where the wall time of a whole run goes (`make bench CASE=profile`).

Runs the whole default run from an empty copy of the workflow, as a user's
first command does,

    snakemake --cores 2 --config accuracy=<preset>

with ``ASPERITY_PROFILE`` set, so that every job runs under cProfile and says how
long its process ran before the job began (`asperity.io.joblog`).  The run's
2-core wall time is then split into

- **before the job**: each process from its start to its job's start: the
  interpreter, Snakemake's script preamble and the script's imports;
- **the jobs**, by concern (below), from their profiles;
- **Snakemake and idle cores**: the rest of wall time x cores (the scheduler,
  its file checks, and cores without a job while the last jobs finish).

A job's time is split by concern through its profile: a function of the project
(or of scikit-fem, SuperLU, xarray, matplotlib) counts for its concern; time in
NumPy, SciPy, builtins and the standard library counts for the concerns of the
functions that called it, in proportion of their calls' time.  cProfile slows
Python-heavy code, so the jobs' seconds here are larger than in a plain run; the
shares are what this measures, and the plain run's wall time is in
benchmarks/results/scenes-<preset>.json.

Writes benchmarks/results/profile-<preset>.json and prints its table (the docs'
cost page shows it).

    python benchmarks/profile_run.py --accuracy draft
    python benchmarks/profile_run.py --accuracy draft --scenes hertz     # a small case
    python benchmarks/profile_run.py --keep /tmp/profiles                # each job's profile kept
"""

from __future__ import annotations

import argparse
import collections
import json
import pstats
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
import scipy.sparse

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import full_command, provenance, run_snakemake  # noqa: E402
from benchmarks.workflow_copy import copy_workflow  # noqa: E402

OUT = Path(__file__).with_name("results")
BEFORE = "start-up and imports (before the job)"
SCHEDULER = "Snakemake and idle cores"
#: concern -> parts of a file path (first match wins, in this order)
CONCERNS = [
    ("imports inside the job", ("<frozen importlib", "importlib/", "<module>")),
    ("figures", ("matplotlib/", "PIL/", "asperity/io/figures", "asperity/stages/figures")),
    ("netCDF reading and writing", ("xarray/", "netCDF4", "pandas/", "cftime", "asperity/io/netcdf")),
    ("factorization and linear solves", ("scipy/sparse/linalg/", "_superlu", "SuperLU")),
    ("assembly and meshes", ("skfem/", "asperity/fe/assembly", "asperity/fe/discretization",
                             "asperity/fe/mesh")),
    ("constitutive updates", ("asperity/fe/materials/",)),
    ("finite element drivers, Newton, contact", ("asperity/fe/",)),
    ("surface statistics and peaks", ("asperity/surface/", "asperity/peaks", "SurfaceTopography")),
    ("homogenization, routes, references", ("asperity/homogenize/", "asperity/references/",
                                            "ContactMechanics", "asperity/friction")),
    ("other project code", ("asperity/",)),
]
OTHER = "other (not attributed)"
#: a job's log path -> its rule: <results>/<scene>/logs/<rule>.log, <results>/samples/logs/<key>.log,
#: <results>/accuracy/logs/<study>.log
LOG = re.compile(r"([^/]+)/logs/([^/]+)\.log$")


def concern_of(key: tuple) -> str | None:
    """The concern of a profiled function (file, line, name), None for shared code."""
    filename, _, name = key
    where = filename if filename != "~" else name
    if name == "<module>":
        where = "<module>"  # a module's top-level code runs when it is first imported
    for concern, parts in CONCERNS:
        if any(part in where for part in parts):
            return concern
    return None


def split_by_concern(stats: dict) -> dict[str, float]:
    """Own time (s) of every function, each counted for its concern or, for shared code,
    for its callers' shares in proportion of their calls' cumulative time: a Markov
    chain up the call graph, absorbed by the functions that have a concern (the part
    that never is, a function called from the script's top level or recursion only,
    is `OTHER`)."""
    keys = list(stats)
    index = {k: i for i, k in enumerate(keys)}
    names = [c for c, _ in CONCERNS] + [OTHER]
    fixed = np.zeros((len(keys), len(names)))
    rows, cols, weights = [], [], []
    for i, key in enumerate(keys):
        own = concern_of(key)
        if own is not None:
            fixed[i, names.index(own)] = 1.0
            continue
        edges = [(index[c], e[3] + 1e-9 * e[1]) for c, e in stats[key][4].items() if c in index]
        total = sum(w for _, w in edges)
        if total <= 0:
            fixed[i, -1] = 1.0
            continue
        for j, w in edges:
            rows.append(i), cols.append(j), weights.append(w / total)
    up = scipy.sparse.csr_matrix((weights, (rows, cols)), shape=(len(keys), len(keys)))
    share = fixed.copy()
    for _ in range(500):  # call chains are far shorter; recursion converges geometrically
        new = fixed + up @ share
        if np.abs(new - share).max() < 1e-9:
            break
        share = new
    share[:, -1] += np.clip(1.0 - share.sum(axis=1), 0.0, None)
    own_time = np.array([stats[k][2] for k in keys])
    seconds = own_time @ share
    return {name: float(t) for name, t in zip(names, seconds) if t > 0}


def rule_of(log: str) -> str:
    m = LOG.search(log)
    if not m:
        return "unknown"
    folder, stem = m.groups()
    return {"samples": "sample", "accuracy": f"accuracy_{stem}"}.get(folder, stem)


def read_profiles(folder: Path) -> list[dict]:
    """Every job's record, with its seconds by concern."""
    jobs = []
    for meta in sorted(folder.glob("*.json")):
        record = json.loads(meta.read_text())
        prof = meta.with_suffix(".prof")
        record["rule"] = rule_of(record["log"])
        record["concerns"] = split_by_concern(pstats.Stats(str(prof)).stats) if prof.exists() else {}
        jobs.append(record)
    return jobs


def summarize(jobs: list[dict], wall: float, cores: int) -> dict:
    """The run's core-seconds by concern, and by rule."""
    by_concern = collections.Counter()
    by_rule = collections.defaultdict(lambda: {"jobs": 0, "before_job_s": 0.0, "job_s": 0.0})
    for job in jobs:
        before = job.get("before_job_s") or 0.0
        by_concern[BEFORE] += before
        profiled = sum(job["concerns"].values())
        for concern, seconds in job["concerns"].items():
            by_concern[concern] += seconds
        by_concern[OTHER] += max(job["job_s"] - profiled, 0.0)  # the profiler's own bookkeeping
        rule = by_rule[job["rule"]]
        rule["jobs"] += 1
        rule["before_job_s"] += before
        rule["job_s"] += job["job_s"]
    busy = sum(by_concern.values())
    by_concern[SCHEDULER] = max(wall * cores - busy, 0.0)
    return {
        "core_seconds": round(wall * cores, 2),
        "processes": len(jobs),
        "by_concern_s": {k: round(v, 2) for k, v in by_concern.most_common()},
        "by_rule": {k: {"jobs": v["jobs"], "before_job_s": round(v["before_job_s"], 2),
                        "job_s": round(v["job_s"], 2)}
                    for k, v in sorted(by_rule.items(), key=lambda kv: -kv[1]["job_s"]
                                       - kv[1]["before_job_s"])},
    }


def markdown(result: dict) -> str:
    s = result["summary"]
    total = s["core_seconds"]
    rows = ["| where | core-seconds | share |\n|---|---|---|"]
    rows += [f"| {k} | {v:.1f} | {100 * v / total:.0f} % |" for k, v in s["by_concern_s"].items()]
    rules = ["| rule | jobs | before the job (s) | job (s) |\n|---|---|---|---|"]
    rules += [f"| `{k}` | {v['jobs']} | {v['before_job_s']:.1f} | {v['job_s']:.1f} |"
              for k, v in s["by_rule"].items()]
    head = (f"`{result['run']['command']}` with every job profiled: {result['run']['wall_time_s']:.0f} s "
            f"on {result['cores']} cores ({total:.0f} core-seconds), {s['processes']} job processes.")
    return head + "\n\n" + "\n".join(rows) + "\n\n" + "\n".join(rules)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--accuracy", choices=["draft", "standard", "fine"], default="draft")
    parser.add_argument("--scenes", nargs="+", metavar="NAME",
                        help="only these scenes, without the studies (default: the whole default run)")
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=None, help="s")
    parser.add_argument("--out", type=Path, help="JSON file (default benchmarks/results/profile-<preset>.json)")
    parser.add_argument("--keep", type=Path, metavar="DIR",
                        help="keep the jobs' profiles in DIR (<host>-<pid>.prof for pstats or snakeviz)")
    args = parser.parse_args(argv)

    command = full_command(args.accuracy, args.cores)
    if args.scenes:
        command += [f"scenes=[{','.join(args.scenes)}]", "studies=False"]
    header = provenance(args.accuracy, args.cores)
    with tempfile.TemporaryDirectory(prefix="profile-run-") as tmp:
        workdir = copy_workflow(Path(tmp))
        profiles = args.keep.resolve() if args.keep else Path(tmp) / "asperity-profiles"
        print(" ".join(command), "(profiled) ...", flush=True)
        run = run_snakemake(workdir, command, args.timeout, env={"ASPERITY_PROFILE": str(profiles)})
        jobs = read_profiles(profiles) if profiles.exists() else []
    result = {
        **header,
        "run": {k: run[k] for k in ("command", "wall_time_s", "status", "jobs", "fe_jobs")},
        "summary": summarize(jobs, run["wall_time_s"], args.cores),
    }
    if run["status"] != "ok":
        print(run["error_tail"], file=sys.stderr)
    out = args.out or OUT / f"profile-{args.accuracy}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=1) + "\n")
    print(markdown(result))
    print(f"written: {out}")
    return 0 if run["status"] == "ok" else 1


if __name__ == "__main__":
    sys.exit(main())
