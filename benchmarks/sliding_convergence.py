"""Convergence of the sliding study `asperity_sliding` (`make bench CASE=sliding`).

Runs the scene's 3-D asperity (report 9.2: pressed 0.125 um in 0-1800 s, slid 1.0 um
in 1800-4000 s with a friction coefficient of 20) at the sliding presets, one process
per preset (one BLAS thread, `nice`), and compares:

* the normal and tangential force histories of each preset with the next finer one,
  over the pressing phase (0 < t <= 1800 s) and the sliding phase (t > 1800 s): for
  presets with the same steps (as `standard` and `fine`: every run's steps land on the
  times of `flat_motion.step_grid`, the same for both) at the step times both runs reached,
  else the finer history interpolated linearly in time onto the coarser one's step
  times (``compared_at``); the largest difference divided by the largest force of the finer
  run in that phase ("largest relative difference"); also the difference of the phase
  means over those times;
* what each run costs (dofs, steps, cuts, Newton iterations, CPU time);
* the mean tangential traction while sliding, F_T / A, A the contact area of the
  model (quadrature weights of the contact points with a positive pressure), next to
  the shear flow stress k = q / sqrt 3 of the Bodner-Partom steel at its saturated
  hardness Z1, which bounds any shear traction the bulk can carry, and to the
  report's 64 MPa;
* how the forces scatter while sliding: the step-to-step changes, and the steps
  whose tangential force is zero although the flat touches (the junction released).

A preset that did not finish within ``--timeout`` is compared over the part of the
history it reached (from its log).  Writes benchmarks/results/sliding-convergence.json
and prints a table.  Nothing is asserted here.

    python benchmarks/sliding_convergence.py                         # draft, standard, fine
    python benchmarks/sliding_convergence.py --presets draft standard
    python benchmarks/sliding_convergence.py --reuse                 # compare the runs in --out
    python benchmarks/sliding_convergence.py --presets draft --out /tmp/s --results /tmp/s.json

``--study``: what moves the sliding forces.  The runs of `STUDY` (the standard
preset of before the presets changed, `STUDY_STANDARD`, with one thing changed at a
time: the time controls, the penalty, each of the mesh sizes, and the whole mesh
scaled; and `fine` of before), each stopped once the flat
has slid ``--until`` (default 0.08 um, past the fall of F_N), are compared with
the finest mesh of the study over the sliding they share, and with `standard`.
Runs that stall (Newton failing again and again, the step cut to microseconds) are
stopped after ``--timeout`` seconds and compared over what they reached.  Writes
benchmarks/results/sliding-study.json::

    python benchmarks/sliding_convergence.py --study --jobs 2 --timeout 1800

Each run's log carries the critical friction coefficient of the junction where sliding
starts and after every sliding step (`SlidingModel.critical_factor`); the tables report
it at the start, and the smallest (and median) while sliding.  ``--coefficient mu``
or ``--shear-strength k`` [MPa] replace the report's mu = 20 (3.21: c1 = mu, or c0 = k
ramped in over 0-2k; k = 280 is the scene `asperity_sliding_junction`),
with their own --out and results (``-mu<mu>``, ``-k<k>`` added to the names)::

    python benchmarks/sliding_convergence.py --coefficient 1 --jobs 2
    python benchmarks/sliding_convergence.py --study --coefficient 1 --until 1.0

``--standard-tip f`` runs the preset ``standard`` with its finest edge (``tip_fraction``)
f r instead of its own, the rest of the preset unchanged: what a finer `standard` would
change against `fine` (README, the junction's tables)::

    python benchmarks/sliding_convergence.py --shear-strength 280 --standard-tip 0.21 --jobs 2
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # run as a script: `benchmarks` importable
SCENE = "asperity_sliding"
RESULTS = Path(__file__).with_name("results")
OUT = Path(__file__).with_name("out") / "sliding"
STEP = re.compile(r"step (\d+): t = (\S+)(?: of \S+)? s, w = (\S+) m, delta = (\S+) m, "
                  r"F_N = (\S+) N, F_T = (\S+) N(?:, A = (\S+) m\^2)?")
REPORT_TRACTION = 64e6           # Pa, report 9.2

#: the sliding presets the study was made on, kept as they were: `standard` then had
#: a coarser mesh (4.3 k dofs) and `fine` the mesh `standard` had before a75dc29 (13 k
#: dofs); both refine a ball about the apex (depth_grading None)
STUDY_STANDARD = dict(tip_fraction=0.75, refine_fraction=0.5, grading=0.7, coarse_fraction=0.5,
                      depth_grading=None,
                      normal_steps=8, tangential_steps=16, tolerance=1e-7, max_iterations=40,
                      max_cuts=10, max_inelastic_step=1.0)
STUDY_FINE = dict(tip_fraction=0.5, refine_fraction=0.8, grading=0.5, coarse_fraction=0.35,
                  depth_grading=None,
                  normal_steps=16, tangential_steps=32, tolerance=1e-8, max_iterations=40,
                  max_cuts=10, max_inelastic_step=0.1)
#: ``--study``: name -> (preset, overrides of the scene's ``sliding`` section).  The
#: mesh scale s multiplies the lengths of the study's standard mesh (tip_fraction 0.75,
#: grading 0.7, coarse_fraction 0.5) with the finest region over 0.8 r (fine's).
STUDY = {
    "standard": (STUDY_STANDARD, {}),
    "time steps of fine": (STUDY_STANDARD, {"steps": {"normal": 16, "tangential": 32},
                                            "max_inelastic_step": 0.1}),
    "penalty factor 10": (STUDY_STANDARD, {"penalty_factor": 10.0}),
    "tip 0.5 r": (STUDY_STANDARD, {"mesh": {"tip_fraction": 0.5}}),
    "finest region 0.8 r": (STUDY_STANDARD, {"mesh": {"refine_fraction": 0.8}}),
    "grading 0.5": (STUDY_STANDARD, {"mesh": {"grading": 0.5}}),
    "coarse 0.35": (STUDY_STANDARD, {"mesh": {"coarse_fraction": 0.35}}),
    "mesh scale 0.7": (STUDY_STANDARD, {"mesh": {"tip_fraction": 0.525, "grading": 0.49,
                                                 "coarse_fraction": 0.35,
                                                 "refine_fraction": 0.8}}),
    "fine": (STUDY_FINE, {}),
    "mesh scale 0.5": (STUDY_STANDARD, {"mesh": {"tip_fraction": 0.375, "grading": 0.35,
                                                 "coarse_fraction": 0.25,
                                                 "refine_fraction": 0.8}}),
}


def scene() -> dict:
    """The scene, validated against the workflow's schema (defaults filled in)."""
    import yaml
    from snakemake.utils import validate

    sc = yaml.safe_load((ROOT / "config" / "scenes" / f"{SCENE}.yaml").read_text())
    config = {"scenes": [SCENE], "accuracy": "draft", "results": "results",
              "scene_dir": str(ROOT / "config" / "scenes"), "scene_definitions": {SCENE: sc}}
    validate(config, str(ROOT / "config" / "schema.yaml"))
    return sc


