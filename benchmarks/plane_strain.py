"""Numbers and CPU cost of the plane-strain scenes (`make time-plane-strain`).

Runs the stage of scenes `aluminum_cylinder` (report 6.3.2) and `truncated_v` (6.3.3) in
this process, each at the presets asked for, from the scene files validated against
config/schema.yaml (its defaults filled in, as the workflow does), and prints the
README's table: force per length at the largest interference of the elastic and the
viscoplastic body on the coarse (initial) and refined meshes, their difference, the
largest nonelastic strain, for the cylinder the largest deviation of the elastic half
width from plane-strain Hertz, and the CPU time (`time.process_time`) of the solves.
With ``--sensitivity`` it also runs, at draft, each scene with the dimension the report
does not give doubled (the cylinder's radius, the ridge's flat top), the rest unchanged;
with ``--finite-strain``, each scene at each preset with the effect ``finite_strain``
added (the report's theory, and the scenes', is small strain). Each row also counts the
elements the viscoplastic body's displacement turns inside out at the end.
Writes benchmarks/results/plane-strain.json. Nothing is asserted.

    python benchmarks/plane_strain.py --sensitivity --finite-strain   # the README's table
    python benchmarks/plane_strain.py --presets draft standard
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
import time
from pathlib import Path

import numpy as np
import yaml
from snakemake.utils import validate

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
from asperity.stages.plane_strain import plane_strain_dataset  # noqa: E402

SCENES = ("aluminum_cylinder", "truncated_v")
RESULTS = Path(__file__).with_name("results")


def filled(name: str) -> dict:
    scene = yaml.safe_load((REPO / "config" / "scenes" / f"{name}.yaml").read_text())
    config = {"scenes": [name], "accuracy": "standard", "results": "results",
              "scene_dir": "config/scenes", "scene_definitions": {name: copy.deepcopy(scene)}}
    validate(config, str(REPO / "config" / "schema.yaml"))
    return config["scene_definitions"][name]


#: scene -> the dimension of its section the report does not give
UNKNOWN = {"aluminum_cylinder": "radius", "truncated_v": "top_width"}


def measure(name: str, preset: str, factor: float = 1.0, finite: bool = False) -> dict:
    scene = filled(name)
    scene["plane_strain"]["section"][UNKNOWN[name]] *= factor
    if finite:
        scene["effects"] = [*scene["effects"], "finite_strain"]
    t0 = time.process_time()
    ds = plane_strain_dataset(name, scene, preset)
    total = time.process_time() - t0
    end = ds.isel(interference=-1)
    f = end["force"]
    row = dict(
        scene=name, preset=preset, **({UNKNOWN[name] + "_factor": factor} if factor != 1 else {}),
        kinematics=ds.attrs["kinematics"],
        max_interference_um=1e6 * float(ds.attrs["max_interference"]),
        dofs={m: int(ds["dofs"].sel(mesh=m, body="elastic")) for m in ds["mesh"].values},
        steps={m: int(ds["viscoplastic_steps"].sel(mesh=m)) for m in ds["mesh"].values},
        force_kN_per_m={f"{b}, {m}": 1e-3 * float(f.sel(mesh=m, body=b))
                        for m in ds["mesh"].values for b in ds["body"].values},
        coarse_vs_refined_percent={
            b: 100 * float(f.sel(mesh="coarse", body=b) / f.sel(mesh="refined", body=b) - 1)
            for b in ds["body"].values},
        viscoplastic_over_elastic={m: float(f.sel(mesh=m, body="viscoplastic")
                                            / f.sel(mesh=m, body="elastic"))
                                   for m in ds["mesh"].values},
        largest_inelastic_strain={m: float(ds["largest_inelastic_strain"].sel(mesh=m))
                                  for m in ds["mesh"].values},
        inverted_elements={m: int(ds["inverted_elements"].sel(mesh=m)) for m in ds["mesh"].values},
        cpu_solves_s=float(ds["cpu_time"].sum()),
        cpu_stage_s=total,
    )
    if "hertz_half_width" in ds:
        a = ds["contact_half_width"].sel(body="elastic")
        dev = np.abs(a / ds["hertz_half_width"] - 1)
        row["hertz_half_width_deviation_percent"] = {m: 100 * float(dev.sel(mesh=m).max())
                                                     for m in ds["mesh"].values}
    return row


def table(rows: list[dict]) -> str:
    out = ["| scene | preset | dofs coarse / refined | F elastic, refined (kN/m) | F viscoplastic coarse / refined (kN/m) "
           "| coarse - refined, viscoplastic | viscoplastic / elastic | largest nonelastic strain coarse / refined "
           "| elements inside out coarse / refined | CPU (s) |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f = r["force_kN_per_m"]
        doubled = next((f", {k[:-7]} x {v:g}" for k, v in r.items() if k.endswith("_factor")), "")
        if r["kinematics"] == "finite":
            doubled += ", finite strain"
        n = r["inverted_elements"]
        out.append(
            f"| `{r['scene']}`{doubled} | {r['preset']} | {r['dofs']['coarse']} / {r['dofs']['refined']} "
            f"| {f['elastic, refined']:.1f} | {f['viscoplastic, coarse']:.1f} / "
            f"{f['viscoplastic, refined']:.1f} | {r['coarse_vs_refined_percent']['viscoplastic']:+.1f} % "
            f"| {r['viscoplastic_over_elastic']['refined']:.3f} "
            f"| {r['largest_inelastic_strain']['coarse']:.3g} / {r['largest_inelastic_strain']['refined']:.3g} "
            f"| {n['coarse']} / {n['refined']} | {r['cpu_stage_s']:.1f} |")
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--presets", nargs="+", default=["draft", "standard", "fine"])
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--sensitivity", action="store_true",
                        help="also each scene at draft with its unknown dimension doubled")
    parser.add_argument("--finite-strain", action="store_true",
                        help="also each scene at each preset with the effect finite_strain")
    args = parser.parse_args(argv)
    rows = []
    for preset in args.presets:
        for name in args.scenes:
            rows.append(measure(name, preset))
            print(json.dumps(rows[-1]), flush=True)
    if args.sensitivity:
        for name in args.scenes:
            rows.append(measure(name, "draft", factor=2.0))
            print(json.dumps(rows[-1]), flush=True)
    if args.finite_strain:
        for preset in args.presets:
            for name in args.scenes:
                rows.append(measure(name, preset, finite=True))
                print(json.dumps(rows[-1]), flush=True)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "plane-strain.json").write_text(json.dumps(rows, indent=1) + "\n")
    print(table(rows))


if __name__ == "__main__":
    main()
