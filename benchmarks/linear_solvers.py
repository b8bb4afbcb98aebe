"""SuperLU against PARDISO on the 3-D asperity's tangents (`make bench CASE=linear`).

    python benchmarks/linear_solvers.py [--tips 0.5 0.25] [--repeats 3]

The tangent of the first Newton iteration of an elastic elliptic paraboloid (curvature
ratio 1/4, the `standard` sliding preset's mesh fractions about the Hertz ellipse, block
of 40 long semi-axes, the tip edge `--tips` times the short semi-axis: the larger the
finer), as `asperity.fe.solvers.linear.ReusedLU` factorizes it in the pressing of
`solid3d.press_3d`. For each size, one thread each (OpenBLAS and MKL):

* SuperLU (`assembly.OrderedLU`): its first factorization (minimum degree ordering and
  factors) and a factorization in the kept order;
* PARDISO (`linear.PardisoLU`, where pypardiso is installed): its first factorization
  (analysis and factors) and a numerical factorization of the kept analysis;
* a solve of each, and the residual of the solution.

Best CPU seconds of ``--repeats``. Writes benchmarks/results/linear-solvers.json
(``--out``) and prints a table; asserts nothing.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.scenes import _commit  # noqa: E402
from benchmarks.run import best_of  # noqa: E402
from benchmarks.scenes import OUT  # noqa: E402


class _Captured(BaseException):
    """Raised with the first tangent; not an Exception, so that the driver's step cuts let it
    through."""


def tangent(tip: float):
    """The first tangent the pressing factorizes, for the tip fraction `tip`."""
    from asperity.fe import LinearElastic
    from asperity.fe.discretization.geometry import EllipticParaboloid
    from asperity.fe.discretization.half_model_mesh import MeshSpec
    from asperity.fe.drivers.solid3d import press_3d
    from asperity.fe.presets import resolve
    from asperity.fe.solvers import linear
    from asperity.references.hertz import elliptic_hertz

    elastic = LinearElastic(1000.0, 0.3)
    w = 0.005
    geo = EllipticParaboloid(1.0, 0.25)
    a = float(elliptic_hertz(np.array([w]), 1.0, 0.25, elastic.contact_modulus)["semi_axis_a"][0])
    preset = dict(resolve("sliding", "standard"), tip_fraction=tip)
    spec = dataclasses.replace(MeshSpec.for_hill(geo, a, preset), half_width=40 * a, depth=40 * a,
                               coarse_size=40 * a / 3)
    captured = {}

    def capture(self, K):
        captured["K"] = K.copy()
        raise _Captured

    original = linear.ReusedLU._factor
    linear.ReusedLU._factor = capture
    try:
        press_3d(geo, elastic, np.array([w]), accuracy=dict(base="standard", normal_steps=1), mesh=spec,
                 contact_radius=a)
    except _Captured:
        pass
    finally:
        linear.ReusedLU._factor = original
    return captured["K"]


def measure(K, repeats: int) -> dict:
    from asperity.fe.discretization.assembly import OrderedLU
    from asperity.fe.solvers.linear import PardisoLU, pardiso_available

    b = np.random.default_rng(0).standard_normal(K.shape[0])
    out = {"dofs": int(K.shape[0]), "nonzeros": int(K.nnz)}
    backends = {"superlu": lambda: OrderedLU(diag_pivot_thresh=0.1)}
    if pardiso_available():
        backends["pardiso"] = PardisoLU
    for name, make in backends.items():
        first = best_of(lambda: make().factor(K), repeats, clock=time.process_time)
        solver = make()
        solver.factor(K)
        again = best_of(lambda: solver.factor(K), repeats, clock=time.process_time)
        factors = solver.factor(K)
        solve = best_of(lambda: factors.solve(b), repeats, clock=time.process_time)
        x = factors.solve(b)
        out[name] = {"first_factorization_s": first, "factorization_s": again, "solve_s": solve,
                     "residual": float(np.linalg.norm(K @ x - b) / np.linalg.norm(b))}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tips", type=float, nargs="+", default=[0.5, 0.35, 0.25])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", type=Path, default=OUT / "linear-solvers.json", help="JSON file")
    args = ap.parse_args(argv)
    result = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "commit": _commit()[0], "clock": "CPU",
              "machine": {"platform": platform.platform(), "python": platform.python_version()},
              "sizes": []}
    print("| dofs | SuperLU first / kept order | PARDISO first / kept analysis | solves |")
    for tip in args.tips:
        row = measure(tangent(tip), args.repeats)
        row["tip_fraction"] = tip
        result["sizes"].append(row)
        s, p = row["superlu"], row.get("pardiso")
        pard = (f"{p['first_factorization_s']:.3f} / {p['factorization_s']:.3f}" if p else "not installed")
        solves = f"{s['solve_s']:.4f}" + (f" / {p['solve_s']:.4f}" if p else "")
        print(f"| {row['dofs']} | {s['first_factorization_s']:.3f} / {s['factorization_s']:.3f} | {pard} "
              f"| {solves} |", flush=True)
    path, repo = args.out.resolve(), Path(__file__).resolve().parents[1]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(f"written {path.relative_to(repo) if path.is_relative_to(repo) else path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
