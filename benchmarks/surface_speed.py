"""Speed of a measured map's preparation and statistics against SurfaceTopography's
(`make bench CASE=surface`).

The case of the README: a 2048 x 2048 map with 10 % of its points undefined
(scattered, as an optical instrument leaves them), measured side by side in one
run on the same heights:

* asperity: form removal (least-squares plane over the defined points),
  statistics (heights, slopes and curvatures along x and y, the nine
  spectral moments and their invariants, 2.3.2) and the eight-neighbour peaks
  with their curvatures (2.4.3): ``remove_form``, ``map_statistics``,
  ``map_peaks``; target under 2 s;
* SurfaceTopography on the same masked map: rms height, rms gradient and rms
  curvature (``Sq``, ``rms_gradient``, ``rms_curvature_from_area``): asperity's
  three steps must take less time than these three.

Also timed, for the README (no target): the whole surface stage of a map
(``surface_from_data``: the above plus the height distribution, the radially
averaged PSD of the map in-filled for it, the autocorrelation and the preview),
and each of its parts.

Times are the best of ``--repeats`` runs, CPU time (``time.process_time``; BLAS
single-threaded) and wall time. Writes benchmarks/results/surface-speed.json (``--out``) and
prints a table; nothing is asserted.

    python benchmarks/surface_speed.py               # 2048 x 2048, 10 % undefined
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import sys
import time
import warnings
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import _commit  # noqa: E402

OUT = Path(__file__).with_name("results") / "surface-speed.json"
TARGET_S = 2.0


def best(fn, repeats: int) -> dict:
    """Best CPU and wall time of `repeats` calls of `fn`."""
    cpu, wall = [], []
    for _ in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    return {"cpu_s": min(cpu), "wall_s": min(wall)}


def the_map(n: int, undefined: float, seed: int = 1):
    """A Gaussian random map (correlation length 8 spacings), tilted, with scattered undefined points."""
    from asperity import surface

    dx = 1e-6
    z = surface.gaussian_map(n, dx, 1e-7, 8 * dx, seed)
    y, x = np.meshgrid(np.arange(n) * dx, np.arange(n) * dx, indexing="ij")
    z = z + 0.01 * x - 0.005 * y  # a tilt of 1 % and 0.5 %: 100 times the roughness over the map
    defined = np.random.default_rng(seed).random(z.shape) >= undefined
    return np.where(defined, z, np.nan), defined, dx


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--points", type=int, default=2048, help="points per side (default 2048)")
    parser.add_argument("--undefined", type=float, default=0.10, help="share of undefined points (0.10)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", type=Path, default=OUT, help="JSON file")
    args = parser.parse_args(argv)

    from asperity import surface
    from asperity.stages.surface import surface_from_data

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import SurfaceTopography as ST

    z, defined, dx = the_map(args.points, args.undefined)
    rows = {}

    def ours():
        rough, _ = surface.remove_form(z, "tilt", None, defined)
        surface.map_statistics(rough, dx, dx, defined=defined)
        surface.map_peaks(rough, dx, dx, defined=defined)

    rough, _ = surface.remove_form(z, "tilt", None, defined)
    rows["asperity: form removal"] = best(lambda: surface.remove_form(z, "tilt", None, defined), args.repeats)
    rows["asperity: map_statistics"] = best(lambda: surface.map_statistics(rough, dx, dx, defined=defined),
                                            args.repeats)
    rows["asperity: map_peaks"] = best(lambda: surface.map_peaks(rough, dx, dx, defined=defined), args.repeats)
    rows["asperity: form removal + statistics + peaks"] = best(ours, args.repeats)

    # SurfaceTopography: x along axis 0, so the transpose; the same masked heights
    topo = ST.Topography(np.ma.masked_array(rough.T, ~defined.T), (args.points * dx, args.points * dx),
                         periodic=False, unit="m")

    def theirs():
        topo.Sq()
        topo.rms_gradient()
        topo.rms_curvature_from_area()

    rows["SurfaceTopography: Sq"] = best(topo.Sq, args.repeats)
    rows["SurfaceTopography: rms_gradient"] = best(topo.rms_gradient, args.repeats)
    rows["SurfaceTopography: rms_curvature_from_area"] = best(topo.rms_curvature_from_area, args.repeats)
    rows["SurfaceTopography: Sq + rms_gradient + rms_curvature"] = best(theirs, args.repeats)

    cfg = {"map": {"file": "benchmark"}, "form": "tilt", "undefined": {"max_share": 0.5}}
    rows["asperity: whole surface stage (surface_from_data)"] = best(
        lambda: surface_from_data(z, (dx, dx), cfg, {"length": "um"}, defined=defined), 1)
    rows["  of it: harmonic in-fill for the PSD"] = best(lambda: surface.harmonic_fill(rough, defined), 1)
    rows["  of it: autocorrelation over defined pairs"] = best(
        lambda: surface.autocorrelation(rough, (dx, dx), defined), 1)

    ours_s = rows["asperity: form removal + statistics + peaks"]
    theirs_s = rows["SurfaceTopography: Sq + rms_gradient + rms_curvature"]
    record = {
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "commit": _commit()[0], "uncommitted_changes": _commit()[1],
        "machine": {"platform": platform.platform(), "python": sys.version.split()[0],
                    "cpus": os.cpu_count()},
        "map": {"points": [args.points, args.points], "undefined_share": float(1 - defined.mean()),
                "repeats": args.repeats},
        "times": rows,
        "target_s": TARGET_S,
        "met_target": ours_s["wall_s"] < TARGET_S,
        "ratio_cpu_asperity_over_surfacetopography": ours_s["cpu_s"] / theirs_s["cpu_s"],
        "ratio_wall_asperity_over_surfacetopography": ours_s["wall_s"] / theirs_s["wall_s"],
    }
    print(f"{args.points} x {args.points} map, {100 * record['map']['undefined_share']:.1f} % undefined, "
          f"best of {args.repeats}")
    print(f"{'':58s} {'CPU [s]':>9s} {'wall [s]':>9s}")
    for name, t in rows.items():
        print(f"{name:58s} {t['cpu_s']:9.3f} {t['wall_s']:9.3f}")
    print(f"target: form removal + statistics + peaks under {TARGET_S:g} s: "
          f"{'met' if record['met_target'] else 'MISSED'}; asperity / SurfaceTopography: "
          f"{record['ratio_cpu_asperity_over_surfacetopography']:.3f} (CPU), "
          f"{record['ratio_wall_asperity_over_surfacetopography']:.3f} (wall)")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1) + "\n")
    print(f"written {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