# ---------------------------------------------------------------------------- one preset
def patch_diagnostics(tn, tx, vw, x, facets, fw, stress, dv, before=None) -> dict:
    """The contact patch of one step against the stresses under it.

    tn, tx (nV,): pressure and x traction at the contact nodes; vw (nV,) their
    weights; x (nV,) their x; facets (6, nf) the nodes of each contact facet, fw
    (nf,) the facets' areas; stress (6, nf, nqv) at the volume points of the elements
    of the contact facets, dv (nf, nqv) their volume weights; before (nV,): which
    nodes touched in the step before.  Areas are of the whole model (twice the
    half).  The touching facets have a touching node; the bulk shear stress under
    the patch is sigma_xz in their elements: its largest value and its volume mean.
    """
    on = tn > 0
    changes = {} if before is None else dict(entered=int(np.sum(on & ~before)),
                                             left=int(np.sum(before & ~on)))
    if not on.any():
        return dict(points=0, facets=0, **changes)
    fac = on[facets].any(axis=0)
    sx, sy, sz, sxy, sxz, syz = stress[:, fac]
    q = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                + 3.0 * (sxy ** 2 + sxz ** 2 + syz ** 2))
    return dict(points=int(on.sum()), facets=int(fac.sum()), **changes,
                area_of_touching_facets=2.0 * float(fw[fac].sum()),
                largest_point_tangential_traction=float(np.abs(tx[on]).max()),
                largest_patch_shear_stress=float(np.abs(sxz).max()),
                mean_patch_shear_stress=float(np.sum(sxz * dv[fac]) / np.sum(dv[fac])),
                largest_patch_mises_stress=float(q.max()),
                x_touching=[float(x[on].min()), float(x[on].max())])


def _hook_diagnostics(path: Path):
    """Write `patch_diagnostics` of every recorded step to `path` (one JSON a line)."""
    from asperity.fe.drivers.sliding_model import SlidingModel

    record = SlidingModel.record
    sink = open(path, "w")
    last = {}

    def recorded(self, u, w, delta, out):
        rec = record(self, u, w, delta, out)
        m, c = self.m, out["contact"]
        d = patch_diagnostics(c["tn"], c["txy"][0], m.vw, m.vX[0], m.vfacets, m.cw.sum(axis=1),
                              out["stress"][:, m.ctind], m.weights[m.ctind],
                              last.get("touching"))
        last["touching"] = c["tn"] > 0
        sink.write(json.dumps(dict(d, normal_displacement=w, tangential_displacement=delta,
                                   tangential_force=rec["tangential_force"],
                                   contact_area=rec["contact_area"])) + "\n")
        sink.flush()
        return rec

    SlidingModel.record = recorded


