"""Finite against small strain in the inelastic asperity (`asperity.fe.discretization.kinematics`).

Two cases, each with ``kinematics`` small and finite, CPU time by
``time.process_time`` in this process:

* ``j2_sphere``: the J2 sphere of benchmarks/remesh.py (R = 1, E / Y = 400) to
  50 times its critical interference, where strains stay near 2 %: the two
  kinematics should agree to the strain's order, and the finite one's cost is
  the price of the kinematics alone.
* ``steel_hill``: the steepest coupled hill of ``steel_glass_bead``
  (aspect q = kappa z_p = 1.28, slope k C = 1.13; SAE 1020 Bodner-Partom, 8.2.1)
  pressed to its amplitude C = 5 um at 0.25 um/s, as its FE job is: the
  strains the small-strain theory reports there, and what finite strain gives.

Writes benchmarks/results/finite-strain.json (``--out``)::

    python benchmarks/finite_strain.py [--presets draft standard]
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import subprocess
import time
from pathlib import Path

import numpy as np

from asperity.fe import J2Plasticity, Sphere
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.discretization.geometry import CosineHill
from asperity.fe.drivers.inelastic import History, solve_asperity_history

OUT = Path(__file__).with_name("results") / "finite-strain.json"

E, NU = 1000.0, 0.3
Y = E / 400
W_C = (math.pi * 1.6 * Y / (2 * E / (1 - NU**2))) ** 2
C, Q = 5e-6, 1.28


def j2_sphere(accuracy, kinematics):
    ds = solve_asperity_history(Sphere(1.0), J2Plasticity(E, NU, Y), History.loading(50 * W_C, 1.0),
                                accuracy=accuracy, kinematics=kinematics)
    return ds, W_C, "w / w_c", (1.0, 10.0, 50.0)


def steel_hill(accuracy, kinematics):
    hill = CosineHill(C, math.sqrt(Q) / C)
    ds = solve_asperity_history(hill, BodnerPartom.sae_1020(), History.loading(C, 0.25e-6),
                                accuracy=accuracy, kinematics=kinematics,
                                mesh_levels=np.geomspace(0.01 * C, C, 6),
                                initial_time_step=1e-4 * C / 0.25e-6)
    return ds, C, "w / C", (0.01, 0.1, 0.3, 0.5, 1.0)


CASES = {"j2_sphere": j2_sphere, "steel_hill": steel_hill}


def run(case, accuracy, kinematics) -> dict:
    t0 = time.process_time()
    ds, unit, label, at = CASES[case](accuracy, kinematics)
    cpu = time.process_time() - t0
    w = ds.interference.values / unit
    rows = [dict(at=x, force=float(np.interp(x, w, ds.force.values)),
                 contact_area=float(np.interp(x, w, ds.contact_area.values)),
                 max_equivalent_strain=float(np.interp(x, w, ds.max_equivalent_strain.values)))
            for x in at]
    return dict(case=case, accuracy=accuracy, kinematics=kinematics, cpu_seconds=cpu,
                steps=int(ds.attrs["steps"]), step_cuts=int(ds.attrs["total_step_cuts"]),
                completed=int(ds.attrs["completed"]), abscissa=label, at=rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--presets", nargs="+", default=["draft", "standard"])
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--out", type=Path, default=OUT, help="JSON file")
    args = ap.parse_args()
    rows = []
    for case in args.cases:
        for accuracy in args.presets:
            for kinematics in ("small", "finite"):
                row = run(case, accuracy, kinematics)
                rows.append(row)
                print(f"{case:10s} {accuracy:9s} {kinematics:7s} CPU {row['cpu_seconds']:7.1f} s  "
                      + "  ".join(f"{r['at']:g}: F {r['force']:.4g} A {r['contact_area']:.4g} "
                                  f"eps {r['max_equivalent_strain']:.3f}" for r in row["at"]),
                      flush=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=Path(__file__).parent).stdout.strip()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(dict(commit=commit, date=time.strftime("%Y-%m-%dT%H:%M:%S%z"),
                                        machine=platform.processor() or platform.machine(),
                                        rows=rows), indent=1) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
