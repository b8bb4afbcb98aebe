"""What accuracy costs for an inelastic asperity: its mesh and kinematics at each preset
against a finer run (`asperity.fe.drivers.inelastic.solve_asperity_history`).

Three cases (`CASES`), each pressed from first touch by a rigid flat:

* ``j2_sphere``: a sphere R = 1, E = 1000, nu = 0.3, elastic-perfectly plastic with
  E / Y = 400, loaded to 50 times its critical interference
  w_c = (pi p_0 / (2 E*))^2 R with p_0 = 1.6 Y, the Hertz peak pressure at first yield
  (Johnson 1985, 4.2, 6.2); strains stay near 2 %;
* ``viscoplastic_hill``: a cosine hill of SAE 1020 steel (Bodner-Partom, report 8.2.1)
  with the width-to-height ratio of report 8.2.2, loaded to a tenth of its height at
  0.25 um/s and unloaded;
* ``steel_hill``: the steepest coupled hill of ``steel_glass_bead`` (aspect
  q = kappa z_p = 1.28, amplitude C = 5 um, 2.5.1), pressed to its amplitude at
  0.25 um/s: strains far past small-strain theory's range.

Each case is run at each preset with each variant (`VARIANTS`): the preset's own fixed
mesh (``fixed``), meshes that follow the contact (``remesh``), the fixed mesh refined
along the surface where the plastic contact edge goes (``edge_band``, the preset's
`asperity.fe.presets.EDGE_SIZE`), and the fixed mesh in finite strain
(``finite_strain``, `asperity.fe.discretization.kinematics`).  The reference is the
case at the `reference` preset on its fixed mesh in small strain.  Every run's loading
branch is compared, in force and contact area, with the reference (``against`` =
reference: the discretization's error) and with the same preset's fixed mesh in small
strain (``against`` = fixed: what the variant changes), as |y / y_ref - 1|: at the
largest interference, the largest over its second half and from a tenth to a half of it,
y_ref read at the run's interferences linearly in (ln w, ln y) (`power_interp`).  Beside
them: CPU time (``time.process_time`` of the solve in this process), steps, Newton
iterations, remeshes, the largest dofs, the largest equivalent strain, and how much the
contact area scatters from step to step (`area_scatter`).
"""

from __future__ import annotations

import math
import time
from typing import Callable, Sequence

import numpy as np
import xarray as xr

from asperity.fe.discretization.geometry import CosineHill, Sphere
from asperity.fe.drivers.inelastic import History, solve_asperity_history
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.materials.j2 import J2Plasticity
from asperity.fe.presets import EDGE_SIZE
from asperity.units import attrs

__all__ = ["CASES", "VARIANTS", "area_scatter", "inelastic_accuracy", "power_interp"]

E, NU = 1000.0, 0.3
Y = E / 400
#: critical interference of the J2 sphere (module text)
W_C = (math.pi * 1.6 * Y / (2 * E / (1 - NU**2))) ** 2
#: the coupled steel hill: amplitude [m], aspect q
C, Q = 5e-6, 1.28


def _j2_sphere(accuracy: dict, kinematics: str):
    ds = solve_asperity_history(Sphere(1.0), J2Plasticity(E, NU, Y), History.loading(50 * W_C, 1.0),
                                accuracy=accuracy, kinematics=kinematics)
    return ds, W_C


def _viscoplastic_hill(accuracy: dict, kinematics: str):
    ratio = np.pi / (np.sqrt(2.0) * 0.160)
    hill = CosineHill.from_aspect(ratio, 2.0 * np.pi**2 / (ratio**2 * 0.042e6))
    w_max = 0.1 * hill.height
    ds = solve_asperity_history(hill, BodnerPartom.sae_1020(), History.load_unload(w_max, 0.25e-6),
                                accuracy=accuracy, kinematics=kinematics)
    return ds, w_max


def _steel_hill(accuracy: dict, kinematics: str):
    hill = CosineHill(C, math.sqrt(Q) / C)
    ds = solve_asperity_history(hill, BodnerPartom.sae_1020(), History.loading(C, 0.25e-6),
                                accuracy=accuracy, kinematics=kinematics,
                                mesh_levels=np.geomspace(0.01 * C, C, 6), initial_time_step=1e-4 * C / 0.25e-6)
    return ds, C


#: case -> (accuracy, kinematics) -> (history, the interference its figure is scaled by)
CASES: dict[str, Callable] = {"j2_sphere": _j2_sphere, "viscoplastic_hill": _viscoplastic_hill,
                              "steel_hill": _steel_hill}