class _Reached(Exception):
    """The flat has slid as far as the run was asked to go (``--until``)."""


def slug(name: str) -> str:
    """A run's file name: the preset, or a `STUDY` name with its blanks as _."""
    return name.replace(" ", "_")


def study_section(section: dict, overrides: dict) -> dict:
    """The scene's ``sliding`` section with `overrides` (``mesh`` and ``steps`` merged)."""
    out = dict(section)
    for k, v in overrides.items():
        out[k] = {**(out.get(k) or {}), **v} if isinstance(v, dict) else v
    return out


def sliding(sc: dict, overrides: dict):
    """The scene's `Sliding` section with `overrides` (`study_section`)."""
    from asperity.scene import Sliding, Units

    return Sliding.from_section(study_section(sc["sliding"], overrides),
                                Units.from_section(sc["units"]))


def worker(name: str, out: Path, until: float | None = None,
           law: dict | None = None, study: bool = False,
           standard_tip: float | None = None) -> None:
    """Run the scene at preset `name` (with `study`, the `STUDY` run `name`); progress lines to
    out/<name>.log, the dataset to out/<name>.nc (with its CPU time), the contact
    patch of every step to out/<name>.patch.jsonl.  With `until` [m] the run stops
    after the first step that has slid that far (its log is the history); `law`
    replaces the junction's shear resistance (`shear_law`); `standard_tip` the
    ``tip_fraction`` of the preset ``standard`` (an experiment on its finest edge)."""
    from asperity.stages.sliding import sliding_dataset

    sc = scene()
    preset, overrides = STUDY[name] if study else (name, {})
    if law is not None:
        overrides = dict(overrides, shear_resistance=law)
    if standard_tip is not None and name == "standard":
        overrides = dict(overrides, mesh={"tip_fraction": standard_tip})
    section = study_section(sc["sliding"], overrides)
    _hook_diagnostics(out / f"{slug(name)}.patch.jsonl")
    log = open(out / f"{slug(name)}.log", "w")
    t0, c0 = time.perf_counter(), time.process_time()

    def say(s):
        m = STEP.search(s)
        cpu = f" ({time.process_time() - c0:.1f} s CPU)" if m else ""
        log.write(f"[{time.perf_counter() - t0:9.1f} s] {s}{cpu}\n")
        log.flush()
        if until is not None and m and float(m.group(4)) >= until * (1 - 1e-9):
            raise _Reached

    try:
        ds = sliding_dataset(SCENE, section, sc["units"], preset, progress=say)
    except RuntimeError as err:
        if not isinstance(err.__cause__, _Reached):
            raise
        log.write(f"reached: {time.process_time() - c0:.1f} s CPU\n")
        return
    ds.attrs["cpu_time"] = time.process_time() - c0
    ds.attrs["wall_time"] = time.perf_counter() - t0
    say(f"done: {ds.attrs['cpu_time']:.1f} s CPU")
    save(ds, out / f"{slug(name)}.nc")


def save(ds: xr.Dataset, path: Path) -> None:
    """The dataset as netCDF (the step phases as strings, no booleans or None)."""
    ds = ds.copy()
    ds["phase"] = ds["phase"].astype(str)
    for k, v in list(ds.attrs.items()):
        if isinstance(v, (bool, np.bool_)):
            ds.attrs[k] = int(v)
        elif v is None:
            del ds.attrs[k]
    ds.to_netcdf(path)


