"""Numbers and CPU cost of the plane-strain scenes (`make bench CASE=plane-strain`).

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
added (the report's theory, and the scenes', is small strain); with ``--unloading``, each
scene at each preset with the effect ``unloading``, and a second table: on each mesh the
permanent set (residual interference), the elastic recovery w_max - w_r against F_max / k
and the unloading stiffness (the first unloading step's slope) against k, with k the
elastic twin's stiffness at the largest interference, and the viscoplastic contact half
width at the top of the loading against the twin's; the ridge's run with unloading at
standard is drawn to docs/figures/truncated_v_plane_strain_unloading.png (the stage's
figure). Each row also counts the elements the viscoplastic body's displacement turns
inside out at the end.
Writes benchmarks/results/plane-strain.json (``--out``). Nothing is asserted.

    python benchmarks/plane_strain.py --sensitivity --finite-strain --unloading   # the README's tables
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
from asperity.io.figures import save_figure  # noqa: E402
from asperity.stages.plane_strain import plane_strain_dataset, plane_strain_figure  # noqa: E402

SCENES = ("aluminum_cylinder", "truncated_v")
RESULTS = Path(__file__).with_name("results")
#: the run with unloading drawn for the README, and where
UNLOADING_FIGURE = ("truncated_v", "standard",
                    REPO / "docs" / "figures" / "truncated_v_plane_strain_unloading.png")


def filled(name: str) -> dict:
    scene = yaml.safe_load((REPO / "config" / "scenes" / f"{name}.yaml").read_text())
    config = {"scenes": [name], "accuracy": "standard", "results": "results",
              "scene_dir": "config/scenes", "scene_definitions": {name: copy.deepcopy(scene)}}
    validate(config, str(REPO / "config" / "schema.yaml"))
    return config["scene_definitions"][name]


#: scene -> the dimension of its section the report does not give
UNKNOWN = {"aluminum_cylinder": "radius", "truncated_v": "top_width"}


def measure(name: str, preset: str, factor: float = 1.0, finite: bool = False,
            unloading: bool = False) -> dict:
    scene = filled(name)
    scene["plane_strain"]["section"][UNKNOWN[name]] *= factor
    scene["effects"] = [*scene["effects"], *(["finite_strain"] if finite else []),
                        *(["unloading"] if unloading else [])]
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
    if unloading:
        row["unloading"] = {m: unloaded(ds.sel(mesh=m)) for m in ds["mesh"].values}
        if (name, preset) == UNLOADING_FIGURE[:2] and factor == 1 and not finite:
            save_figure(plane_strain_figure(ds, scene["units"]), UNLOADING_FIGURE[2], dpi=110)
            print(f"written {UNLOADING_FIGURE[2]}", flush=True)
    if "hertz_half_width" in ds:
        a = ds["contact_half_width"].sel(body="elastic")
        dev = np.abs(a / ds["hertz_half_width"] - 1)
        row["hertz_half_width_deviation_percent"] = {m: 100 * float(dev.sel(mesh=m).max())
                                                     for m in ds["mesh"].values}
    return row


def unloaded(d) -> dict:
    """The unloading of one mesh of a study with the effect ``unloading`` (module
    docstring)."""
    w, f = d["step_interference"].values, d["step_force"].values
    peak = int(np.nanargmax(w))
    residual = float(d["residual_interference"])
    k = float(d["elastic_stiffness"][-1])
    a = d["contact_half_width"].isel(interference=-1)
    return dict(max_force_kN_per_m=1e-3 * float(f[peak]), residual_interference_um=1e6 * residual,
                recovery_um=1e6 * (w[peak] - residual),
                recovery_over_force_by_elastic_stiffness=(w[peak] - residual) * k / float(f[peak]),
                unloading_over_elastic_stiffness=float(d["unloading_stiffness"]) / k,
                loaded_over_elastic_half_width=float(a.sel(body="viscoplastic") / a.sel(body="elastic")),
                steps=int(np.sum(np.isfinite(w))) - 1)


def unloading_table(rows: list[dict]) -> str:
    out = ["| scene | preset | F_max coarse / refined (kN/m) | permanent set coarse / refined (um) "
           "| recovery x k / F_max | unloading stiffness / k | loaded / elastic half width | steps |",
           "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c, f = r["unloading"]["coarse"], r["unloading"]["refined"]
        both = (lambda key, fmt: f"{c[key]:{fmt}} / {f[key]:{fmt}}")
        out.append(
            f"| `{r['scene']}` | {r['preset']} | {both('max_force_kN_per_m', '.1f')} "
            f"| {both('residual_interference_um', '.3f')} "
            f"| {both('recovery_over_force_by_elastic_stiffness', '.3f')} "
            f"| {both('unloading_over_elastic_stiffness', '.4f')} "
            f"| {both('loaded_over_elastic_half_width', '.3f')} | {both('steps', 'd')} |")
    return "\n".join(out)


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
        if "unloading" in r:
            doubled += ", unloading"
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
    parser.add_argument("--unloading", action="store_true",
                        help="also each scene at each preset with the effect unloading")
    parser.add_argument("--out", type=Path, default=RESULTS / "plane-strain.json", help="JSON file")
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
    if args.unloading:
        for preset in args.presets:
            for name in args.scenes:
                rows.append(measure(name, preset, unloading=True))
                print(json.dumps(rows[-1]), flush=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(rows, indent=1) + "\n")
    print(table(rows))
    unloads = [r for r in rows if "unloading" in r]
    if unloads:
        print()
        print(unloading_table(unloads))


if __name__ == "__main__":
    main()
