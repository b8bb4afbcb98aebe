"""The one entry point of the benchmarks: `make bench CASE=<case> ARGS="..."`.

``kernels`` (the default) times the kernels the issues set targets for, each as the
best of several repeats (wall clock, this machine), printed as a table and written to
benchmarks/results/kernels.json (read by docs/generate.py, with the machine, date and
commit); ARGS picks kernels by part of their name, and such a partial run writes
benchmarks/out/kernels.json instead, leaving the record of the full run as it is.  Targets are
stated beside each case; a miss is printed, not raised: speed is measured here, never
asserted in the unit tests.  Every other case runs its script in benchmarks/ with
ARGS, or with the arguments of `STUDIES` when ARGS is empty; ``make bench CASE=list``
lists them.  ``short`` (what CI runs) runs a small case of every kernel and every study
one after the other and records their times in benchmarks/out/short.json (`short`),
asserting none: it fails only if a case does.
"""

from __future__ import annotations

import json
import os
import platform
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from asperity import homogenize, peaks, surface

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable

OUT = Path(__file__).with_name("out")


def best_of(fn, repeats=5, clock=time.perf_counter):
    """The least time of `repeats` calls of `fn` (wall clock, or `clock`)."""
    times = []
    for _ in range(repeats):
        t0 = clock()
        fn()
        times.append(clock() - t0)
    return min(times)


# Each case takes `small`: a smaller input (or a coarser preset) run once, for the short
# form (`short`), which times it without a target.

def case_profile_statistics(small=False):
    x = np.arange(10_000 if small else 1_000_000) * 0.05
    c, k, e = surface.quasirandom_series(n=40, seed=1993)
    z = surface.evaluate_series(x, c, k, e)
    return best_of(lambda: surface.profile_statistics(z, 0.05), repeats=1 if small else 3)


def case_expectation_gauss_200(small=False):
    density = peaks.JointDensity(sigma=1.1620, sigma_slope=0.59221, sigma_curvature=0.49315)
    rect = (-5.0, 10.0, 0.0, 5.0)
    n = 20 if small else 200
    return best_of(lambda: homogenize.expectation(
        1.0, density, rect, cells=(n, n), rule="gauss", peak_density=0.025359),
        repeats=1 if small else 5)


def case_fe_hertz_five_points(small=False):
    from asperity.fe import LinearElastic, Paraboloid, solve_asperity

    return best_of(lambda: solve_asperity(Paraboloid(1.0), LinearElastic(1000.0, 0.3),
                                          [0.001, 0.002, 0.005, 0.01, 0.02],
                                          accuracy="draft" if small else "standard"),
                   repeats=1 if small else 3)


def case_fe_cosine_forty_levels(small=False):
    from asperity.fe import CosineHill, LinearElastic, solve_asperity

    hill = CosineHill.from_aspect(17.09, 2e-6)  # the representative hill of scene asperity_shape
    levels = np.geomspace(1e-10, 0.3 * 2e-6, 5 if small else 40)
    return best_of(lambda: solve_asperity(hill, LinearElastic(65e9, 0.3), levels,
                                          accuracy="draft" if small else "standard"),
                   repeats=1 if small else 3)