#: variant -> (accuracy overrides given the preset, kinematics)
VARIANTS: dict[str, Callable[[str], tuple[dict, str]]] = {
    "fixed": lambda preset: ({"base": preset, "remesh": False}, "small"),
    "remesh": lambda preset: ({"base": preset, "remesh": True}, "small"),
    "edge_band": lambda preset: ({"base": preset, "remesh": False, "edge_size": EDGE_SIZE[preset]}, "small"),
    "finite_strain": lambda preset: ({"base": preset, "remesh": False}, "finite"),
}
#: case -> what its interferences are scaled by in the figure
SCALES = {"j2_sphere": "w / w_c (critical interference)", "viscoplastic_hill": "w / w_max",
          "steel_hill": "w / C (amplitude)"}
QUANTITIES = ("force", "contact_area")
RANGES = ("at_top", "second_half", "tenth_to_half")


def power_interp(x, xp, fp) -> np.ndarray:
    """fp(xp) at x > 0, linear in (ln x, ln f) between the points of positive xp and fp,
    and below the first of them the power law of the first two: a force or an area that
    grows like a power of the interference is interpolated without the error of a chord."""
    xp, fp = np.asarray(xp, float), np.asarray(fp, float)
    keep = (xp > 0) & (fp > 0)
    lx, lf = np.log(xp[keep]), np.log(fp[keep])
    t = np.log(np.asarray(x, float))
    out = np.interp(t, lx, lf)
    below = t < lx[0]
    out[below] = lf[0] + (t[below] - lx[0]) * (lf[1] - lf[0]) / (lx[1] - lx[0])
    return np.exp(out)


def area_scatter(w, area, start: float = 0.3) -> float:
    """How much a contact area curve scatters from step to step: the largest relative
    deviation of the area from a cubic in ln w fitted to ln A over w >= `start` x the
    largest interference."""
    w, area = np.asarray(w, float), np.asarray(area, float)
    late = (w >= start * w.max()) & (area > 0)
    x, y = np.log(w[late]), np.log(area[late])
    return float(np.max(np.abs(np.expm1(y - np.polyval(np.polyfit(x, y, 3), x)))))


def _loading(ds: xr.Dataset) -> dict:
    top = int(np.argmax(ds["interference"].values))
    return {name: ds[name].values[:top + 1] for name in ("interference", "force", "contact_area",
                                                        "max_equivalent_strain")}


def _differences(run: dict, ref: dict) -> np.ndarray:
    """|y / y_ref - 1| per quantity and range (module text), shaped (quantity, range)."""
    w = run["interference"]
    parts = {"second_half": w >= 0.5 * w[-1], "tenth_to_half": (w >= 0.1 * w[-1]) & (w < 0.5 * w[-1])}
    out = np.full((len(QUANTITIES), len(RANGES)), np.nan)
    for i, q in enumerate(QUANTITIES):
        out[i, 0] = abs(run[q][-1] / float(power_interp([w[-1]], ref["interference"], ref[q])[0]) - 1)
        for j, name in enumerate(RANGES[1:], start=1):
            if parts[name].any():
                y = power_interp(w[parts[name]], ref["interference"], ref[q])
                out[i, j] = float(np.max(np.abs(run[q][parts[name]] / y - 1)))
    return out


def _solve(case: str, preset: str, variant: str) -> tuple[dict, dict, float]:
    accuracy, kinematics = VARIANTS[variant](preset)
    t0 = time.process_time()
    ds, scale = CASES[case](accuracy, kinematics)
    cost = {"cpu_time": time.process_time() - t0, "steps": int(ds.attrs["steps"]),
            "step_cuts": int(ds.attrs["total_step_cuts"]), "remeshes": int(ds.attrs.get("remeshes", 0)),
            "newton_iterations": int(ds["newton_iterations"].sum()), "dofs": int(ds["dofs"].max()),
            "completed": int(ds.attrs["completed"])}
    return _loading(ds), cost, scale


