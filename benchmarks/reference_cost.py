"""The `deterministic_reference` scene (or another scene with a reference, ``--scene``: the
measured map of `afm_reference`): its wall time and each route's, side by side, and the
statistical routes' error against the boundary-element solution
(`make bench CASE=reference`).

Each measurement runs in its own fresh copy of the workflow (benchmarks.workflow_copy),
Snakemake's start-up included, with

    snakemake --cores 2 [target] --config 'scenes=[deterministic_reference]' accuracy=<preset> studies=False

for the targets: the whole scene; the boundary-element solve alone
(results/deterministic_reference/reference.nc: the map, its statistics and the solve);
and each statistical route alone (results/deterministic_reference+<route>/interface.nc:
the map, its statistics, the plan, the asperities (FE jobs for nayak_fe) and the
homogenization).  CPU times are the jobs' own: the solve's (reference.nc, per limit) and
the FE jobs' (interface.nc, fe_cpu_time).  Wall times on a shared machine are noisy;
compare CPU times.

The whole-scene run's comparison.nc gives the table of each route's error against the
elastic boundary-element solution and the range of separations where it holds.

Writes benchmarks/results/reference-<preset>.json (reference-<scene>-<preset>.json for
another scene; or the file ``--out``) and prints markdown tables.  ``--parts`` runs some
of the measurements only; a small case keeps some of the scene's routes (``--routes``) and
fewer separations (``--separations``).

    python benchmarks/reference_cost.py --accuracy draft
    python benchmarks/reference_cost.py --scene afm_reference --accuracy draft
    python benchmarks/reference_cost.py --scene afm_reference --parts scene --routes peaks \
        --separations 4 --out /tmp/reference.json
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

import numpy as np
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from asperity.scene.files import read_scene  # noqa: E402
from benchmarks.scenes import OUT, provenance, run_snakemake  # noqa: E402
from benchmarks.workflow_copy import REPO, copy_workflow  # noqa: E402

SCENE = "deterministic_reference"
#: what ``--parts`` picks from: the whole scene, the boundary elements alone, each route alone
PARTS = ("scene", "reference", "routes")


def trimmed(definition: dict, routes: list[str] | None = None,
            separations: int | None = None) -> dict:
    """A reference scene with only `routes` of its routes and `separations` separations of
    its reference (None: as it is), for a small case."""
    if routes is not None:
        unknown = set(routes) - set(definition["routes"])
        if unknown:
            raise SystemExit(f"no route {', '.join(sorted(unknown))} in the scene "
                             f"(one of {', '.join(definition['routes'])})")
        definition["routes"] = {k: v for k, v in definition["routes"].items() if k in routes}
    if separations is not None:
        definition["reference"]["separations"]["count"] = separations
    return definition


def command(scene: str, preset: str, cores: int, target: str | None) -> list[str]:
    # the target before --config, which takes every argument after it
    return ["snakemake", "--cores", str(cores), *([target] if target else []), "--config",
            f"scenes=[{scene}]", f"accuracy={preset}", "studies=False"]


def _read(path: Path):
    from asperity.io.netcdf import read_dataset

    return read_dataset(path)


def comparison_rows(results: Path, scene: str = SCENE) -> list[dict]:
    """Per route: errors against the elastic BEM at a few separations, and where it holds."""
    ref = _read(results / scene / "reference.nc")
    cmp_ = _read(results / scene / "comparison.nc")
    sigma = float(ref.attrs["sigma"])
    rows = []
    for route in cmp_["route"].values:
        c = cmp_.sel(route=route)
        rows.append({
            "route": str(route),
            "separation_sigma": [round(float(h) / sigma, 3) for h in cmp_["separation"].values],
            "reference_area_ratio": [float(a) for a in cmp_["reference_area_ratio"].values],
            "pressure_error": [float(e) for e in c["pressure_error"].values],
            "area_error": [float(e) for e in c["area_error"].values],
            "contact_count_ratio": [float(e) for e in c["contact_count_ratio"].values],
            "holds_from_sigma": float(c["holds_from"]) / sigma,
            "holds_to_sigma": float(c["holds_to"]) / sigma,
            "holds_pressure_low_Pa": float(c["holds_pressure_low"]),
            "holds_pressure_high_Pa": float(c["holds_pressure_high"]),
        })
    extra = {"agreement": float(cmp_.attrs["agreement"]), "sigma_m": sigma,
             "bem_cpu_time_s": {str(k): float(v) for k, v in zip(ref["limit"].values, ref["cpu_time"].values)},
             "plastic_departure": ([float(v) for v in cmp_["plastic_departure"].values]
                                   if "plastic_departure" in cmp_ else None)}
    return rows, extra


def measure(scene: str, preset: str, cores: int, timeout: float | None, parts=PARTS,
            routes: list[str] | None = None, separations: int | None = None) -> dict:
    """The runs of `parts` (`PARTS`), each in a fresh copy; with `routes` or `separations`,
    the scene `trimmed` to them in each copy."""
    path = REPO / "config" / "scenes" / f"{scene}.yaml"
    small = routes is not None or separations is not None
    definition = read_scene(path)  # whole: a trimmed copy must not start from another scene
    definition.pop("like", None)
    if small:
        definition = trimmed(definition, routes, separations)
    targets = {"whole scene": None} if "scene" in parts else {}
    if "reference" in parts:
        targets["boundary elements"] = f"results/{scene}/reference.nc"
    if "routes" in parts:
        targets |= {f"route {r}": f"results/{scene}+{r}/interface.nc" for r in definition["routes"]}
    runs, comparison, extra = [], None, None
    for label, target in targets.items():
        with tempfile.TemporaryDirectory(prefix="reference-") as tmp:
            workdir = copy_workflow(Path(tmp))
            if small:
                (workdir / "config" / "scenes" / path.name).write_text(
                    yaml.safe_dump(definition, sort_keys=False))
            record = run_snakemake(workdir, command(scene, preset, cores, target), timeout)
            record["what"] = label
            results = workdir / "results"
            if record["status"] == "ok":
                if target is None:
                    comparison, extra = comparison_rows(results, scene)
                if label == "boundary elements" or target is None:
                    ref = _read(results / scene / "reference.nc")
                    record["bem_cpu_time_s"] = float(ref["cpu_time"].sum())
                if label.startswith("route"):
                    interface = _read(results / f"{scene}+{label.split()[1]}" / "interface.nc")
                    record["fe_cpu_time_s"] = float(interface.attrs.get("fe_cpu_time", 0.0))
            runs.append(record)
            print(f"{label}: {record['wall_time_s']} s ({record['status']})", flush=True)
    return {"scene": scene, **provenance(preset, cores), "runs": runs, "comparison": comparison,
            "comparison_extra": extra,
            **({"trimmed": {"routes": routes, "separations": separations}} if small else {})}


def _pct(v: float) -> str:
    return "n/a" if not np.isfinite(v) else f"{100 * v:+.0f} %"


def markdown(result: dict) -> str:
    lines = ["| run | jobs (FE) | wall time | CPU of the solve / FE jobs |", "|---|---|---|---|"]
    for r in result["runs"]:
        cpu = r.get("bem_cpu_time_s", r.get("fe_cpu_time_s"))
        cpu_text = "" if cpu is None else f"{cpu:.1f} s"
        lines.append(f"| {r['what']} | {r['jobs']} ({r['fe_jobs']}) | {r['wall_time_s']:.1f} s "
                     f"{'' if r['status'] == 'ok' else '(' + r['status'] + ')'}| {cpu_text} |")
    if result["comparison"]:
        rows = result["comparison"]
        seps = rows[0]["separation_sigma"]
        pick = [i for i, s in enumerate(seps) if i % 2 == 0]
        lines += ["", "| route | " + " | ".join(f"h = {seps[i]:g} sigma" for i in pick)
                  + " | holds (separation, BEM pressure) |",
                  "|---|" + "---|" * len(pick) + "---|"]
        area = rows[0]["reference_area_ratio"]
        lines.append("| BEM A/A0 | " + " | ".join(f"{100 * area[i]:.2g} %" for i in pick) + " | |")
        for r in rows:
            cells = " | ".join(f"{_pct(r['pressure_error'][i])} / {_pct(r['area_error'][i])}" for i in pick)
            held = ("nowhere" if not np.isfinite(r["holds_from_sigma"]) else
                    f"{r['holds_from_sigma']:.2f}-{r['holds_to_sigma']:.2f} sigma, "
                    f"{r['holds_pressure_low_Pa'] / 1e6:.3g}-{r['holds_pressure_high_Pa'] / 1e6:.3g} MPa")
            lines.append(f"| {r['route']} | {cells} | {held} |")
        lines.append(f"(pressure error at equal separation / area error at equal pressure; "
                     f"holds: both within {100 * result['comparison_extra']['agreement']:g} %)")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=SCENE, help="a scene with a reference and routes")
    ap.add_argument("--accuracy", default="draft", choices=("draft", "standard", "fine"))
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=1800.0)
    ap.add_argument("--parts", nargs="+", choices=PARTS, default=list(PARTS),
                    help="the whole scene, the boundary elements alone, each route alone")
    ap.add_argument("--routes", nargs="+", metavar="ROUTE", help="only these routes of the scene")
    ap.add_argument("--separations", type=int, metavar="N",
                    help="N separations of the reference instead of the scene's")
    ap.add_argument("--out", type=Path,
                    help="JSON file (default benchmarks/results/reference[-<scene>]-<preset>.json)")
    args = ap.parse_args(argv)
    result = measure(args.scene, args.accuracy, args.cores, args.timeout, args.parts, args.routes,
                     args.separations)
    stem = "reference" if args.scene == SCENE else f"reference-{args.scene}"
    path = (args.out or OUT / f"{stem}-{args.accuracy}.json").resolve()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(markdown(result))
    print(f"written {path.relative_to(REPO) if path.is_relative_to(REPO) else path}")
    return 0 if all(r["status"] == "ok" for r in result["runs"]) else 1


if __name__ == "__main__":
    raise SystemExit(main())
