"""Every route's error against the boundary elements on every map: the table of the docs.

    python benchmarks/routes.py [--accuracy draft] [--maps synthetic di-3 mi-1 frt-1]
    python benchmarks/routes.py --maps synthetic anisotropic --output routes-anisotropic

For each map, the reference scene runs in a fresh copy of the workflow
(benchmarks.workflow_copy): the synthetic Gaussian map of `deterministic_reference`,
and each measured map of data/topographies as `afm_reference` with only its map file
changed (the way a user would run their own map), with the scene's lateral scale
(`surface.scale`), routes and separations as they are. From its comparison.nc: per
separation (in sigma of the prepared map), the boundary elements' contact area ratio
and whether they resolve their contact patches, each route's pressure error at equal
separation (mean gap) and area error at equal pressure, and the recommended route.

Writes benchmarks/results/<output>-<accuracy>.json (output `routes` by default, or the
file ``--out``; read by docs/generate.py for the verification page) and prints one markdown
table per map.  The second form is the anisotropic surface of `anisotropic_reference`
beside the isotropic synthetic map of the same rms gradient (the docs' "Anisotropic
surfaces").  A small case keeps some of the scene's routes (``--routes``) and fewer
separations (``--separations``)::

    python benchmarks/routes.py --maps di-3 --routes peaks --separations 4 --out /tmp/routes.json
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
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import OUT, run_snakemake  # noqa: E402
from benchmarks.workflow_copy import REPO, copy_workflow  # noqa: E402

#: map name -> (scene to copy, map file or None for the scene's own)
MAPS = {
    "synthetic": ("deterministic_reference", None),
    "di-3": ("afm_reference", "data/topographies/di-3.di"),
    "mi-1": ("afm_reference", "data/topographies/mi-1.mi"),
    "frt-1": ("afm_reference", "data/topographies/frt-1.frt"),
    "anisotropic": ("anisotropic_reference", None),
}
#: the maps of the default run (the anisotropic one has its own table: --maps synthetic
#: anisotropic --output routes-anisotropic)
DEFAULT_MAPS = ("synthetic", "di-3", "mi-1", "frt-1")


def _commit() -> str:
    run = subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True, text=True)
    return run.stdout.strip()


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


def scene_for(workdir: Path, name: str, routes: list[str] | None = None,
              separations: int | None = None) -> str:
    """Write the scene of map `name` into the copy (`trimmed` to `routes` and
    `separations`); its scene name."""
    base, file = MAPS[name]
    if file is None and routes is None and separations is None:
        return base
    definition = yaml.safe_load((workdir / "config" / "scenes" / f"{base}.yaml").read_text())
    if file is not None:
        definition["surface"]["map"] = {"file": file}
        definition["title"] = f"{definition['title']} ({Path(file).name})"
    trimmed(definition, routes, separations)
    scene = f"routes_{name.replace('-', '_')}"
    (workdir / "config" / "scenes" / f"{scene}.yaml").write_text(yaml.safe_dump(definition, sort_keys=False))
    return scene


def comparison(results: Path, scene: str) -> dict:
    from asperity.io.netcdf import read_dataset

    ref = read_dataset(results / scene / "reference.nc")
    cmp_ = read_dataset(results / scene / "comparison.nc")
    surface = read_dataset(results / scene / "surface.nc")
    sigma = float(ref.attrs["sigma"])

    def floats(values):
        return [None if not np.isfinite(v) else float(v) for v in np.asarray(values, dtype=float).ravel()]

    return {
        "routes": [str(r) for r in cmp_["route"].values],
        "sigma": sigma,
        "separation": floats(cmp_["separation"].values),
        "reference_area_ratio": floats(cmp_["reference_area_ratio"].values),
        "reference_pressure": floats(cmp_["reference_pressure"].values),
        "reference_resolved": [bool(v) for v in cmp_["reference_resolved"].values],
        "cells_per_patch": floats(ref["cells_per_patch"].sel(limit="elastic").values),
        "pressure_error": [floats(row) for row in cmp_["pressure_error"].values],
        "area_error": [floats(row) for row in cmp_["area_error"].values],
        "reference_limit": [str(v) for v in cmp_["reference_limit"].values],
        "recommended_route": [str(v) for v in cmp_["recommended_route"].values],
        "recommended_error": floats(cmp_["recommended_error"].values),
        "scale": surface.attrs.get("scale"),
        "scale_rule": surface.attrs.get("scale_rule", ""),
        "grid": ref.attrs.get("grid", ""),
    }


def measure(names, preset: str, cores: int, timeout: float, routes: list[str] | None = None,
            separations: int | None = None) -> dict:
    out = {"accuracy": preset, "cores": cores, "date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
           "commit": _commit(), "machine": {"platform": platform.platform(), "cpu_count": cores,
                                            "python": platform.python_version()}, "maps": {}}
    if routes is not None or separations is not None:
        out["trimmed"] = {"routes": routes, "separations": separations}
    for name in names:
        with tempfile.TemporaryDirectory(prefix=f"routes-{name}-") as tmp:
            workdir = copy_workflow(Path(tmp))
            scene = scene_for(workdir, name, routes, separations)
            record = run_snakemake(workdir, ["snakemake", "--cores", str(cores), "--config",
                                             f"scenes=[{scene}]", f"accuracy={preset}", "studies=False"],
                                   timeout)
            if record["status"] == "ok":
                record["comparison"] = comparison(workdir / "results", scene)
            record["scene"] = scene
            out["maps"][name] = record
            print(f"{name}: {record['wall_time_s']} s ({record['status']})", flush=True)
            if record["status"] != "ok":
                print(record.get("error_tail", ""), flush=True)
    return out


def _pct(value) -> str:
    return "-" if value is None else f"{100 * value:+.0f}"


def markdown(result: dict) -> str:
    lines = []
    for name, record in result["maps"].items():
        c = record.get("comparison")
        if not c:
            lines.append(f"\n{name}: {record['status']}")
            continue
        lines.append(f"\n{name} ({record['scene']}, scale {c['scale']}):")
        lines.append("| h/sigma | BEM A/A0 | cells/patch | " + " | ".join(c["routes"]) + " | best |")
        lines.append("|---" * (4 + len(c["routes"])) + "|")
        for k, h in enumerate(c["separation"]):
            cells = [f"{_pct(c['pressure_error'][i][k])}/{_pct(c['area_error'][i][k])}"
                     for i in range(len(c["routes"]))]
            area = c["reference_area_ratio"][k]
            lines.append(f"| {h / c['sigma']:.2f} | {'-' if area is None else f'{100 * area:.3g} %'} | "
                         f"{c['cells_per_patch'][k] or 0:.3g} | " + " | ".join(cells)
                         + f" | {c['recommended_route'][k]} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--accuracy", default="draft", choices=("draft", "standard", "fine"))
    ap.add_argument("--maps", nargs="+", default=list(DEFAULT_MAPS), choices=list(MAPS))
    ap.add_argument("--output", default="routes", help="the result file's name before -<accuracy>.json")
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=1800.0)
    ap.add_argument("--routes", nargs="+", metavar="ROUTE", help="only these routes of the scene")
    ap.add_argument("--separations", type=int, metavar="N",
                    help="N separations of the reference instead of the scene's")
    ap.add_argument("--out", type=Path,
                    help="JSON file (default benchmarks/results/<output>-<accuracy>.json)")
    args = ap.parse_args(argv)
    result = measure(args.maps, args.accuracy, args.cores, args.timeout, args.routes, args.separations)
    path = (args.out or OUT / f"{args.output}-{args.accuracy}.json").resolve()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(markdown(result))
    print(f"written {path.relative_to(REPO) if path.is_relative_to(REPO) else path}")
    return 0 if all(r["status"] == "ok" for r in result["maps"].values()) else 1


if __name__ == "__main__":
    raise SystemExit(main())
