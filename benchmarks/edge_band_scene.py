"""The FE jobs of a scene with and without the band the plastic contact edge sweeps
(a scene's ``asperity: {edge_band: true}``, issue #14).

Issue #14 saw the steel hills' force and area against interference bump where the
contact edge crosses the grading of a mesh adapted once to elastic solutions
(`results/steel_glass_bead/figures/asperities.png`).  This makes the scene's plan
through the workflow (a fresh copy, `snakemake results/<scene>/plan.nc`), then solves
each FE job of the plan in this process twice, on the preset's mesh without the band
(whatever the plan says: a J2 scene's plan has the band at standard) and with it
(`asperity.population.kinds.inelastic.edge_band_accuracy`), with
``time.process_time`` around each (one job after the other: CPU of a machine
otherwise idle).  For each job and mesh it records the history and:

* ``kink_force``, ``kink_area``: how much the curve bumps from step to step, the
  largest |y_i / y*_i - 1| over the steps, y*_i the value at w_i on the straight line
  in (ln w, ln y) through the steps before and after (0 for a power law), over
  w >= ``--from`` x the job's largest interference (`asperity.population.gather.largest_kink`,
  which the gathered asperities.nc reports for every scene);
* the band's difference from the plain mesh at equal interference
  (`benchmarks.remesh.compare`: at the top, the largest over the second half, from a
  tenth to a half and below a tenth of the loading).

Writes benchmarks/results/edge-band-<scene>-<preset>.json (``--out``) and, from it,
docs/figures/edge_band_<scene>.png (``--figure``: every step's kink against the
interference over the job's largest, where a bump shows as a spike)::

    python benchmarks/edge_band_scene.py --scene steel_glass_bead --accuracy standard
    python benchmarks/edge_band_scene.py --scene steel_glass_bead --accuracy standard --figure-only
"""

from __future__ import annotations

import argparse
import json
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.remesh import compare  # noqa: E402
from benchmarks.workflow_copy import SNAKEMAKE, copy_workflow  # noqa: E402

from asperity.population.gather import KINK_FROM, kinks, largest_kink  # noqa: E402

RESULTS = Path(__file__).with_name("results")
FIGURES = Path(__file__).resolve().parents[1] / "docs" / "figures"


def plan_jobs(scene: str, preset: str) -> list[tuple[str, dict]]:
    """(key, spec) of every FE job of the scene's plan at `preset`, made by the workflow."""
    from asperity.io.netcdf import read_dataset

    with tempfile.TemporaryDirectory() as tmp:
        workdir = copy_workflow(Path(tmp))
        target = f"results/{scene}/plan.nc"
        subprocess.run([str(SNAKEMAKE), "--cores", "1", target, "--config", f"scenes=[{scene}]",
                        f"accuracy={preset}", "studies=False"], cwd=workdir, check=True,
                       capture_output=True, text=True)
        plan = read_dataset(workdir / target)
        specs = {}
        for key, spec in zip(plan["key"].values, plan["spec"].values):
            specs.setdefault(str(key), json.loads(str(spec)))
    return sorted(specs.items())


def solve(spec: dict, key: str) -> dict:
    from asperity.population import samples

    t0 = time.process_time()
    ds = samples.solve(spec, key)
    cpu = time.process_time() - t0
    k = int(np.argmax(ds.interference.values))
    loading = ds.isel(step=slice(0, k + 1))
    keep = (loading.force.values > 0) & (loading.contact_area.values > 0)  # in contact
    return dict(cpu_seconds=cpu, steps=int(ds.sizes["step"]), dofs=int(ds.dofs.max()),
                newton_iterations=int(ds.newton_iterations.sum()),
                interference=loading.interference.values[keep].tolist(),
                force=loading.force.values[keep].tolist(),
                contact_area=loading.contact_area.values[keep].tolist(),
                force_at_top=float(ds.force[k]), contact_area_at_top=float(ds.contact_area[k]))


def summary(jobs: dict, start: float) -> dict:
    out = {}
    for key, runs in jobs.items():
        row = {}
        for mesh, r in runs.items():
            row[f"{mesh}_kink_force"] = largest_kink(r["interference"], r["force"], start)
            row[f"{mesh}_kink_area"] = largest_kink(r["interference"], r["contact_area"], start)
            row[f"{mesh}_cpu_seconds"] = r["cpu_seconds"]
        row["band_against_plain"] = compare(runs["band"], runs["plain"])
        out[key] = row
    return out


def figure(record: dict, path: Path) -> None:
    """The kinks of every job's force and area (rows) against w / the job's largest
    interference, without and with the band (columns): a bump is a spike."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from asperity.io.figures import save_figure

    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True, sharey=True)
    for i, (key, runs) in enumerate(record["jobs"].items()):
        for col, mesh in enumerate(("plain", "band")):
            r = runs[mesh]
            w = np.asarray(r["interference"])
            for row, name in enumerate(("force", "contact_area")):
                axes[row, col].plot(w[1:-1] / w.max(), 100 * kinks(w, r[name]), "-", color=f"C{i}",
                                    lw=0.7, label=f"job {key[:6]}, w_max {w.max() * 1e6:.3g} um")
    for col, title in enumerate(("without the band", "edge band (asperity.edge_band)")):
        axes[0, col].set_title(f"{record['scene']} at {record['accuracy']}, {title}", fontsize=9)
        axes[1, col].set_xlabel("interference / the job's largest")
    for row, name in enumerate(("force", "contact area")):
        axes[row, 0].set_ylabel(f"{name}: kink from step to step [%]")
    for ax in axes.ravel():
        ax.set(xscale="log", ylim=(-6, 6))
        ax.axvline(record["from"], color="0.6", lw=0.8, ls=":")
    axes[0, 0].legend(fontsize=6)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="steel_glass_bead")
    ap.add_argument("--accuracy", default="standard")
    ap.add_argument("--from", dest="start", type=float, default=KINK_FROM,
                    help="compare from this fraction of each job's largest interference")
    ap.add_argument("--figure-only", action="store_true", help="redraw from the results file")
    ap.add_argument("--out", type=Path,
                    help="JSON file (default benchmarks/results/edge-band-<scene>-<preset>.json)")
    ap.add_argument("--figure", type=Path,
                    help="PNG file (default docs/figures/edge_band_<scene>.png)")
    args = ap.parse_args(argv)
    from asperity.population.kinds.inelastic import edge_band_accuracy

    out = args.out or RESULTS / f"edge-band-{args.scene}-{args.accuracy}.json"
    drawn = args.figure or FIGURES / f"edge_band_{args.scene}.png"
    if args.figure_only:
        record = json.loads(out.read_text())
    else:
        record = dict(scene=args.scene, accuracy=args.accuracy, machine=platform.platform(),
                      python=sys.version.split()[0], jobs={})
        for key, spec in plan_jobs(args.scene, args.accuracy):
            plain = dict(spec, accuracy=args.accuracy)
            band = dict(spec, accuracy=edge_band_accuracy(args.accuracy))
            record["jobs"][key] = {"plain": solve(plain, key), "band": solve(band, key)}
            runs = record["jobs"][key]
            print(f"job {key}: {runs['plain']['cpu_seconds']:.1f} s without the band, "
                  f"{runs['band']['cpu_seconds']:.1f} s with the band", flush=True)
    record["summary"] = summary(record["jobs"], args.start)
    record["from"] = args.start
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(record, indent=1))
    figure(record, drawn)
    print(json.dumps(record["summary"], indent=1))
    print(f"written {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