def case_fe_viscoplastic_hill_load_unload(small=False):
    """One viscoplastic asperity of report 8.2.2 loaded and unloaded, `standard` (`small`:
    at `draft` to a fiftieth of its height, once).

    SAE 1020 (Bodner-Partom, 8.2.1) cosine hill of the steel surface: width /
    height pi / (sqrt 2 0.160) = 13.9 (rms slope 0.160), tip curvature
    0.042 1/um (the report's representative asperity), height 2.44 um;
    pressed at 0.25 um/s to a tenth of its height (0.244 um: 8.5 % inelastic
    strain, the small-strain limit of 7.3) and unloaded to zero force.  The
    report needed about 10,000 time steps for its analysis.  Returns the
    best wall time and the steps of the run.
    """
    from asperity.fe import CosineHill
    from asperity.fe.materials.bodner_partom import BodnerPartom
    from asperity.fe.drivers.inelastic import History, solve_asperity_history

    ratio = np.pi / (np.sqrt(2.0) * 0.160)
    hill = CosineHill.from_aspect(ratio, 2.0 * np.pi**2 / (ratio**2 * 0.042e6))
    history = History.load_unload((0.02 if small else 0.1) * hill.height, 0.25e-6)
    out = {}

    def run():
        out["ds"] = solve_asperity_history(hill, BodnerPartom.sae_1020(), history,
                                           accuracy="draft" if small else "standard")

    seconds = best_of(run, repeats=1 if small else 2)
    ds = out["ds"]
    extra = {"steps": int(ds.attrs["steps"]), "report_steps": 10_000,
             "rejected_steps": int(ds.attrs["total_step_cuts"]),
             "newton_iterations": int(ds.newton_iterations.sum()),
             "dofs": int(ds.dofs[0]), "time_tolerance": ds.attrs["time_tolerance"],
             "residual_interference_m": ds.attrs["residual_interference"]}
    print(f"    {extra['steps']} time steps (report: about 10,000), {extra['rejected_steps']} "
          f"rejected, {extra['newton_iterations']} Newton iterations, {extra['dofs']} dofs",
          flush=True)
    return seconds, extra


def case_interacting_2000_peaks(small=False):
    """The interacting route alone (issue 48): about 1,800 peaks of a synthetic Gaussian map
    (512^2 points every 1 um, correlation length 5 um) coupled over 11 separations (`small`:
    a 128^2 map, 3 separations): CPU seconds with the route's default law (each summit's
    shape), and with Hertz's."""
    from asperity.homogenize.interacting import interacting_interface
    from asperity.stages.routes import INTERACTING_ACCEPT, INTERACTING_TOLERANCE, asperity_law
    from asperity.surface.maps import map_peaks
    from asperity.surface.synthetic import gaussian_map

    n = 128 if small else 512
    z = gaussian_map(n, 1e-6, 1e-6, 5e-6, 3)
    z = z - z.mean()
    found = map_peaks(z, 1e-6, 1e-6)
    found = found.isel(peak=np.flatnonzero(found["curvature"].values > 0))
    h = np.linspace(0.5, 3.0, 3 if small else 11) * float(z.std())
    modulus = 70e9 / (1 - 0.33**2)

    def run(kind):
        t0 = time.process_time()
        law = asperity_law(kind, z, 1e-6, 1e-6, found, modulus)
        interacting_interface(found["x"].values, found["y"].values, found["height"].values,
                              found["curvature"].values, h, modulus, (n * 1e-6, n * 1e-6), law=law,
                              tolerance=INTERACTING_TOLERANCE, accept=INTERACTING_ACCEPT)
        return time.process_time() - t0

    hertz = run("hertz")
    return run("shape"), {"peaks": int(found.sizes["peak"]), "clock": "CPU", "hertz_seconds": hertz}


