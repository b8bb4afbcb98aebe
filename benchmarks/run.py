"""The one entry point of the benchmarks: `make bench CASE=<case> ARGS="..."`.

``kernels`` (the default) times the kernels the issues set targets for, each as the
best of several repeats (wall clock, this machine), printed as a table and written to
benchmarks/out/results.json; ARGS picks kernels by part of their name.  Targets are
stated beside each case; a miss is printed, not raised: speed is measured here, never
asserted in the unit tests.  Every other case runs its script in benchmarks/ with
ARGS, or with the arguments of `STUDIES` when ARGS is empty; ``make bench CASE=list``
lists them.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from asperity import homogenize, peaks, surface

OUT = Path(__file__).with_name("out")


def best_of(fn, repeats=5, clock=time.perf_counter):
    """The least time of `repeats` calls of `fn` (wall clock, or `clock`)."""
    times = []
    for _ in range(repeats):
        t0 = clock()
        fn()
        times.append(clock() - t0)
    return min(times)


def case_profile_statistics():
    x = np.arange(1_000_000) * 0.05
    c, k, e = surface.quasirandom_series(n=40, seed=1993)
    z = surface.evaluate_series(x, c, k, e)
    return best_of(lambda: surface.profile_statistics(z, 0.05), repeats=3)


def case_expectation_gauss_200():
    density = peaks.JointDensity(sigma=1.1620, sigma_slope=0.59221, sigma_curvature=0.49315)
    rect = (-5.0, 10.0, 0.0, 5.0)
    return best_of(lambda: homogenize.expectation(
        1.0, density, rect, cells=(200, 200), rule="gauss", peak_density=0.025359))


def case_fe_hertz_five_points():
    from asperity.fe import LinearElastic, Paraboloid, solve_asperity

    return best_of(lambda: solve_asperity(Paraboloid(1.0), LinearElastic(1000.0, 0.3),
                                          [0.001, 0.002, 0.005, 0.01, 0.02], accuracy="standard"),
                   repeats=3)


def case_fe_cosine_forty_levels():
    from asperity.fe import CosineHill, LinearElastic, solve_asperity

    hill = CosineHill.from_aspect(17.09, 2e-6)  # the representative hill of scene asperity_shape
    levels = np.geomspace(1e-10, 0.3 * 2e-6, 40)
    return best_of(lambda: solve_asperity(hill, LinearElastic(65e9, 0.3), levels,
                                          accuracy="standard"), repeats=3)


def case_fe_viscoplastic_hill_load_unload():
    """One viscoplastic asperity of report 8.2.2 loaded and unloaded, `standard`.

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
    history = History.load_unload(0.1 * hill.height, 0.25e-6)
    out = {}

    def run():
        out["ds"] = solve_asperity_history(hill, BodnerPartom.sae_1020(), history,
                                           accuracy="standard")

    seconds = best_of(run, repeats=2)
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


def case_interacting_2000_peaks():
    """The interacting route alone (issue 48): about 1,800 peaks of a synthetic Gaussian map
    (512^2 points every 1 um, correlation length 5 um) coupled over 11 separations: CPU
    seconds with the route's default law (each summit's shape), and with Hertz's."""
    from asperity.homogenize.interacting import interacting_interface
    from asperity.stages.routes import INTERACTING_ACCEPT, INTERACTING_TOLERANCE, asperity_law
    from asperity.surface.maps import map_peaks
    from asperity.surface.synthetic import gaussian_map

    z = gaussian_map(512, 1e-6, 1e-6, 5e-6, 3)
    z = z - z.mean()
    found = map_peaks(z, 1e-6, 1e-6)
    found = found.isel(peak=np.flatnonzero(found["curvature"].values > 0))
    h = np.linspace(0.5, 3.0, 11) * float(z.std())
    modulus = 70e9 / (1 - 0.33**2)

    def run(kind):
        t0 = time.process_time()
        law = asperity_law(kind, z, 1e-6, 1e-6, found, modulus)
        interacting_interface(found["x"].values, found["y"].values, found["height"].values,
                              found["curvature"].values, h, modulus, (512e-6, 512e-6), law=law,
                              tolerance=INTERACTING_TOLERANCE, accept=INTERACTING_ACCEPT)
        return time.process_time() - t0

    hertz = run("hertz")
    return run("shape"), {"peaks": int(found.sizes["peak"]), "clock": "CPU", "hertz_seconds": hertz}


