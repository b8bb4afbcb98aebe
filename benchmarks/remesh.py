"""Meshes that follow the contact of an inelastic history (issue #14, item 2).

Two cases, each run in this process with ``time.process_time`` (CPU time, valid
on a shared machine), for every requested preset with the preset's remeshing
on or off (``--remesh on off``; off is every preset's default):

* ``j2_sphere``: the J2 sphere of tests/fe/test_inelastic_edge.py (R = 1,
  E = 1000, nu = 0.3, elastic-perfectly plastic with E / Y = 400) pressed to
  50 times its critical interference (Hertz first yield, p0 = 1.6 Y).  Targets:
  CPU at `fine` under 5 times that at `standard`; contact area at `standard`
  within 1 % of `fine` (at the largest interference, and the largest
  difference at equal interference over the second half of the loading).
* ``viscoplastic_hill``: the SAE 1020 hill of benchmarks/run.py (report 8.2.2)
  loaded and unloaded at `standard`: CPU time and steps (target: no slower
  than the fixed mesh, 131 steps).

Writes benchmarks/results/remesh.json (``--out``; merged with what is already there, so
that the presets can be run separately: fine takes minutes) and, from what it holds,
docs/figures/remesh_contact_area.png (``--figure``; ``--cases`` with no case: the summary
and the figure only).  The summary compares every recorded run (`compare`): standard with
fine on the same kind of mesh (``against_fine``; fine's fixed mesh has the band, so it is the
reference of standard's fixed mesh with and without it), each kind of mesh with the
preset's default fixed one (``against_fixed``, with the CPU ratio and steps), each run
with fine on its default mesh (``against_fine_fixed``) and with the finest run
(``against_finest``); and gives each run's ``contact_area_scatter``::

    python benchmarks/remesh.py --cases j2_sphere --presets standard fine --remesh on off
    python benchmarks/remesh.py --cases viscoplastic_hill --presets standard --remesh on off

``--edge-band`` refines the fixed mesh along the surface where the plastic contact edge
goes (the preset key ``edge_size``, `asperity.fe.drivers.remesh.edge_band`; ``presets.EDGE_SIZE``
per preset; runs recorded as <case>/<preset>/fixed-edge): the elastic contact edge at
w_max lies well inside the plastic one (a sphere: sqrt(R w) against nearly sqrt(2 R w)),
so the elastic adaptation leaves the plastic edge's path coarse.  Fine's one mesh has
the band in every inelastic history (`presets.INELASTIC_ACCURACY`), and a scene's J2
jobs have it at standard (`asperity.population.kinds.inelastic.wants_band`), so the
J2 sphere's targets hold for standard's ``fixed-edge`` run (README, "Meshes that follow
the contact")::

    python benchmarks/remesh.py --cases j2_sphere viscoplastic_hill --presets standard --remesh off --edge-band

``--interference-step FRACTION`` caps the steps at that fraction of the largest
interference instead of 0.025 (``max_interference_step``; recorded as
<case>/<preset>/<mesh>-dw<FRACTION>), which tells the error of the steps from that of
the mesh::

    python benchmarks/remesh.py --cases j2_sphere --presets standard --remesh off --interference-step 0.005

``--presets finest`` runs the reference of the summary (``FINEST``: fine's rings adapted
as far as the elastic 'fine' preset goes, 7 sweeps to 0.002, and a band of 0.008 r_g;
recorded as <case>/finest/fixed)::

    python benchmarks/remesh.py --presets finest --remesh off

The records <case>/fine_before/... are the runs of the fine preset before it had the
band (its one mesh adapted by 7 elastic sweeps to 0.002, 37 k dofs on the sphere; the
``-edge`` ones with ``edge_size`` 0.0125 on top), kept from the measurements before
(README, "Meshes that follow the contact"): they are compared, not run again.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

from asperity.fe import J2Plasticity, Sphere
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.discretization.geometry import CosineHill
from asperity.fe.drivers.inelastic import History, solve_asperity_history
from asperity.fe.presets import ACCURACY, EDGE_SIZE

OUT = Path(__file__).with_name("results") / "remesh.json"
FIGURE = Path(__file__).resolve().parents[1] / "docs" / "figures" / "remesh_contact_area.png"

E, NU = 1000.0, 0.3
Y = E / 400
W_C = (math.pi * 1.6 * Y / (2 * E / (1 - NU**2))) ** 2



def j2_sphere(accuracy, **options):
    w_max = 50 * W_C
    return solve_asperity_history(Sphere(1.0), J2Plasticity(E, NU, Y),
                                  History.loading(w_max, 1.0), accuracy=accuracy, **options)


def viscoplastic_hill(accuracy, **options):
    ratio = np.pi / (np.sqrt(2.0) * 0.160)
    hill = CosineHill.from_aspect(ratio, 2.0 * np.pi**2 / (ratio**2 * 0.042e6))
    w_max = 0.1 * hill.height
    return solve_asperity_history(hill, BodnerPartom.sae_1020(),
                                  History.load_unload(w_max, 0.25e-6), accuracy=accuracy,
                                  **options)


CASES = {"j2_sphere": j2_sphere, "viscoplastic_hill": viscoplastic_hill}


#: the reference of the runs (``--presets finest``): fine's rings adapted to the elastic
#: solutions as far as the elastic 'fine' preset goes, and a band finer than fine's
FINEST = dict(base="fine", sweeps=ACCURACY["fine"]["sweeps"],
              target_error=ACCURACY["fine"]["target_error"], edge_size=0.008)


def run(case: str, preset: str, remesh: bool, edge: bool = False,
        interference_step: float | None = None) -> dict:
    if preset == "finest":
        accuracy = dict(FINEST)
    else:
        accuracy = dict(base=preset, remesh=remesh)
    if edge:
        accuracy["edge_size"] = EDGE_SIZE[preset]
    t0 = time.process_time()
    options = {} if interference_step is None else dict(max_interference_step=interference_step)
    ds = CASES[case](accuracy, **options)
    cpu = time.process_time() - t0
    k = int(np.argmax(ds.interference.values))
    return dict(
        cpu_seconds=cpu, steps=int(ds.attrs["steps"]), remeshes=int(ds.attrs["remeshes"]),
        newton_iterations=int(ds.newton_iterations.sum()),
        dofs_min=int(ds.dofs.min()), dofs_max=int(ds.dofs.max()),
        force_at_top=float(ds.force[k]), contact_area_at_top=float(ds.contact_area[k]),
        residual_interference=float(ds.attrs["residual_interference"]),
        interference=ds.interference.values[:k + 1].tolist(),
        force=ds.force.values[:k + 1].tolist(),
        contact_area=ds.contact_area.values[:k + 1].tolist())


def area_scatter(w, area, start: float = 0.3) -> float:
    """How much a contact area curve scatters from step to step: the largest relative
    deviation of the area from a cubic in ln w fitted to ln A over w >= `start` x the
    largest interference (tests/fe/test_inelastic_edge.py asserts it)."""
    w, area = np.asarray(w), np.asarray(area)
    late = w >= start * w.max()
    x, y = np.log(w[late]), np.log(area[late])
    return float(np.max(np.abs(np.expm1(y - np.polyval(np.polyfit(x, y, 3), x)))))


def compare(coarse: dict, fine: dict) -> dict:
    """Relative differences of `coarse` from `fine`: at the top of the loading, and
    the largest at equal interference over its second half (``_largest``), from a
    tenth to a half of it (``_largest_early``) and below a tenth (``_largest_start``;
    `fine` interpolated at `coarse`'s interferences as a power of w between its steps,
    `power_interp`)."""
    w = np.asarray(coarse["interference"])
    ranges = {"_largest": w >= 0.5 * w[-1], "_largest_early": (w >= 0.1 * w[-1]) & (w < 0.5 * w[-1]),
              "_largest_start": (w > 0) & (w < 0.1 * w[-1])}
    out = {}
    for name in ("force", "contact_area"):
        out[name + "_at_top"] = coarse[name + "_at_top"] / fine[name + "_at_top"] - 1
        for suffix, part in ranges.items():
            ref = power_interp(w[part], fine["interference"], fine[name])
            out[name + suffix] = float(np.max(np.abs(np.asarray(coarse[name])[part] / ref - 1)))
    return out


def power_interp(x, xp, fp):
    """fp(xp) at x > 0, linear in (ln x, ln f) between the points of positive xp and fp,
    and below the first of them the power law of the first two: a force or an area that
    grows like a power of the interference is interpolated without the error of a chord
    (from 0 to fine's first step in contact, a chord is 41 % above a force growing like
    w^1.5 at half the step)."""
    xp, fp = np.asarray(xp, float), np.asarray(fp, float)
    keep = (xp > 0) & (fp > 0)
    lx, lf = np.log(xp[keep]), np.log(fp[keep])
    t = np.log(np.asarray(x, float))
    out = np.interp(t, lx, lf)
    below = t < lx[0]
    out[below] = lf[0] + (t[below] - lx[0]) * (lf[1] - lf[0]) / (lx[1] - lx[0])
    return np.exp(out)


def figure(runs: dict, path: Path = FIGURE) -> bool:
    """Left, the J2 sphere's contact area over the geometric one, against w / w_c, of
    standard's meshes, fine's and the finest run; then, for each case, standard's contact
    area on each kind of mesh over fine's (fine's fixed mesh has the band; interpolated at
    standard's interferences).  False if no case has both presets."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from asperity.io.figures import save_figure

    # the band's curves last, on top: it is the mesh that agrees with fine
    kinds = {"fixed": "default fixed mesh", "remesh": "remeshing", "fixed-edge": "edge band"}
    pairs = {(case, k): (runs.get(f"{case}/standard/{k}"),
                         runs.get(f"{case}/fine/{'fixed' if k == 'fixed-edge' else k}"))
             for case in CASES for k in kinds}
    pairs = {ck: v for ck, v in pairs.items() if v[0] and v[1]}
    if not pairs:
        return False
    fig, (left, *right) = plt.subplots(1, 3, figsize=(15, 4.2))
    panels = dict(zip(CASES, right))
    titles = {"j2_sphere": ("J2 sphere", "interference / critical interference w_c"),
              "viscoplastic_hill": ("viscoplastic hill (loading)",
                                    "interference / largest interference")}

    def area_ratio(run):
        wr = np.asarray(run["interference"][1:])
        return wr / W_C, np.asarray(run["contact_area"][1:]) / (np.pi * (2 * wr - wr**2))

    for (case, kind), (standard, fine) in pairs.items():
        colour = f"C{list(kinds).index(kind)}"
        w = np.asarray(standard["interference"][1:])
        scale = W_C if case == "j2_sphere" else w[-1]
        if case == "j2_sphere":
            left.plot(*area_ratio(standard), "o-", color=colour, ms=2.5, lw=1,
                      label=f"standard, {kinds[kind]}")
        ref = power_interp(w, fine["interference"][1:], fine["contact_area"][1:])
        panels[case].plot(w / scale, 100 * (np.asarray(standard["contact_area"][1:]) / ref - 1),
                          "o-", color=colour, ms=2.5, lw=1, label=f"standard, {kinds[kind]}")
    for key, style, colour, label in (("fine/fixed", "-", "k", "fine (with the band)"),
                                      ("fine/remesh", ":", "k", "fine, remeshing"),
                                      ("finest/fixed", "--", "0.5", "finest")):
        run = runs.get(f"j2_sphere/{key}")
        if run:
            left.plot(*area_ratio(run), style, color=colour, lw=1, label=label)
    left.set(xscale="log", xlabel="interference / critical interference w_c",
             ylabel="contact area / geometric area pi (2 R w - w^2)",
             title="J2 sphere, E/Y = 400: contact area")
    left.legend(fontsize=7)
    for case, ax in panels.items():
        title, xlabel = titles[case]
        ax.axhspan(-1, 1, color="0.9", label="1 %")
        half = 25 if case == "j2_sphere" else 0.5
        ax.axvline(half, color="0.6", lw=0.8, ls=":", label="second half of the loading")
        ax.set(xscale="log", xlabel=xlabel, ylabel="standard / fine - 1 [%]", ylim=(-6, 6),
               title=f"{title}: standard's contact area against fine's")
        ax.title.set_fontsize(9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    return True


def _read(path: Path = OUT) -> dict:
    record = json.loads(path.read_text()) if path.exists() else {}
    record.update(machine=platform.platform(), python=sys.version.split()[0])
    record.setdefault("runs", {})
    return record


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES),
                    help="none: only the summary of what benchmarks/results/remesh.json holds")
    ap.add_argument("--presets", nargs="+", default=["standard", "fine"],
                    choices=["draft", "standard", "fine", "finest"],
                    help="finest: the reference of the summary (FINEST; --remesh off)")
    ap.add_argument("--remesh", nargs="+", default=["on"], choices=["on", "off"],
                    help="remeshing on, off (the fixed mesh) or both")
    ap.add_argument("--edge-band", action="store_true",
                    help="the fixed mesh refined where the plastic edge goes (edge_size "
                    f"{EDGE_SIZE}; runs recorded as <case>/<preset>/fixed-edge)")
    ap.add_argument("--interference-step", type=float, metavar="FRACTION",
                    help="the largest step as a fraction of the largest interference "
                    "(max_interference_step; default 0.025), to tell the error of the steps "
                    "from that of the mesh; runs recorded as <case>/<preset>/<mesh>-dw<FRACTION>")
    ap.add_argument("--out", type=Path, default=OUT, help="JSON file the runs are merged into")
    ap.add_argument("--figure", type=Path, default=FIGURE, help="PNG file of the summary's figure")
    args = ap.parse_args(argv)
    if args.edge_band and "on" in args.remesh:
        ap.error("--edge-band refines the fixed mesh: give --remesh off")
    if args.edge_band and {"fine", "finest"} & set(args.presets):
        ap.error("fine's and finest's one mesh have their band already")
    if "finest" in args.presets and "on" in args.remesh:
        ap.error("finest is a fixed mesh: give --remesh off")
    suffix = ("-edge" if args.edge_band else "") + (
        "" if args.interference_step is None else f"-dw{args.interference_step:g}")
    for case in args.cases:
        for preset in args.presets:
            for remesh in [m == "on" for m in args.remesh]:
                key = f"{case}/{preset}/{'remesh' if remesh else 'fixed'}{suffix}"
                r = run(case, preset, remesh, args.edge_band, args.interference_step)
                record = _read(args.out)  # other presets may run at the same time
                record["runs"][key] = r
                print(f"{key:<36s} {r['cpu_seconds']:8.1f} s CPU  {r['steps']:4d} steps  "
                      f"{r['remeshes']:2d} remeshes  dofs {r['dofs_min']}-{r['dofs_max']}  "
                      f"F {r['force_at_top']:.6g}  A {r['contact_area_at_top']:.6g}", flush=True)
                args.out.parent.mkdir(parents=True, exist_ok=True)
                args.out.write_text(json.dumps(record, indent=1))
    record = _read(args.out)
    runs = record["runs"]
    summary = dict(against_fine={}, against_fixed={}, against_fine_fixed={},
                   against_finest={})
    for key, r in sorted(runs.items()):
        case, preset, mode = key.split("/")
        # standard against fine on the same kind of mesh (fine's fixed mesh has the band)
        fine = runs.get(f"{case}/fine/{'fixed' if mode == 'fixed-edge' else mode}")
        if preset == "standard" and fine:
            summary["against_fine"][f"{case}/{mode}"] = dict(
                cpu_fine_over_standard=fine["cpu_seconds"] / r["cpu_seconds"], **compare(r, fine))
        # another kind of mesh against the preset's default fixed mesh
        fixed = runs.get(f"{case}/{preset}/fixed")
        if mode != "fixed" and fixed:
            summary["against_fixed"][key] = dict(
                cpu_over_fixed=r["cpu_seconds"] / fixed["cpu_seconds"], steps=r["steps"],
                steps_fixed=fixed["steps"], **compare(r, fixed))
        # any run against fine on its default fixed mesh
        reference = runs.get(f"{case}/fine/fixed")
        if reference and key != f"{case}/fine/fixed":
            summary["against_fine_fixed"][key] = compare(r, reference)
        finest = runs.get(f"{case}/finest/fixed")
        if finest and key != f"{case}/finest/fixed":
            summary["against_finest"][key] = compare(r, finest)
    summary["contact_area_scatter"] = {
        key: area_scatter(r["interference"], r["contact_area"]) for key, r in sorted(runs.items())}
    record["summary"] = summary
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1))
    print(json.dumps(summary, indent=1))
    print(f"written {args.out}")
    if figure(runs, args.figure):
        print(f"written {args.figure}")


if __name__ == "__main__":
    main()