def case_j2_sphere_fine_over_standard(small=False):
    """An elastic-perfectly plastic sphere (E/Y = 400, nu = 0.3; the sphere of
    tests/fe/test_inelastic_edge.py) pressed to 20 times its critical interference (Hertz
    first yield, p0 = 1.6 Y) at `standard` and at `fine`: the CPU time of fine over that of
    standard (issue #51: at most 5), each the best of two runs (`best_of`, CPU clock).
    `small`: to 5 times at `draft` alone, once, its CPU seconds."""
    from asperity.fe import J2Plasticity, Sphere, solve_asperity_history
    from asperity.fe.drivers.inelastic import History

    E, nu = 1000.0, 0.3
    Y = E / 400
    w_c = (np.pi * 1.6 * Y / (2 * E / (1 - nu**2))) ** 2
    cpu, steps = {}, {}
    for preset in ("draft",) if small else ("standard", "fine"):
        def press(preset=preset):
            ds = solve_asperity_history(Sphere(1.0), J2Plasticity(E, nu, Y),
                                        History.loading((5 if small else 20) * w_c, 1.0),
                                        accuracy=preset)
            steps[preset] = int(ds.attrs["steps"])

        cpu[preset] = best_of(press, repeats=1 if small else 2, clock=time.process_time)
    if small:
        return cpu["draft"], {"steps": steps}
    print(f"    CPU standard {cpu['standard']:.1f} s ({steps['standard']} steps), "
          f"fine {cpu['fine']:.1f} s ({steps['fine']} steps)", flush=True)
    return cpu["fine"] / cpu["standard"], {"unit": "x standard", "standard_cpu_s": cpu["standard"],
                                           "fine_cpu_s": cpu["fine"], "steps": steps}


CASES = [
    ("profile statistics, 10^6 points, all three methods", case_profile_statistics, 1.0),
    ("expectation integral, 200 x 200 cells, Gauss rule", case_expectation_gauss_200, 0.1),
    ("FE Hertz curve, 5 interferences, standard", case_fe_hertz_five_points, 2.0),
    ("FE cosine hill, 40-level loading curve, standard", case_fe_cosine_forty_levels, 3.0),
    ("FE viscoplastic hill (SAE 1020), load and unload, standard",
     case_fe_viscoplastic_hill_load_unload, 30.0),
    ("interacting route, ~1,800 peaks, 11 separations, shape law (CPU)", case_interacting_2000_peaks, 10.0),
    ("J2 sphere to 20 w_c, CPU of fine over standard", case_j2_sphere_fine_over_standard, 5.0),
]


class Study(NamedTuple):
    """A case that runs a script of benchmarks/ (CORES, the Makefile's, is the number of
    cores of the workflow runs)."""

    script: str
    #: its arguments when ARGS is empty
    default: list[str]
    #: what it measures
    what: str
    #: the arguments of its small case in the short form (`short`), every output under
    #: benchmarks/out/short/; None: left out of it, for the reason in `SHORT_SKIPPED`
    short: list[str] | None


_CORES = os.environ.get("CORES", "2")
#: where the short form's cases write (relative to the repository, the commands' folder)
_S = "benchmarks/out/short"
STUDIES = {
    "scenes": Study("scenes.py", ["--accuracy", "standard", "--cores", _CORES, "--full"],
                    "wall time of each scene from an empty copy, then of the whole default run",
                    ["--accuracy", "draft", "--scenes", "asperity_shape", "--cores", _CORES,
                     "--keep", f"{_S}/results", "--out", f"{_S}/scenes.json"]),
    "profile": Study("profile_run.py", ["--accuracy", "draft", "--cores", _CORES],
                     "where a whole run's wall time goes: start-up, imports, assembly, solves, I/O, "
                     "figures",
                     ["--accuracy", "draft", "--scenes", "profile_cosine", "--cores", _CORES,
                      "--out", f"{_S}/profile.json"]),
    "jobs": Study("job_overhead.py", ["--cores", _CORES],
                  "what a job pays before it computes: Snakemake per script job, each script's imports",
                  ["--jobs", "4", "--repeats", "1", "--scripts", "sample", "--cores", _CORES,
                   "--out", f"{_S}/job-overhead.json"]),
    "adhesion": Study("adhesion_cost.py", [], "CPU time of the adhesive jobs",
                      ["--only-large", "--radii", "5", "--accuracies", "draft",
                       "--out", f"{_S}/adhesion-cost.json"]),
    # a route alone: the whole reference scene, boundary elements and comparison, is what
    # the workflow's test of deterministic_reference runs
    "reference": Study("reference_cost.py", ["--accuracy", "draft", "--cores", _CORES],
                       "the deterministic_reference scene: wall time, the routes' errors",
                       ["--scene", "afm_reference", "--accuracy", "draft", "--cores", _CORES,
                        "--parts", "routes", "--routes", "peaks", "--out", f"{_S}/reference.json"]),
    "linear": Study("linear_solvers.py", [], "SuperLU against PARDISO on the 3-D asperity's tangents",
                    ["--tips", "2", "--repeats", "1", "--out", f"{_S}/linear-solvers.json"]),
    "surface": Study("surface_speed.py", [], "a 2048^2 map's statistics beside SurfaceTopography's",
                     ["--points", "256", "--repeats", "1", "--out", f"{_S}/surface-speed.json"]),
}
#: case -> why the short form leaves it out
SHORT_SKIPPED: dict[str, str] = {}
#: a short case still running after this many seconds has failed
SHORT_TIMEOUT = 600.0