def case_j2_sphere_fine_over_standard():
    """An elastic-perfectly plastic sphere (E/Y = 400, nu = 0.3; the sphere of
    tests/fe/test_inelastic_edge.py) pressed to 20 times its critical interference (Hertz
    first yield, p0 = 1.6 Y) at `standard` and at `fine`: the CPU time of fine over that of
    standard (issue #51: at most 5)."""
    from asperity.fe import J2Plasticity, Sphere, solve_asperity_history
    from asperity.fe.drivers.inelastic import History

    E, nu = 1000.0, 0.3
    Y = E / 400
    w_c = (np.pi * 1.6 * Y / (2 * E / (1 - nu**2))) ** 2
    cpu, steps = {}, {}
    for preset in ("standard", "fine"):
        t0 = time.process_time()
        ds = solve_asperity_history(Sphere(1.0), J2Plasticity(E, nu, Y), History.loading(20 * w_c, 1.0),
                                    accuracy=preset)
        cpu[preset], steps[preset] = time.process_time() - t0, int(ds.attrs["steps"])
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


#: case -> (script in benchmarks/, its arguments when ARGS is empty, what it measures);
#: CORES (the Makefile's) is the number of cores of the workflow runs
_CORES = os.environ.get("CORES", "2")
STUDIES = {
    "scenes": ("scenes.py", ["--accuracy", "standard", "--cores", _CORES, "--full"],
               "wall time of each scene from an empty copy, then of the whole default run"),
    "profile": ("profile_run.py", ["--accuracy", "draft", "--cores", _CORES],
                "where a whole run's wall time goes: start-up, imports, assembly, solves, I/O, figures"),
    "jobs": ("job_overhead.py", ["--cores", _CORES],
             "what a job pays before it computes: Snakemake per script job, each script's imports"),
    "adhesion": ("adhesion_cost.py", [], "CPU time of the adhesive jobs"),
    "plane-strain": ("plane_strain.py", ["--sensitivity", "--finite-strain", "--unloading"],
                     "numbers and CPU time of the plane-strain scenes at every preset"),
    "reference": ("reference_cost.py", ["--accuracy", "draft", "--cores", _CORES],
                  "the deterministic_reference scene: wall time, the routes' errors"),
    "routes": ("routes.py", [], "every route's error on every map against the boundary elements"),
    "scale": ("scale_study.py", [], "summits and the routes' error against the lateral scale"),
    "j2-sphere": ("j2_sphere.py", [], "the J2 sphere beside Kogut and Etsion's fits and the "
                  "hardness-limited boundary elements"),
    "sliding": ("sliding_convergence.py", [], "the sliding study at draft, standard and fine"),
    "linear": ("linear_solvers.py", [], "SuperLU against PARDISO on the 3-D asperity's tangents"),
    "remesh": ("remesh.py", ["--remesh", "on", "off"],
               "inelastic histories on meshes that follow the contact"),
    "edge-band": ("edge_band_scene.py", ["--scene", "steel_glass_bead", "--accuracy", "standard"],
                  "a scene's FE jobs without and with the plastic edge band"),
    "finite-strain": ("finite_strain.py", [], "finite against small strain: CPU, force, area"),
    "surface": ("surface_speed.py", [], "a 2048^2 map's statistics beside SurfaceTopography's"),
    "validity": ("validity_numbers.py", [], "how much of the FE scenes rests on extrapolation"),
    "coupled": ("coupled_numbers.py", [], "the coupled hill family beside the representative hill"),
    "adhesion-scene": ("adhesion_numbers.py", [], "the adhesive scene beside its elastic twin"),
    "adhesion-secant": ("adhesion_secant.py", [], "the adhesive step test in contact"),
}


def run_case(case: str, args: list[str]) -> int:
    """Run one case (module docstring); the exit code of its script."""
    if case == "kernels":
        main(args)
        return 0
    if case == "list":
        print(f"{'kernels':<14s} the kernels' speed against the issues' targets (default)")
        for name, (_, _, what) in STUDIES.items():
            print(f"{name:<14s} {what}")
        return 0
    if case not in STUDIES:
        print(f"make bench: no case {case!r} (key CASE); one of kernels, {', '.join(STUDIES)}",
              file=sys.stderr)
        return 2
    script, default, _ = STUDIES[case]
    command = [sys.executable, str(Path(__file__).with_name(script)), *(args or default)]
    print(" ".join(command), flush=True)
    return subprocess.call(command)


def main(names=None):
    OUT.mkdir(exist_ok=True)
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
    record = {"machine": platform.platform(), "python": sys.version.split()[0],
              "processor": platform.processor() or platform.machine(), "cases": rows}
    (OUT / "results.json").write_text(json.dumps(record, indent=2))
    print(f"written {OUT / 'results.json'}")


if __name__ == "__main__":
    argv = sys.argv[1:]
    sys.exit(run_case(argv[0] if argv else "kernels", argv[1:]))
