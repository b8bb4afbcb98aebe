"""The J2 sphere of the reference scenes' aluminum beside two models of it: Kogut and
Etsion's fits of the elastic-plastic sphere, and the boundary elements of a paraboloid
limited by the hardness (the J2 route's reference).

    python benchmarks/j2_sphere.py [--accuracy draft standard]

E = 70 GPa, nu = 0.33, Y = 280 MPa (E / Y = 250), R = 1 um:

* pressed to 300 w_c (w_c of `asperity.references.kogut_etsion`), its force and area
  over Kogut and Etsion's at 1 to 100 w_c;
* pressed to R / 4 as a population's job is (its first step 1e-4 of that), on the
  mesh of `asperity.population.kinds.inelastic.mesh_levels` and on the finite element
  default (from a hundredth of the range), its force over theirs at 1 to 50 w_c;
* the same job's force and area over the boundary elements of the paraboloid of radius
  R limited by the hardness 2.8 Y (free boundary, 256 x 256 cells over 2.4 R or 0.5 R,
  ``--cells``) at w / R = 0.001 to 0.25.

Writes benchmarks/results/j2-sphere.json (``--out``; read by docs/generate.py) and prints it.
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.routes import _commit  # noqa: E402
from benchmarks.scenes import OUT  # noqa: E402
from benchmarks.workflow_copy import REPO  # noqa: E402

E, NU, Y, R = 70e9, 0.33, 280e6, 1e-6
KE_POINTS = [1, 2, 4, 6, 10, 20, 50, 100]
WR_POINTS = [0.001, 0.003, 0.01, 0.03, 0.1, 0.25]


def _press(accuracy: str, top: float, levels, first: float):
    from asperity import fe

    t0 = time.process_time()
    ds = fe.solve_asperity_history(fe.Sphere(R), fe.J2Plasticity(E, NU, Y), fe.History((0.0, 1.0), (0.0, top)),
                                   accuracy=accuracy, mesh_levels=levels, initial_time_step=first)
    return ds, time.process_time() - t0


def _at(ds, w, name):
    return np.interp(w, ds["interference"].values, ds[name].values)


def _hardness_paraboloid(w_over_r, modulus, cells: int = 256):
    """Force and area of the paraboloid of radius R pressed by w under the hardness 2.8 Y
    (`cells` x `cells` boundary elements)."""
    from asperity.references.boundary_element import solve_map

    out = {}
    for half, ws in ((0.25 * R, [v for v in w_over_r if v <= 0.03]), (1.2 * R, [v for v in w_over_r if v > 0.03])):
        x = (np.arange(cells) - (cells - 1) / 2) * (2 * half / cells)
        xx, yy = np.meshgrid(x, x)
        z = -(xx ** 2 + yy ** 2) / (2 * R)
        w = np.asarray(ws) * R
        ds = solve_map(z, x[1] - x[0], x[1] - x[0], -z.mean() - w, modulus, hardness=2.8 * Y, boundary="free")
        area = (2 * half) ** 2  # the separations come back increasing: the deepest first
        for k, v in enumerate(ws):
            j = len(ws) - 1 - k
            out[v] = (float(ds["nominal_pressure"][j]) * area, float(ds["contact_area_ratio"][j]) * area)
    return out


def measure(accuracy: str, cells: int = 256) -> dict:
    from asperity.fe.drivers.inelastic import MESH_LEVELS, MESH_RANGE
    from asperity.population.kinds.inelastic import FIRST_STEP, mesh_levels
    from asperity.references.hertz import plane_strain_modulus
    from asperity.references.kogut_etsion import critical_interference, kogut_etsion
    from asperity.scene import Material

    modulus = float(plane_strain_modulus(E, NU))
    wc = critical_interference(R, modulus, NU, Y)
    record = {"critical_interference_over_radius": wc / R}
    ds, cpu = _press(accuracy, 300 * wc, np.geomspace(MESH_RANGE * 300 * wc, 300 * wc, MESH_LEVELS), 2e-3)
    w = np.array(KE_POINTS) * wc
    ref = kogut_etsion(w, R, modulus, NU, Y)
    record["to_300_wc"] = {"w_over_wc": KE_POINTS, "cpu_s": cpu,
                           "force_over_ke": (_at(ds, w, "force") / ref["force"]).tolist(),
                           "area_over_ke": (_at(ds, w, "contact_area") / ref["contact_area"]).tolist()}
    top = R / 4
    body = Material(model="j2", youngs_modulus=E, poisson=NU, yield_stress=Y)
    w = np.array(KE_POINTS[:-1]) * wc
    ref = kogut_etsion(w, R, modulus, NU, Y)
    jobs = {}
    for name, levels in (("mesh_levels", mesh_levels(top, 1.0 / R, body)),
                         ("fe_default", np.geomspace(MESH_RANGE * top, top, MESH_LEVELS))):
        job, cpu = _press(accuracy, top, levels, FIRST_STEP)
        jobs[name] = (job, {"cpu_s": cpu, "w_over_wc": KE_POINTS[:-1],
                            "force_over_ke": (_at(job, w, "force") / ref["force"]).tolist()})
    record["job_to_quarter_radius"] = {name: value for name, (_, value) in jobs.items()}
    bem = _hardness_paraboloid(WR_POINTS, modulus, cells)
    job = jobs["mesh_levels"][0]
    record["against_hardness"] = {
        "w_over_r": WR_POINTS, "w_over_wc": [v * R / wc for v in WR_POINTS],
        "force_ratio": [float(_at(job, v * R, "force")) / bem[v][0] for v in WR_POINTS],
        "area_ratio": [float(_at(job, v * R, "contact_area")) / bem[v][1] for v in WR_POINTS]}
    return record


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--accuracy", nargs="+", default=["draft", "standard"])
    ap.add_argument("--cells", type=int, default=256,
                    help="boundary elements per side of the paraboloid limited by the hardness")
    ap.add_argument("--out", type=Path, default=OUT / "j2-sphere.json", help="JSON file")
    args = ap.parse_args(argv)
    result = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "commit": _commit(),
              "machine": {"platform": platform.platform(), "python": platform.python_version()},
              "material": {"youngs_modulus": E, "poisson": NU, "yield_stress": Y, "radius": R},
              "presets": {}, **({"cells": args.cells} if args.cells != 256 else {})}
    for preset in args.accuracy:
        result["presets"][preset] = measure(preset, args.cells)
        print(preset, json.dumps(result["presets"][preset], indent=1), flush=True)
    path = args.out.resolve()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(f"written {path.relative_to(REPO) if path.is_relative_to(REPO) else path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
