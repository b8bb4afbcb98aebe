"""CPU time of the adhesive asperity jobs (`make bench CASE=adhesion`).

The README's adhesion section quotes what the adhesive solver costs; this
script measures it (CPU time of this process, `time.process_time`):

1. the eight FE jobs of scene `smooth_aluminum_adhesion` (R = 300 to
   13.6 um at d = 0.3 nm), at `draft` (the scene's preset) and at
   `standard`.  Their specs come from the scene's plan, built by Snakemake
   in a fresh copy of the workflow;
2. `asperity.studies.adhesion.smooth_aluminum_curves` (Fig. 7.6: R = 15.4, 30,
   60 um at d = 0.3 nm), at draft, one radius at a time;
3. the flat end of report 7.3's range, R = 150 and 300 um at d = 0.3 nm
   (Tabor parameter 10 and 13), pressed to 10 nm, at draft
   and at standard: CPU time, the pull-off force against JKR's
   3/2 pi R W_c, the jump-off interference against JKR's, and the draft
   pull-off against standard's, and against the Maugis-Dugdale pull-off at
   lambda = 1.16 mu (`--compare` recomputes these comparisons alone), and
   the peak resident memory of the process after each run (``peak_rss_mb``,
   `resource.getrusage`: the run's own peak when it is the first, or only,
   run of its process, as with ``--only-large --radii R --accuracies A``; an
   upper bound otherwise);
4. ``--bands``: R = 150 um at draft on meshes whose fine band reaches from the
   contact edge to the cohesive zone (preset key ``edge_band`` off, the mesh of
   the code before) and on meshes with the contact edge in a band of its own
   (the default): CPU time, the median size of the Newton tangent's active set,
   and how far the second run's force and contact radius (on the first run's
   levels, away from its jumps), pull-off and jumps are from the first's;
5. ``--margins``: the same comparison between the following band's margins of
   the code before (0.15 times the radius the cohesive zone reaches, at least
   40 ring elements: preset keys ``follow_margin``, ``follow_margin_elements``)
   and the preset's (20 ring elements);
6. ``--follow``: the same comparison at R = 15.4 um between the whole band
   refined once (preset key ``follow_above`` raised out of reach) and the
   preset (a band of more than ``follow_above`` ring elements follows the
   contact), pressed to 79 nm as in the scene.

Writes benchmarks/results/adhesion-cost.json and prints a table.  Nothing
is asserted: speed is measured here, not in the tests.

    python benchmarks/adhesion_cost.py             # everything
    python benchmarks/adhesion_cost.py --no-curves # without part 2
    python benchmarks/adhesion_cost.py --no-large   # parts 1-2, part 3 kept
    python benchmarks/adhesion_cost.py --only-large # part 3 alone, the other
                                                    # parts kept from the JSON
    python benchmarks/adhesion_cost.py --only-large --radii 300 --accuracies draft
                                                    # one radius and preset: the other
                                                    # rows kept (such runs may go side
                                                    # by side)
    python benchmarks/adhesion_cost.py --bands      # part 4 alone, the rest kept
    python benchmarks/adhesion_cost.py --margins    # part 5 alone, the rest kept
    python benchmarks/adhesion_cost.py --follow     # part 6 alone, the rest kept
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import _commit, _env  # noqa: E402
from benchmarks.workflow_copy import SNAKEMAKE, copy_workflow  # noqa: E402

from asperity.population import samples  # noqa: E402
from asperity.fe import ConvergenceError  # noqa: E402
from asperity.fe import BodnerPartom, LennardJones, LinearElastic, Paraboloid  # noqa: E402
from asperity.fe.drivers import adhesive  # noqa: E402
from asperity.fe.solvers.adhesive import AdhesiveNewton  # noqa: E402
from asperity.population.kinds.adhesive import on_levels  # noqa: E402
from asperity.studies.adhesion import smooth_aluminum_curves  # noqa: E402
from asperity.references.adhesion import jkr_jump_off, maugis_pull_off  # noqa: E402

SCENE = "smooth_aluminum_adhesion"
ALLOY = BodnerPartom.aluminum_6061_t4()  # the aluminum of Fig. 7.6 (report 6.3.1)
RESULTS = Path(__file__).with_name("results")
#: part 3: report 7.3's flattest asperities [m]
LARGE_RADII = (150e-6, 300e-6)


def scene_specs() -> list[dict]:
    """The job specs of the scene's plan, flattest asperity first."""
    with tempfile.TemporaryDirectory(prefix="adhesion-cost-") as tmp:
        work = copy_workflow(Path(tmp))
        target = f"results/{SCENE}/plan.nc"
        subprocess.run([str(SNAKEMAKE), "--cores", "1", target], cwd=work, env=_env(),
                       check=True, capture_output=True, text=True)
        with xr.open_dataset(work / target) as plan:
            texts = sorted(set(str(s) for s in plan["spec"].values))
    return sorted((json.loads(t) for t in texts), key=lambda s: s["curvature"])