def run(presets, out: Path, timeout: float, jobs: int, until: float | None = None,
        flags: list[str] | None = None, study: bool = False) -> None:
    """The presets (or `STUDY` runs) in child processes, at most `jobs` at a time,
    finest first (it has the most time), with the law's `flags` (`shear_law`); a child
    past `timeout` seconds is stopped (its log stays)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
               PYTHONPATH=str(ROOT / "src") + os.pathsep + os.environ.get("PYTHONPATH", ""))
    rank = ["mesh scale 0.5", "fine", "mesh scale 0.7", "standard", "draft"]  # costliest first
    order = sorted(presets, key=lambda p: rank.index(p) if p in rank else len(rank))
    running: list[tuple[str, subprocess.Popen, float]] = []
    while order or running:
        while order and len(running) < jobs:
            p = order.pop(0)
            (out / f"{slug(p)}.nc").unlink(missing_ok=True)
            cmd = ["nice", "-n", "15", sys.executable, __file__, "--worker", p, "--out", str(out)]
            if until is not None:
                cmd += ["--until", repr(until / 1e-6)]
            cmd += (flags or []) + (["--study"] if study else [])
            running.append((p, subprocess.Popen(cmd, env=env), time.perf_counter()))
        time.sleep(2.0)
        for item in list(running):
            p, proc, t0 = item
            if proc.poll() is not None:
                running.remove(item)
                if proc.returncode:
                    print(f"{p}: exited with {proc.returncode} (see {out / (slug(p) + '.log')})")
            elif time.perf_counter() - t0 > timeout:
                proc.terminate()
                proc.wait()
                running.remove(item)
                print(f"{p}: stopped after {timeout:.0f} s; compared over what it reached")


# ------------------------------------------------------------------------------ compare
def critical_coefficients(text: str) -> dict:
    """The critical friction coefficients of the sliding junction a log reports
    (`SlidingModel.critical_factor`; inf: none; None: not reported): where sliding
    starts, and the smallest and the median over the sliding steps.  For a law that
    is not Coulomb's, the factor of its shear resistance instead, as the log words it."""
    value = r"(?:a friction coefficient (\S+)|(\S+) times the shear resistance)"
    start = re.search(rf"turns singular at {value}$|(stays regular)", text, flags=re.M)
    steps = [math.inf if m.group(3) else float(m.group(1) or m.group(2)) for m in re.finditer(
        rf"cuts, critical: (?:{value}|(none))", text)]
    return dict(critical_friction_coefficient=None if start is None else
                math.inf if start.group(3) else float(start.group(1) or start.group(2)),
                smallest_critical_friction_coefficient_sliding=min(steps) if steps else None,
                median_critical_friction_coefficient_sliding=(
                    float(np.median(steps)) if steps else None))


def history(preset: str, out: Path) -> dict | None:
    """A run's history: from its dataset when it finished, else from its log."""
    h = _history(preset, out)
    log = out / f"{slug(preset)}.log"
    if h is not None and log.exists():
        h.update(critical_coefficients(log.read_text()))
    return h


def _history(preset: str, out: Path) -> dict | None:
    nc = out / f"{slug(preset)}.nc"
    if nc.exists():
        with xr.open_dataset(nc) as ds:
            ds = ds.load()
        h = {k: ds[k].values.astype(float) for k in
             ("time", "normal_force", "tangential_force", "contact_area", "newton_iterations",
              "step_cuts")}
        h["phase"] = ds["phase"].values.astype(str)
        a = ds.attrs
        h.update(completed=bool(a["completed"]), stop_reason=str(a.get("stop_reason", "")),
                 dofs=int(a["dofs"]), steps=int(a["steps"]),
                 cuts=int(a["total_step_cuts"]), newton=int(a["total_newton_iterations"]),
                 steps_through_slip=int(a.get("steps_through_slip", 0)),
                 cpu_time=float(a["cpu_time"]), contact_facets=int(a["contact_facets"]),
                 tip_element_size=float(a["tip_element_size"]),
                 largest_deformation=str(a["largest_deformation"]),
                 largest_inelastic_strain=float(ds["max_inelastic_strain"].values[-1]))
        return h
    log = out / f"{slug(preset)}.log"
    if not log.exists():
        return None
    text = log.read_text()
    rows = [tuple(float(x) if x is not None else math.nan for x in m.groups()[1:])
            for m in map(STEP.search, text.splitlines()) if m]
    dofs = re.search(r"mesh: \d+ tetrahedra, (\d+) dofs", text)
    wall = re.findall(r"^\[\s*([0-9.]+)\s*s\]", text, flags=re.M)
    cpu = re.findall(r"\(([0-9.]+) s CPU\)$|^reached: ([0-9.]+) s CPU", text, flags=re.M)
    if not rows:
        return None
    r = np.array([(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)] + rows)
    h = dict(time=r[:, 0], normal_force=r[:, 3], tangential_force=r[:, 4],
             phase=np.where(r[:, 2] > 0, "sliding", "normal"), completed=False,
             dofs=int(dofs.group(1)) if dofs else None, steps=len(rows),
             wall_time_reached=float(wall[-1]) if wall else None,
             cuts=len(re.findall(r": cut to dt", text)),
             steps_through_slip=len(re.findall(r", through the slip in \d+ damped solves", text)),
             stopped=not re.search(r"^reached:", text, flags=re.M))
    if cpu:  # the last step's, or where the run stopped (--until)
        h["cpu_time"] = float(cpu[-1][0] or cpu[-1][1])
    if np.all(np.isfinite(r[:, 5])):
        h["contact_area"] = r[:, 5]
    return h


