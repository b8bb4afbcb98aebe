"""Scene-level convergence over the valid range (issue #15, item 3), from runs already made.

`snakemake accuracy_scenes` runs every scene of its list at every preset; this script
compares runs that exist, each scene against the finest preset it has, with the
definitions of `asperity.studies.scenes` (the largest relative deviation of the nominal
pressure and the contact area ratio, over all separations and over those where the
reference run is valid). A run of scene S at preset P is ``ROOT/S@P/interface.nc`` or
``ROOT/S/interface.nc`` whose ``accuracy`` attribute is P, for any ROOT given.

    python benchmarks/scene_convergence.py --scenes rough_aluminum_coupled steel_glass_bead_coupled \
        --roots results results_standard

Writes benchmarks/results/scene-convergence.json.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from asperity.io.netcdf import read_dataset
from asperity.studies.scenes import scene_accuracy

OUT = Path(__file__).with_name("results") / "scene-convergence.json"
PRESETS = ("draft", "standard", "fine")


def runs_of(scene: str, roots) -> dict:
    """preset -> interface dataset of `scene`, from the first root that has it."""
    found = {}
    for root in map(Path, roots):
        for path in (root / scene / "interface.nc", *root.glob(f"{scene}@*/interface.nc")):
            if path.exists():
                ds = read_dataset(path)
                found.setdefault(str(ds.attrs.get("accuracy")), (ds, str(path)))
    return found


def _value(x):
    x = float(x)
    return None if not np.isfinite(x) else x


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", nargs="+", required=True)
    ap.add_argument("--roots", nargs="+", default=["results"])
    args = ap.parse_args()
    report = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "scenes": {}}
    for scene in args.scenes:
        found = runs_of(scene, args.roots)
        presets = [p for p in PRESETS if p in found]
        if len(presets) < 2:
            print(f"{scene}: runs at {presets or 'no preset'}; two are needed")
            continue
        ds = scene_accuracy({(scene, p): found[p][0] for p in presets}, [scene], presets)
        rows = {}
        for p in presets[:-1]:
            for q in ds["quantity"].values:
                for b in ds["branch"].values:
                    one = ds.sel(scene=scene, preset=p, quantity=q, branch=b)
                    if int(one["compared_separations"]) == 0:
                        continue
                    rows[f"{p}/{q}/{b}"] = dict(
                        deviation=_value(one["deviation"]),
                        valid_deviation=_value(one["valid_deviation"]),
                        valid_separations=int(one["valid_separations"]),
                        compared_separations=int(one["compared_separations"]))
                    print(f"{scene:28s} {p:8s} vs {presets[-1]:8s} {q:20s} {b:9s} "
                          f"all {100 * float(one['deviation']):6.2f} %  valid "
                          f"{100 * float(one['valid_deviation']):6.2f} % "
                          f"({int(one['valid_separations'])} separations)")
        report["scenes"][scene] = dict(
            reference=presets[-1], runs={p: found[p][1] for p in presets},
            fe_cpu_time={p: _value(ds["fe_cpu_time"].sel(scene=scene, preset=p)) for p in presets},
            deviations=rows)
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text(json.dumps(report, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