def timed(fn):
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


def job_row(spec: dict, accuracy: str) -> dict:
    s = dict(spec, accuracy=accuracy)
    ds, cpu = timed(lambda: samples.solve(s, "benchmark"))
    return dict(tip_radius_um=1e6 / s["curvature"], accuracy=accuracy, cpu_time_s=cpu,
                pull_off_force_N=float(ds.attrs["pull_off_force"]),
                tabor_parameter=float(ds.attrs["tabor_parameter"]))


def compared(rows: list[dict]) -> list[dict]:
    """The rows, each that finished with the Maugis-Dugdale pull-off at lambda = 1.16 mu
    (``maugis_pull_off_over_jkr``) and its own against it (``pull_off_over_maugis``), and
    each standard one with ``pull_off_draft_vs_standard`` (draft / standard - 1) where the
    same radius has a draft row."""
    pulls = {(r["tip_radius_um"], r["accuracy"]): r["pull_off_force_N"]
             for r in rows if "pull_off_force_N" in r}
    for r in rows:
        if "pull_off_over_jkr" in r:
            md = maugis_pull_off(1.16 * r["tabor_parameter"]) / 1.5
            r["maugis_pull_off_over_jkr"] = md
            r["pull_off_over_maugis"] = r["pull_off_over_jkr"] / md
    for r in rows:
        if r["accuracy"] == "standard" and (r["tip_radius_um"], "draft") in pulls \
                and "pull_off_force_N" in r:
            r["pull_off_draft_vs_standard"] = (pulls[(r["tip_radius_um"], "draft")]
                                               / r["pull_off_force_N"] - 1.0)
    return rows


def large_rows(radii=LARGE_RADII, accuracies=("draft", "standard"), done=None) -> list[dict]:
    """Part 3: R = 150, 300 um at d = 0.3 nm, draft and standard; `done(rows)`
    is called after each run (the JSON keeps what finished)."""
    rows = []
    for radius in radii:
        for accuracy in accuracies:
            t0 = time.process_time()
            try:
                ds = smooth_aluminum_curves(radii=(radius,), accuracy=accuracy)
            except ConvergenceError as exc:  # recorded: where and after how much CPU
                rows.append(dict(tip_radius_um=radius * 1e6, d_nm=0.3, accuracy=accuracy,
                                 cpu_time_s=time.process_time() - t0, failed=str(exc)))
                print(f"R = {radius * 1e6:.4g} um, {accuracy}: failed: {exc}", flush=True)
                if done is not None:
                    done(rows)
                continue
            cpu = time.process_time() - t0
            peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
            pull = float(ds["pull_off_force"][0])
            rows.append(dict(tip_radius_um=radius * 1e6, d_nm=0.3, accuracy=accuracy, cpu_time_s=cpu,
                             tabor_parameter=float(ds["tabor_parameter"][0]), pull_off_force_N=pull,
                             pull_off_over_jkr=pull / float(ds["pull_off_force_jkr"][0]),
                             jumps=int(ds["jump"].sum()), steps=int(ds["valid"].sum()),
                             step_cuts=int(np.nansum(ds["step_cuts"].values)),
                             peak_rss_mb=peak,
                             jump_off_interference_over_jkr=float(
                                 ds["jump_off_interference"][0] / jkr_jump_off(
                                     float(ds["tabor_parameter"][0]), 0.3e-9))))
            print(f"R = {radius * 1e6:.4g} um, {accuracy}: {cpu:.1f} s, pull-off "
                  f"{rows[-1]['pull_off_over_jkr']:.4f} JKR", flush=True)
            if done is not None:
                done(rows)
    return rows