def compare(coarse: dict, fine: dict, same_steps: bool = False) -> dict:
    """Largest differences of the force histories (module docstring): at the step times
    both runs reached if they have `same_steps` (the same step grid), else the finer
    history interpolated onto the coarser one's step times."""
    out = {}
    t_end = fine["time"][-1]
    for name in ("normal_force", "tangential_force"):
        for ph, lo, hi in (("pressing", 0.0, 1800.0), ("sliding", 1800.0, math.inf)):
            tc = coarse["time"]
            sel = (tc > lo) & (tc <= min(hi, t_end) * (1 + 1e-12))
            tf = fine["time"]
            fsel = (tf > lo - 1e-9) & (tf <= hi)
            at = "finer run interpolated"
            if same_steps:  # the times both runs reached
                i = np.clip(np.searchsorted(tf, tc), 1, tf.size - 1)
                sel &= np.minimum(np.abs(tf[i] - tc), np.abs(tf[i - 1] - tc)) <= (
                    1e-9 * np.maximum(np.abs(tc), 1.0))
                at = "shared step times"
            if not sel.any() or fsel.sum() < 2:
                continue
            ff = np.interp(tc[sel], tf, fine[name])
            fc = coarse[name][sel]
            peak = float(np.abs(fine[name][fsel & (tf > lo)]).max())
            key = f"{name}_{ph}"
            scale_n = float(np.abs(fine["normal_force"][fsel & (tf > lo)]).max())
            if name == "tangential_force" and peak < 1e-4 * scale_n:
                # zero by symmetry while pressing: its size against the normal force
                out[key] = dict(zero_by_symmetry=True,
                                largest_over_normal_force=float(max(
                                    np.abs(fc).max(), np.abs(ff).max()) / scale_n))
                continue
            out[key] = dict(
                largest_relative_difference=(float(np.abs(fc - ff).max() / peak)
                                             if peak > 0 else None),
                at_time=float(tc[sel][int(np.argmax(np.abs(fc - ff)))]),
                mean_coarse=float(fc.mean()), mean_fine=float(ff.mean()),
                relative_difference_of_means=(float(fc.mean() / ff.mean() - 1)
                                              if ff.mean() else None),
                compared_up_to=float(tc[sel][-1]), points=int(sel.sum()), compared_at=at)
    return out


def sliding_summary(h: dict) -> dict:
    """End of pressing and the sliding phase of one run; tractions are means over the
    sliding steps with contact of F_T / A (A the model's contact area)."""
    s = (h["phase"] == "sliding") & (h["time"] > 1800.0)
    if not s.any():
        return {}
    fn, ft = h["normal_force"][s], h["tangential_force"][s]
    press = h["time"] <= 1800.0

    def step_change(f):
        return float(np.abs(np.diff(f)).max() / max(abs(f.mean()), 1e-300)) if f.size > 1 else None

    d = dict(
        normal_force_end_of_pressing=float(h["normal_force"][press][-1]),
        mean_normal_force_sliding=float(fn.mean()), mean_tangential_force_sliding=float(ft.mean()),
        largest_step_change_normal_force=step_change(fn),
        largest_step_change_tangential_force=step_change(ft),
        sliding_steps=int(s.sum()),
        steps_without_tangential_force=int(np.sum((ft == 0.0) & (fn > 0))),
        sliding_reached=float(h["time"][s][-1]))
    if "contact_area" in h:
        a = h["contact_area"]
        on = s & (a > 0)
        engaged = on & (h["tangential_force"] > 0)
        tau = h["tangential_force"] / np.where(a > 0, a, 1.0)
        d.update(
            contact_area_end_of_pressing=float(a[press][-1]),
            mean_pressure_end_of_pressing=float(h["normal_force"][press][-1] / a[press][-1]),
            mean_contact_area_sliding=float(a[on].mean()),
            mean_tangential_traction_sliding=float(tau[on].mean()),
            largest_tangential_traction_sliding=float(tau[on].max()),
            mean_tangential_traction_sliding_engaged=(float(tau[engaged].mean())
                                                      if engaged.any() else None),
            tangential_traction_on_end_of_pressing_area=float(
                h["tangential_force"][on].mean() / a[press][-1]))
    return d


