"""What the adhesive step test sees in contact at a large Tabor parameter.

`asperity.fe.drivers.adhesive_model.AdhesiveModel.continuity` takes a step whose energy balances
as continuous if the surface stayed within d/2 + 2 |dw| of the tangent predictor,
or else if the state halfway lies within d/2 + |dw| of the secant
(`AdhesiveModel.midpoint`). This script runs one adhesive aluminum asperity
(default R = 100 um, d = 0.3 nm, pressed to 40 nm, draft) and records, for every
step sent to the secant test: where it starts, its length dw, how far the surface
went from the predictor, how far the halfway state lies from the secant (as
`midpoint` measured it) and the verdict. Writes
benchmarks/results/adhesion-secant.json and prints the largest departures, each
over d, against their allowances.

    python benchmarks/adhesion_secant.py                  # R = 100 um
    python benchmarks/adhesion_secant.py --radius 300 --w-max 10
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import _commit  # noqa: E402

from asperity.fe import BodnerPartom, LennardJones, LinearElastic, Paraboloid  # noqa: E402
from asperity.fe.drivers import adhesive  # noqa: E402
from asperity.fe.drivers.adhesive_model import AdhesiveModel  # noqa: E402
from asperity.fe.solvers.adhesive import predictor  # noqa: E402

ALLOY = BodnerPartom.aluminum_6061_t4()  # the aluminum of Fig. 7.6 (report 6.3.1)
RESULTS = Path(__file__).with_name("results")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--radius", type=float, default=100.0, help="tip radius [um]")
    ap.add_argument("--w-max", type=float, default=40.0, help="deepest interference [nm]")
    ap.add_argument("--accuracy", default="draft")
    ap.add_argument("--out", type=Path, default=RESULTS / "adhesion-secant.json")
    args = ap.parse_args(argv)

    rows = []
    midpoint = AdhesiveModel.midpoint

    def recorded(self, old, new, pre):
        out = midpoint(self, old, new, pre)
        d = self.adhesion.d
        rows.append(dict(w_over_d=old.w / d, dw_over_d=(new.w - old.w) / d,
                         predictor_over_d=float(np.max(np.abs(
                             new.u - predictor(old, new.w)))) / d,
                         secant_over_d=out[2] / d,
                         touching=bool(old.contact_force > 0 and new.contact_force > 0),
                         verdict=out[0]))
        return out

    AdhesiveModel.midpoint = recorded
    law = LennardJones(1.0, 0.3e-9)
    t0 = time.process_time()
    ds = adhesive.solve_asperity_adhesive(
        Paraboloid(args.radius * 1e-6), LinearElastic(ALLOY.E, ALLOY.nu),
        law, w_max=args.w_max * 1e-9, accuracy=args.accuracy)
    cpu = time.process_time() - t0
    AdhesiveModel.midpoint = midpoint

    dw = np.abs([r["dw_over_d"] for r in rows])
    off = np.array([r["predictor_over_d"] for r in rows])
    sec = np.array([r["secant_over_d"] for r in rows])
    cont = np.array([r["verdict"] == "continuous" for r in rows])
    summary = dict(
        steps_tested=len(rows), continuous=int(cont.sum()),
        predictor_over_allowance_max=float(np.max(off / (0.5 + 2 * dw), initial=0.0)),
        predictor_minus_3dw_max=float(np.max(off - 3 * dw, initial=0.0)),
        secant_over_allowance_max_continuous=float(np.max((sec / (0.5 + dw))[cont], initial=0.0)),
        secant_minus_041dw_max_continuous=float(np.max((sec - 0.41 * dw)[cont], initial=0.0)))
    commit, dirty = _commit()
    record = dict(date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), commit=commit,
                  uncommitted_changes=dirty, tip_radius_um=args.radius, w_max_nm=args.w_max,
                  d_nm=0.3, accuracy=args.accuracy, cpu_time_s=cpu,
                  tabor_parameter=float(ds.attrs["tabor_parameter"]),
                  pull_off_force_N=float(ds.attrs["pull_off_force"]), summary=summary, steps=rows)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1) + "\n")
    print(f"R = {args.radius:g} um, Tabor parameter {record['tabor_parameter']:.2f}, "
          f"{cpu:.0f} s CPU: {len(rows)} steps off the predictor, {int(cont.sum())} continuous "
          "by the secant")
    for key, value in summary.items():
        print(f"  {key}: {value:.4g}")
    print(f"written: {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