def _children_cpu() -> float:
    """CPU seconds of the waited-for child processes (and theirs) so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _study(case: str, args: list[str], log: Path) -> tuple[int | str, float]:
    """Run the script of `case` with `args` from the repository, its output to `log`: its exit
    code ("timeout" past `SHORT_TIMEOUT`, its process group then stopped) and CPU seconds."""
    root = Path(__file__).resolve().parents[1]
    command = [sys.executable, f"benchmarks/{STUDIES[case].script}", *args]
    cpu = _children_cpu()
    with open(log, "w") as sink:
        proc = subprocess.Popen(command, cwd=root, stdout=sink, stderr=subprocess.STDOUT,
                                start_new_session=True)
        try:
            code = proc.wait(timeout=SHORT_TIMEOUT)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait()
            code = "timeout"
    return code, _children_cpu() - cpu


def short(names: list[str] | None = None) -> int:
    """`make bench CASE=short`: a small case of every kernel (`CASES`, each once on a smaller
    input, in this process) and of every study (`Study.short`, each script in a process of its
    own), one after the other, so that every benchmark keeps working; ARGS picks cases by
    name (``kernels``: every kernel).  Times are recorded, never held against a target:
    benchmarks/out/short.json gets each case's command, exit code, wall and CPU seconds
    beside the machine and commit; the scripts write under benchmarks/out/short/ (emptied
    first when every case runs), each script's output to <case>.log there.  Exit code 1 if a case
    failed."""
    import shutil
    import traceback

    root = Path(__file__).resolve().parents[1]
    folder = root / _S
    if not names:
        shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True, exist_ok=True)
    todo = [(f"kernel {fn.__name__.removeprefix('case_')}", fn) for _, fn, _ in CASES]
    todo += [(case, None) for case in STUDIES]
    if names:
        todo = [(case, fn) for case, fn in todo
                if case in names or (fn is not None and "kernels" in names)]
    from benchmarks.scenes import _commit

    commit, dirty = _commit()
    record = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "commit": commit,
              "uncommitted_changes": dirty, "cores": int(_CORES),
              "machine": {"platform": platform.platform(), "python": sys.version.split()[0],
                          "processor": platform.processor() or platform.machine(),
                          "cpu_count": os.cpu_count(),
                          "load_average_before": round(os.getloadavg()[0], 2)},
              "cases": [], "skipped": {}}
    failed = []
    t_start = time.perf_counter()
    for k, (case, fn) in enumerate(todo, start=1):
        head = f"short [{k}/{len(todo)}] {case}"
        if fn is None and STUDIES[case].short is None:
            print(f"{head}: skipped: {SHORT_SKIPPED[case]}", flush=True)
            record["skipped"][case] = SHORT_SKIPPED[case]
            continue
        if fn is not None:
            command = f"benchmarks/run.py: {fn.__name__}(small=True)"
        else:
            command = " ".join(["python", f"benchmarks/{STUDIES[case].script}", *STUDIES[case].short])
        print(f"{head}: {command}", flush=True)
        t0 = time.perf_counter()
        if fn is not None:
            c0 = time.process_time()
            try:
                fn(small=True)
                code = 0
            except Exception:  # recorded and reported; the other cases still run
                traceback.print_exc()
                code = 1
            cpu = time.process_time() - c0
        else:
            log = folder / f"{case}.log"
            code, cpu = _study(case, STUDIES[case].short, log)
        wall = time.perf_counter() - t0
        record["cases"].append({"case": case, "command": command, "exit_code": code,
                                "wall_time_s": round(wall, 2), "cpu_time_s": round(cpu, 2)})
        if code == 0:
            print(f"{head}: ok, {wall:.1f} s wall, {cpu:.1f} s CPU", flush=True)
            continue
        failed.append(case)
        print(f"{head}: FAILED (exit code {code}) after {wall:.1f} s", flush=True)
        if fn is None:
            tail = log.read_text(errors="replace").splitlines()[-30:] + [f"(all of it: {_S}/{case}.log)"]
            print("\n".join(f"    {line}" for line in tail), flush=True)
    record["wall_time_s"] = round(time.perf_counter() - t_start, 2)
    record["machine"]["load_average_after"] = round(os.getloadavg()[0], 2)
    record["failed"] = failed
    (OUT / "short.json").write_text(json.dumps(record, indent=1) + "\n")
    print(f"short form: {len(record['cases'])} cases in {record['wall_time_s']:.0f} s wall, "
          f"{len(record['skipped'])} skipped; written {OUT / 'short.json'}", flush=True)
    if failed:
        print(f"make bench CASE=short: {len(failed)} case(s) failed: {', '.join(failed)} "
              f"(their output: {_S}/<case>.log)", file=sys.stderr)
        return 1
    return 0


def run_case(case: str, args: list[str]) -> int:
    """Run one case (module docstring); the exit code of its script."""
    if case == "kernels":
        main(args)
        return 0
    if case == "short":
        return short(args)
    if case == "list":
        print(f"{'kernels':<14s} the kernels' speed against the issues' targets (default)")
        for name, study in STUDIES.items():
            print(f"{name:<14s} {study.what}")
        print(f"{'short':<14s} a small case of each of the above, timed against no target (CI)")
        return 0
    if case not in STUDIES:
        print(f"make bench: no case {case!r} (key CASE); one of kernels, {', '.join(STUDIES)}, short",
              file=sys.stderr)
        return 2
    command = [sys.executable, str(Path(__file__).with_name(STUDIES[case].script)),
               *(args or STUDIES[case].default)]
    print(" ".join(command), flush=True)
    return subprocess.call(command)


def main(names=None):
    from benchmarks.scenes import OUT as RESULTS, _commit

    RESULTS.mkdir(parents=True, exist_ok=True)
    rows = []
    for name, fn, target in CASES:
        if names and not any(n in name for n in names):
            continue
        value = fn()
        value, extra = value if isinstance(value, tuple) else (value, {})
        unit = extra.pop("unit", "s")  # what a case measures: seconds, unless it says
        rows.append({"case": name, "value": value, "unit": unit, "target": target,
                     "met": value < target, **extra})
        print(f"{name:<60s} {value:9.4f} {unit}   target < {target:g} {unit}   "
              f"{'met' if value < target else 'MISSED'}", flush=True)
    commit, dirty = _commit()
    record = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "commit": commit,
              "uncommitted_changes": dirty, "machine": platform.platform(),
              "python": sys.version.split()[0],
              "processor": platform.processor() or platform.machine(), "cases": rows}
    path = (OUT if names else RESULTS) / "kernels.json"  # a partial run is no record
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record, indent=2))
    print(f"written {path}")


if __name__ == "__main__":
    argv = sys.argv[1:]
    sys.exit(run_case(argv[0] if argv else "kernels", argv[1:]))