def patch_summary(preset: str, out: Path) -> dict:
    """Over the sliding steps with contact: the patch in facets, the largest traction at a
    contact point, the largest shear and Mises stress in the patch's elements, F_T over
    the whole area of the facets that touch, where the touching points lie."""
    path = out / f"{slug(preset)}.patch.jsonl"
    if not path.exists():
        return {}
    rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    press = [r for r in rows if r["tangential_displacement"] == 0 and r["points"]]
    slide = [r for r in rows if r["tangential_displacement"] > 0 and r["points"]]
    if not slide:
        return {}
    tau_f = [r["tangential_force"] / r["area_of_touching_facets"] for r in slide]
    moved = [r for r in slide if r.get("entered", 0) + r.get("left", 0) > 0]
    return dict(
        sliding_steps_with_points_entering_or_leaving=len(moved) if "entered" in slide[0]
        else None,
        contact_points_sliding=[min(r["points"] for r in slide), max(r["points"] for r in slide)],
        patch_facets_sliding=[min(r["facets"] for r in slide), max(r["facets"] for r in slide)],
        patch_facets_pressing_end=press[-1]["facets"] if press else None,
        largest_point_tangential_traction_sliding=max(
            r["largest_point_tangential_traction"] for r in slide),
        largest_patch_shear_stress_sliding=max(r["largest_patch_shear_stress"] for r in slide),
        mean_patch_shear_stress_sliding=[min(r["mean_patch_shear_stress"] for r in slide),
                                         max(r["mean_patch_shear_stress"] for r in slide)],
        largest_patch_mises_stress_sliding=max(r["largest_patch_mises_stress"] for r in slide),
        tangential_force_over_touching_facets_sliding=[min(tau_f), max(tau_f)],
        x_touching_first_sliding_step=slide[0]["x_touching"],
        x_touching_last_step=slide[-1]["x_touching"])


def shear_flow_stress(sc: dict) -> dict:
    """k = q / sqrt 3 at Z = Z1 (saturated) from p_dot = (2 / sqrt 3) D0 exp[-1/2 (Z/q)^(2n)]."""
    m = sc["sliding"]["material"]
    D0, n, Z1 = float(m["D0"]), float(m["n"]), float(m["Z1"]) * 1e6
    out = {}
    for rate in (1e-4, 1e-3, 1e-2, 1e-1, 1.0):
        q = Z1 / (2.0 * math.log(2.0 / math.sqrt(3.0) * D0 / rate)) ** (1.0 / (2.0 * n))
        out[f"{rate:g}"] = q / math.sqrt(3.0)
    return out


def study(out: Path, until: float, path: Path) -> dict:
    """`STUDY`: each run's cost and forces along the sliding, and its largest
    differences from the finest mesh and from `standard` (`compare`)."""
    sc = scene()
    mo = sc["sliding"]["motion"]
    (s0, s1), slide = mo["slide_time"], mo["slide"] * 1e-6
    runs = {name: history(name, out) for name in STUDY}
    done = {k: v for k, v in runs.items() if v is not None}
    ref = next((k for k in ("mesh scale 0.5", "mesh scale 0.7", "fine") if k in done), None)
    at = [x for x in (0.02e-6, 0.04e-6, 0.06e-6) if x < until] + [until]
    res = dict(scene=SCENE, slid=until, finest=ref, slid_at=at, runs={})
    for name, h in runs.items():
        if h is None:
            res["runs"][name] = dict(missing=True)
            continue
        t = [s0 + (s1 - s0) * d / slide for d in at]
        info = dict(preset=STUDY[name][0], overrides=STUDY[name][1], dofs=h.get("dofs"),
                    steps=h["steps"], cuts=h.get("cuts"), cpu_time=h.get("cpu_time"),
                    wall_time=h.get("wall_time_reached"), stopped=h.get("stopped", False),
                    **{k: h.get(k) for k in critical_coefficients("")},
                    slid=float(np.interp(
                        h["time"][-1], [s0, s1], [0.0, slide])),
                    normal_force=[float(np.interp(x, h["time"], h["normal_force"]))
                                  if x <= h["time"][-1] * (1 + 1e-9) else None for x in t],
                    tangential_force=[float(np.interp(x, h["time"], h["tangential_force"]))
                                      if x <= h["time"][-1] * (1 + 1e-9) else None for x in t])
        for other, key in ((ref, "against_finest"), ("standard", "against_standard")):
            if other in done and other != name:
                c = compare(h, done[other])
                info[key] = {k: c[k]["largest_relative_difference"] for k in
                             ("normal_force_sliding", "tangential_force_sliding") if k in c}
        res["runs"][name] = info
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(res, indent=1, default=float) + "\n")
    print(f"slid {until / 1e-6:.3f} um; F_N, F_T in mN at slides of "
          + ", ".join(f"{x / 1e-6:.2f}" for x in at) + f" um; differences from {ref!r}")
    for name, i in res["runs"].items():
        if i.get("missing"):
            print(f"{name:20s} missing")
            continue
        f = lambda v: " ".join("   -  " if x is None else f"{1e3 * x:6.3f}" for x in v)  # noqa: E731
        d = i.get("against_finest", {})
        cost = (f"{i['cpu_time']:6.0f} s CPU" if i["cpu_time"] is not None
                else f"{i['wall_time'] or float('nan'):6.0f} s wall") + (
                    ", stopped" if i["stopped"] else "")
        print(f"{name:20s} {i['dofs'] or 0:6d} dofs {i['steps']:4d} steps {i['cuts'] or 0:3d} cuts "
              f"{cost} to {i['slid'] / 1e-6:.3f} um | mu_c "
              f"{i['critical_friction_coefficient'] or float('nan'):6.3g} (sliding: smallest "
              f"{i['smallest_critical_friction_coefficient_sliding'] or float('nan'):6.3g}) | "
              f"F_N {f(i['normal_force'])} | "
              f"F_T {f(i['tangential_force'])} | "
              + " ".join(f"{100 * v:5.1f} %" for v in d.values()))
    print(f"wrote {path}")
    return res