def meshes_row(runs: dict, radius: float = 150e-6, w_max: float = 10e-9) -> dict:
    """Parts 4 to 6: the same path at draft on two meshes, ``runs`` = {name: preset
    overrides} (the reference first): CPU time, meshes, the median size of the
    Newton tangent's active set, and how far the second run's force and contact
    radius (on the first run's levels, away from its jumps), pull-off and jumps
    are from the first's."""
    out = {}
    for name, overrides in runs.items():
        sizes = []
        tangent = AdhesiveNewton.tangent

        def recorded(newton, *args, **kwargs):
            T = tangent(newton, *args, **kwargs)
            sizes.append(T.nodes.size)
            return T

        AdhesiveNewton.tangent = recorded
        try:
            ds, cpu = timed(lambda: adhesive.solve_asperity_adhesive(
                Paraboloid(radius), LinearElastic(ALLOY.E, ALLOY.nu),
                LennardJones(1.0, 0.3e-9), w_max=w_max,
                accuracy=dict(base="draft", **overrides)))
        finally:
            AdhesiveNewton.tangent = tangent
        out[name] = (ds, dict(overrides, cpu_time_s=cpu,
                              active_nodes_median=float(np.median(sizes)),
                              meshes=int(ds.attrs["meshes"]),
                              pull_off_force_N=float(ds.attrs["pull_off_force"])))
        print(f"R = {radius * 1e6:.4g} um draft, {name}: {cpu:.1f} s", flush=True)
    (ref, a), (new, b) = out.values()
    d = 0.3e-9
    diff = {}
    for var in ("force", "contact_radius"):
        worst = 0.0
        for x, y in on_levels(ref, new, var, 0.1 * d):
            ok = np.isfinite(x) & np.isfinite(y)
            worst = max(worst, float(np.max(np.abs(y[ok] - x[ok])) / np.max(np.abs(x[ok]))))
        diff[f"{var}_largest_difference_over_largest"] = worst
    diff["pull_off_relative_difference"] = b["pull_off_force_N"] / a["pull_off_force_N"] - 1.0
    for attr in ("jump_in_interference", "jump_off_interference"):
        diff[f"{attr}_difference_over_d"] = float(new.attrs[attr] - ref.attrs[attr]) / d
    return dict(tip_radius_um=radius * 1e6, d_nm=0.3, w_max_nm=w_max * 1e9, accuracy="draft",
                **{name: row for name, (_, row) in out.items()}, **diff)


#: part 4: one band from the contact edge (the code before) against the edge's own band
BANDS = {"one_band": dict(edge_band=False), "edge_band": dict(edge_band=True)}
#: part 5: the following band's margins of the code before against the preset's
MARGINS = {"wide_margins": dict(follow_margin=0.15, follow_margin_elements=40.0),
           "preset_margins": {}}