def inelastic_accuracy(case: str, presets: Sequence[str], variants: Sequence[str], reference: str,
                       progress: Callable[[str], None] | None = None) -> xr.Dataset:
    """Module text, for one `case`: each of `variants` at each of `presets`, and the
    reference (``fixed`` at `reference`), which must not be among `presets`."""
    presets, variants = list(presets), list(variants)
    if case not in CASES:
        raise ValueError(f"no case {case!r}; one of {', '.join(CASES)}")
    if reference in presets:
        raise ValueError(f"the reference preset {reference!r} is among the compared presets {presets}")
    unknown = [v for v in variants if v not in VARIANTS]
    if unknown or "fixed" not in variants:
        raise ValueError(f"variants {variants}: each one of {', '.join(VARIANTS)}, and fixed among them "
                         "(what the others are compared with)")
    say = progress or (lambda text: None)
    ref, ref_cost, scale = _solve(case, reference, "fixed")
    say(f"{case} {reference} fixed (reference): {ref_cost['cpu_time']:.1f} s CPU, {ref_cost['steps']} steps")
    runs = {}
    for p in presets:
        for v in variants:
            runs[p, v] = _solve(case, p, v)[:2]
            say(f"{case} {p} {v}: {runs[p, v][1]['cpu_time']:.1f} s CPU, {runs[p, v][1]['steps']} steps")
    rows = [(p, v) for p in presets for v in variants] + [(reference, "fixed")]
    everything = {**runs, (reference, "fixed"): (ref, ref_cost)}
    all_presets = [*presets, reference]
    shape = (len(all_presets), len(variants))
    index = {(p, v): (all_presets.index(p), variants.index(v)) for p, v in rows}
    difference = np.full((*shape, 2, len(QUANTITIES), len(RANGES)), np.nan)
    cost = {k: np.full(shape, np.nan) for k in ref_cost}
    scatter, strain = np.full(shape, np.nan), np.full(shape, np.nan)
    steps = max(h["interference"].size for h, _ in everything.values())
    history = {k: np.full((*shape, steps), np.nan) for k in ("interference", "force", "contact_area")}
    for key in rows:
        h, c = everything[key]
        i, j = index[key]
        difference[i, j, 0] = _differences(h, ref)
        difference[i, j, 1] = _differences(h, everything[key[0], "fixed"][0])
        for k, v in c.items():
            cost[k][i, j] = v
        scatter[i, j] = area_scatter(h["interference"], h["contact_area"])
        strain[i, j] = float(np.max(h["max_equivalent_strain"]))
        for k in history:
            history[k][i, j, :h[k].size] = h[k]
    dims = ("preset", "variant")
    data = {"difference": ((*dims, "against", "quantity", "range"), difference, attrs(
        "1", "|y / y_ref - 1| of the loading branch: at the largest interference, the largest over its "
             "second half, from a tenth to a half (y_ref interpolated in (ln w, ln y))"))}
    meta = {"cpu_time": ("s", "CPU time of the solve"), "steps": ("1", "accepted steps"),
            "step_cuts": ("1", "step cuts"), "remeshes": ("1", "new meshes during the history"),
            "newton_iterations": ("1", "Newton iterations"), "dofs": ("1", "largest degrees of freedom"),
            "completed": ("1", "1 where the history ran to its end")}
    for k, (u, n) in meta.items():
        data[k] = (dims, cost[k], attrs(u, f"{n} (NaN: not run)"))
    data["contact_area_scatter"] = (dims, scatter, attrs(
        "1", "largest deviation of ln A from a cubic in ln w over the top 70 % of the loading"))
    data["largest_strain"] = (dims, strain, attrs("1", "largest equivalent strain of the loading branch"))
    for k, u in (("interference", "m"), ("force", "N"), ("contact_area", "m^2")):
        data[f"history_{k}"] = ((*dims, "step"), history[k], attrs(u, f"{k.replace('_', ' ')} of the loading "
                                                                     "branch at each step (NaN past its steps)"))
    coords = {
        "preset": ("preset", all_presets, attrs("", f"accuracy preset (the last, {reference}: the reference)")),
        "variant": ("variant", variants, attrs("", "mesh and kinematics: " + ", ".join(variants))),
        "against": ("against", ["reference", "fixed"], attrs(
            "", f"compared with the reference ({reference}, fixed, small strain) or the same preset's fixed mesh")),
        "quantity": ("quantity", list(QUANTITIES), attrs("", "compared quantity")),
        "range": ("range", list(RANGES), attrs("", "where along the loading")),
        "step": ("step", np.arange(steps), attrs("1", "step of the loading branch")),
    }
    return xr.Dataset(data, coords=coords, attrs={"case": case, "reference": reference,
                                                  "interference_scale": float(scale),
                                                  "interference_scale_label": SCALES[case]})