def stalls(names, out: Path, law: dict | None, study: bool) -> list:
    """Per run log in `out`: the longest streak of accepted steps that each advanced less
    than `solid3d.STALL_FRACTION` of their segment's step cap (STALL_STEPS of them stop a
    run), the step where it ended, and how the run ended (finished, reached its --until,
    or stopped: by hand, --timeout or a stall)."""
    from asperity.fe.drivers.flat_motion import step_caps
    from asperity.fe.drivers.solid3d import STALL_FRACTION

    sc = scene()
    rows = []
    for name in names:
        log = out / f"{slug(name)}.log"
        if not log.exists():
            continue
        preset, overrides = STUDY[name] if study else (name, {})
        if law is not None:
            overrides = dict(overrides, shear_resistance=law)
        s = sliding(sc, overrides)
        motion = s.motion()
        caps = step_caps(motion, s.preset(preset))
        text = log.read_text()
        t = np.array([motion.start] + [float(m.group(2)) for m in STEP.finditer(text)])
        slow = np.diff(t) < STALL_FRACTION * np.array([caps[motion.segment(x)] for x in t[:-1]])
        longest = end = run = 0
        for k, flag in enumerate(slow, start=1):
            run = run + 1 if flag else 0
            if run > longest:
                longest, end = run, k
        rows.append(dict(run=name, steps=int(slow.size), longest_slow_streak=longest,
                         ending_at_step=end,
                         end=("finished" if t[-1] >= motion.end * (1 - 1e-9) else
                              "reached its --until" if re.search(r"^reached:", text, flags=re.M)
                              else "stopped")))
    return rows