#: part 6: the whole band refined once against the preset's following mesh, at a
#: small tip of the scene (R = 15.4 um, 443 ring elements at draft pressed to 79 nm)
FOLLOW = {"whole_band": dict(follow_above=1e9), "following": {}}
FOLLOW_CASE = dict(radius=15.4e-6, w_max=79e-9)
#: parts 4-6, each run alone by its option: the runs compared and the case
MESH_PARTS = {"bands": (BANDS, {}), "margins": (MARGINS, {}), "follow": (FOLLOW, FOLLOW_CASE)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-curves", action="store_true", help="leave out smooth_aluminum_curves")
    ap.add_argument("--only-large", action="store_true",
                    help="run part 3 (R = 150, 300 um) alone; parts 1-2 are kept from --out")
    ap.add_argument("--no-large", action="store_true",
                    help="leave out part 3; its rows are kept from --out")
    ap.add_argument("--radii", type=float, nargs="+", default=[r * 1e6 for r in LARGE_RADII],
                    help="part 3's tip radii [um]")
    ap.add_argument("--accuracies", nargs="+", default=["draft", "standard"],
                    help="part 3's presets")
    ap.add_argument("--compare", action="store_true",
                    help="only recompute part 3's comparisons of the stored rows (no FE run)")
    ap.add_argument("--bands", action="store_true",
                    help="run part 4 alone (R = 150 um, one band against the edge's own); "
                         "the other parts are kept from --out")
    ap.add_argument("--margins", action="store_true",
                    help="run part 5 alone (R = 150 um, the margins of the code before "
                         "against the preset's); the other parts are kept from --out")
    ap.add_argument("--follow", action="store_true",
                    help="run part 6 alone (R = 15.4 um pressed to 79 nm, the whole band "
                         "against the following mesh); the other parts are kept from --out")
    ap.add_argument("--out", type=Path, default=RESULTS / "adhesion-cost.json")
    args = ap.parse_args(argv)
    alone = [key for key in MESH_PARTS if getattr(args, key)]
    if alone:
        commit, dirty = _commit()
        key = alone[0]
        runs, case = MESH_PARTS[key]
        row = dict(meshes_row(runs, **case), commit=commit, uncommitted_changes=dirty,
                   date=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
        record = json.loads(args.out.read_text())
        record[key] = row
        args.out.write_text(json.dumps(record, indent=1) + "\n")
        print(json.dumps(row, indent=1))
        print(f"written: {args.out}")
        return 0
    if args.compare:
        record = json.loads(args.out.read_text())
        record["large_radii"] = compared(record.get("large_radii", []))
        args.out.write_text(json.dumps(record, indent=1) + "\n")
        print(f"written: {args.out}")
        return 0

    radii = tuple(r * 1e-6 for r in args.radii)
    if args.only_large:
        commit, dirty = _commit()
        date = time.strftime("%Y-%m-%dT%H:%M:%S%z")

        def done(rows):
            # re-read: another --only-large run (other radii or presets) may have written
            # meanwhile; its rows are kept, this run's (radius, preset) rows replaced (a new
            # --out file holds this run's rows alone)
            record = json.loads(args.out.read_text()) if args.out.exists() else {}
            key = lambda r: (r["tip_radius_um"], r["accuracy"])  # noqa: E731
            mine = {key(r) for r in rows}
            kept = [r for r in record.get("large_radii", []) if key(r) not in mine]
            large = sorted(kept + [dict(r, commit=commit, uncommitted_changes=dirty, date=date)
                                   for r in rows], key=key)
            record["large_radii"] = compared(large)
            for old in ("large_radii_commit", "large_radii_uncommitted_changes", "large_radii_date"):
                record.pop(old, None)  # per row now
            args.out.parent.mkdir(parents=True, exist_ok=True)
            args.out.write_text(json.dumps(record, indent=1) + "\n")

        large_rows(radii, tuple(args.accuracies), done)
        print(f"written: {args.out}")
        return 0
    specs = scene_specs()
    rows = []
    for accuracy in ("draft", "standard"):
        for spec in specs:
            rows.append(job_row(spec, accuracy))
            print(f"scene job R = {rows[-1]['tip_radius_um']:.4g} um, {accuracy}: "
                  f"{rows[-1]['cpu_time_s']:.1f} s", flush=True)
    totals = {a: sum(r["cpu_time_s"] for r in rows if r["accuracy"] == a) for a in ("draft", "standard")}
    curves = []
    if not args.no_curves:
        for radius in (15.4e-6, 30e-6, 60e-6):
            ds, cpu = timed(lambda: smooth_aluminum_curves(radii=(radius,), accuracy="draft"))
            curves.append(dict(tip_radius_um=radius * 1e6, d_nm=0.3, accuracy="draft", cpu_time_s=cpu,
                               tabor_parameter=float(ds["tabor_parameter"][0])))
            print(f"smooth_aluminum_curves R = {radius * 1e6:.4g} um: {cpu:.1f} s", flush=True)
    if args.no_large:
        large = json.loads(args.out.read_text()).get("large_radii", [])
    else:
        large = compared(large_rows(radii, tuple(args.accuracies)))
    commit, dirty = _commit()
    old = json.loads(args.out.read_text()) if args.out.exists() else {}
    record = dict(date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), commit=commit, uncommitted_changes=dirty,
                  scene=SCENE, scene_jobs=rows, scene_cpu_time_s=totals,
                  smooth_aluminum_curves=curves, large_radii=large)
    for key in MESH_PARTS:  # parts 4-6 run on their own
        if key in old:
            record[key] = old[key]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1) + "\n")
    print(f"scene FE CPU: draft {totals['draft']:.0f} s, standard {totals['standard']:.0f} s")
    print(f"written: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