def shear_law(coefficient: float | None, strength: float | None):
    """The scene's ``shear_resistance`` replaced by a friction coefficient or a constant
    shear strength [MPa] (report 3.21: c1 = mu, or c0 = k ramped in over the pressures
    0-2k, as in `asperity_sliding_junction`): (law or None, the worker's flags, the tag
    of the output names)."""
    if coefficient is not None:
        return (dict(c0=0.0, c1=coefficient, c2=0.0), ["--coefficient", repr(coefficient)],
                f"-mu{coefficient:g}")
    if strength is not None:
        return (dict(c0=strength, c1=0.0, c2=0.0, onset_pressure=2.0 * strength),
                ["--shear-strength", repr(strength)],
                f"-k{strength:g}")
    return None, [], ""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--presets", nargs="+", default=["draft", "standard", "fine"])
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--timeout", type=float, default=3 * 3600.0, help="seconds per preset")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--reuse", action="store_true", help="compare the runs already in --out")
    ap.add_argument("--results", type=Path, help="default: results/sliding-convergence.json "
                    "(--study: sliding-study.json; -mu<mu> or -k<k> before .json)")
    ap.add_argument("--study", action="store_true",
                    help="the runs of STUDY to --until (writes sliding-study.json)")
    ap.add_argument("--until", type=float, help="stop each run once slid this far, um "
                    "(--study: 0.08)")
    other = ap.add_mutually_exclusive_group()
    other.add_argument("--coefficient", type=float, help="the junction's friction coefficient "
                       "instead of the report's 20 (runs in <out>-mu<mu>)")
    other.add_argument("--shear-strength", type=float, help="a junction of constant shear "
                       "strength c0 [MPa] instead of mu = 20 (runs in <out>-k<c0>)")
    ap.add_argument("--stalls", action="store_true", help="only report, per run log in --out, "
                    "the longest streak of steps under solid3d.STALL_FRACTION of their cap")
    ap.add_argument("--standard-tip", type=float, help="the finest edge of the preset standard "
                    "(tip_fraction, times r) instead of its own: an experiment (runs in "
                    "<out>-tip<f>)")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.study and a.until is None:
        a.until = 0.08
    until = None if a.until is None else a.until * 1e-6
    law, flags, tag = shear_law(a.coefficient, a.shear_strength)
    if a.standard_tip is not None:
        flags, tag = flags + ["--standard-tip", repr(a.standard_tip)], tag + f"-tip{a.standard_tip:g}"
    if a.out == OUT:
        a.out = OUT.with_name(("sliding-study" if a.study else "sliding") + tag)
    if a.results is None:
        a.results = RESULTS / (("sliding-study" if a.study else "sliding-convergence") + tag
                               + ".json")
    a.out.mkdir(parents=True, exist_ok=True)
    if a.worker:
        worker(a.worker, a.out, until, law, a.study, a.standard_tip)
        return 0
    if a.stalls:
        for r in stalls(list(STUDY) if a.study else a.presets, a.out, law, a.study):
            print(f"{a.out.name}/{slug(r['run'])}: {r['steps']} steps, longest streak under "
                  f"the stall fraction {r['longest_slow_streak']} (ending at step "
                  f"{r['ending_at_step']}), {r['end']}")
        return 0
    if a.study:
        if not a.reuse:
            run(list(STUDY), a.out, a.timeout, a.jobs, until, flags, study=True)
        study(a.out, until, a.results)
        return 0
    if not a.reuse:
        run(a.presets, a.out, a.timeout, a.jobs, until, flags)
    sc = scene()
    runs = {p: history(p, a.out) for p in a.presets}
    res = dict(scene=SCENE, report="9.2, Figs. 9.4, 9.5",
               report_mean_tangential_traction=REPORT_TRACTION,
               shear_flow_stress_at_Z1_by_inelastic_rate=shear_flow_stress(sc),
               presets={}, comparisons={})
    for p, h in runs.items():
        if h is None:
            res["presets"][p] = dict(missing=True)
            continue
        info = {k: v for k, v in h.items() if not isinstance(v, np.ndarray)}
        info["time_reached"] = float(h["time"][-1])
        info.update(sliding_summary(h))
        info.update(patch_summary(p, a.out))
        res["presets"][p] = info
    done = [p for p in a.presets if runs.get(p) is not None]
    s = sliding(sc, {})
    steps = {p: (s.preset(p)["normal_steps"], s.preset(p)["tangential_steps"]) for p in done}
    for c, f in zip(done, done[1:]):
        res["comparisons"][f"{c} vs {f}"] = compare(runs[c], runs[f], steps[c] == steps[f])
    path = a.results
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(res, indent=1, default=float) + "\n")

    print(f"{'preset':9s} {'dofs':>6s} {'steps':>5s} {'cuts':>4s} {'CPU s':>7s} {'reached s':>9s} "
          f"{'F_N press mN':>12s} {'F_T slide mN':>12s} {'tau MPa':>8s} {'F_T=0 steps':>11s} "
          f"{'mu_c':>6s} {'sliding: smallest, median':>25s}")
    for p, i in res["presets"].items():
        if i.get("missing"):
            print(f"{p:9s} missing")
            continue
        print(f"{p:9s} {i.get('dofs') or 0:6d} {i['steps']:5d} {i.get('cuts', 0):4d} "
              f"{i.get('cpu_time', float('nan')):7.0f} {i['time_reached']:9.0f} "
              f"{1e3 * i.get('normal_force_end_of_pressing', float('nan')):12.3f} "
              f"{1e3 * i.get('mean_tangential_force_sliding', float('nan')):12.3f} "
              f"{1e-6 * i.get('mean_tangential_traction_sliding', float('nan')):8.0f} "
              f"{i.get('steps_without_tangential_force', 0):11d} "
              f"{i.get('critical_friction_coefficient') or float('nan'):6.3g} "
              f"{i.get('smallest_critical_friction_coefficient_sliding') or float('nan'):12.3g} "
              f"{i.get('median_critical_friction_coefficient_sliding') or float('nan'):12.3g}")
    for pair, cmp_ in res["comparisons"].items():
        for k, v in cmp_.items():
            if v.get("zero_by_symmetry"):
                print(f"{pair:20s} {k:28s} zero by symmetry: |F_T| <= "
                      f"{v['largest_over_normal_force']:.1e} F_N")
                continue
            print(f"{pair:20s} {k:28s} largest {100 * v['largest_relative_difference']:6.1f} % "
                  f"(t = {v['at_time']:.0f} s), means "
                  f"{100 * v['relative_difference_of_means']:+6.1f} %, "
                  f"up to t = {v['compared_up_to']:.0f} s")
    k = res["shear_flow_stress_at_Z1_by_inelastic_rate"]
    print("shear flow stress k at Z1: "
          + ", ".join(f"{1e-6 * v:.0f} MPa at {r} 1/s" for r, v in k.items()))
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
