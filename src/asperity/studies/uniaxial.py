"""Uniaxial material-point scenes and the accuracy study of the integrators.

Report section 5 (B1900+Hf at 871 C: creep, Fig. 5.1; ten tension-compression
cycles, Fig. 5.2; 5000 s loading then 5000 s relaxation, Fig. 5.3; 1000 s
loading then 1000 s creep, Fig. 5.4), 6.3.1 (aluminum 6061-T4 tension,
Fig. 6.14) and 8.2.1 (SAE 1020 steel tension, Fig. 8.13), with the
Bodner-Partom model of 3.2.2 (flow rule, isotropic hardening 3.13,
directional hardening 3.14, damage 3.15) as implemented by
`asperity.fe.materials.bodner_partom.BodnerPartom` and driven by
`asperity.uniaxial.run_uniaxial`.

A scene's ``uniaxial`` section is a list of tests, each an
`asperity.scene.UniaxialTest` (its material, mechanisms, control, history and
integrator, in SI). Everything returned is SI.

- `run_uniaxial_test`: one test;
- `run_uniaxial_scene`: every test of the section as ONE Dataset on dims
  (test, step), shorter histories padded with NaN;
- `uniaxial_reference`: the same uniaxial problem as a small ODE system in
  time (axial stress or inelastic strain, Z^I, beta_11, the rescaled damage
  kappa), integrated with `scipy.integrate.solve_ivp` (LSODA, rtol 1e-10;
  Radau agrees to 1e-8): the reference of the tests and of the accuracy
  study, independent of both integrators;
- `accuracy_study`: steps, wall time and the end error of the implicit
  (backward Euler) and the explicit (predictor-corrector 3.33-3.36)
  integrators over a sweep of tolerances, per test.

The accuracy study measures two regimes (both are in the file; the numbers are
in the docs, theory/plane-strain-uniaxial.md):

1. a pairing of tolerances: the implicit integrator at its default tolerance
   against the explicit *reference* (the report's own scheme of 3.6 at a tight
   tolerance), both within the target of the ODE reference
   (``steps_ratio_reference``);
2. matched accuracy: for each integrator the fewest steps of its sweep
   whose end error is within the target (``steps_to_target``, hence
   ``steps_ratio_matched``). On stiff sets (aluminum, n = 5.8, D0 = 1e8/s;
   steel) the explicit step is limited by stability, not accuracy.
"""

from __future__ import annotations

import math
import time as _time
from typing import Sequence

import numpy as np
import xarray as xr
from scipy.integrate import solve_ivp

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.scene.materials import CONSTANTS, DAMAGE_CONSTANTS
from asperity.scene.uniaxial import EFFECTS, PLOTS, IntegratorStudy, UniaxialTest
from asperity.uniaxial.point import run_uniaxial, uniaxial_flow_stress

__all__ = [
    "run_uniaxial_test",
    "run_uniaxial_scene",
    "uniaxial_reference",
    "accuracy_study",
    "response_name",
]

#: per-step variables of `run_uniaxial` written to the scene's file
STEP_VARS = ("time", "strain", "stress", "hardness", "hardness_isotropic",
             "hardness_directional", "damage", "inelastic_strain", "lateral_strain",
             "plastic_work", "dt")


def response_name(control: str) -> str:
    """The response of a history: the stress under strain control, the
    strain under stress control (where the stress is prescribed)."""
    return "stress" if control == "strain" else "strain"


def run_uniaxial_test(test: UniaxialTest, *, integrator: str | None = None,
                      tolerance: float | None = None, outputs: int | None = None) -> xr.Dataset:
    """One test through `run_uniaxial` (Dataset on dim ``step``).

    ``integrator``, ``tolerance`` (implicit: the error indicator's; explicit:
    the predictor-corrector's) and ``outputs`` (implicit: the initial step is
    the duration / outputs; explicit: output intervals) are the test's own
    unless given (the accuracy study sweeps them)."""
    mat = test.body()
    integrator = integrator or test.integrator
    tol = float(tolerance if tolerance is not None else test.tolerance)
    outputs = int(outputs if outputs is not None else test.outputs)
    kw = dict(tol=tol) if integrator == "implicit" else dict(explicit_tol=tol)
    try:
        return run_uniaxial(mat, list(test.history), integrator=integrator, control=test.control,
                            steps=outputs, **kw)
    except (ValueError, RuntimeError) as err:
        raise type(err)(f"test {test.name}: {err}") from err


def _var(dims, values, units, long_name):
    return (dims, values, dict(units=units, long_name=long_name))


def run_uniaxial_scene(tests: Sequence[UniaxialTest]) -> xr.Dataset:
    """Every test of a scene's ``uniaxial`` section as one Dataset (SI).

    Dims ``test`` (the tests' names) and ``step`` (step 0 the initial
    state; a test with fewer steps is padded with NaN, ``records`` says how
    many are its own).  Per step: time, strain, stress, hardness (Z^I + Z^D),
    hardness_isotropic, hardness_directional, damage, inelastic_strain,
    lateral_strain, plastic_work, dt.  Per test: steps (accepted integration
    steps, explicit sub-steps included), rejected_steps, records, wall_time,
    ruptured, rupture_time (NaN if not), integrator, tolerance, control,
    material (preset), the mechanisms' flags ``effect_<mechanism>``, every
    constant (NaN where the preset has none), the closed-form steady flow
    stresses of constant-rate tension (flow_stress_initial at Z0,
    flow_stress_saturated at Z1), and the figure hints panel and plot.
    """
    tests = list(tests)
    names = [t.name for t in tests]
    if len(set(names)) != len(names):
        raise ValueError(f"uniaxial test names must be unique, got {names}")
    runs, mats = [], []
    for t in tests:
        mats.append(t.body())
        runs.append(run_uniaxial_test(t))
    nmax = max(r.sizes["step"] for r in runs)
    nt = len(tests)
    data = {}
    for k in STEP_VARS:
        arr = np.full((nt, nmax), np.nan)
        for i, r in enumerate(runs):
            arr[i, : r.sizes["step"]] = r[k].values
        data[k] = _var(("test", "step"), arr, runs[0][k].attrs["units"],
                       runs[0][k].attrs["long_name"])
    data["hardness"][2]["long_name"] = "hardness Z = Z^I + Z^D (3.13, 3.14)"
    data["records"] = _var("test", np.array([r.sizes["step"] for r in runs]), "1",
                           "steps recorded for this test (the rest is NaN padding)")
    data["steps"] = _var("test", np.array([r.attrs["steps"] for r in runs]), "1",
                         "accepted integration steps (explicit: sub-steps)")
    data["rejected_steps"] = _var("test", np.array([r.attrs["rejected_steps"] for r in runs]),
                                  "1", "rejected integration steps")
    data["wall_time"] = _var("test", np.array([r.attrs["wall_time"] for r in runs]), "s",
                             "wall time of the integration")
    data["ruptured"] = _var("test", np.array([bool(r.attrs["ruptured"]) for r in runs]), "1",
                            "rupture declared (w reached omega_rupture, or creep runaway)")
    data["rupture_time"] = _var("test", np.array([r.attrs.get("rupture_time", np.nan)
                                                  for r in runs], float), "s", "rupture time")
    data["integrator"] = _var("test", np.array([r.attrs["integrator"] for r in runs], object),
                              "1", "time integrator (implicit: backward Euler; explicit: "
                                   "predictor-corrector 3.33-3.36)")
    data["tolerance"] = _var("test", np.array([t.tolerance for t in tests]),
                             "1", "tolerance of the error indicator (3.36)")
    data["control"] = _var("test", np.array([t.control for t in tests], object), "1",
                           "controlled axial quantity (strain or stress)")
    data["history_kind"] = _var("test", np.array([t.history_kind for t in tests], object),
                                "1", "kind of load history")
    data["material"] = _var("test", np.array([t.preset for t in tests], object), "1",
                            "constant set of the report the test starts from")
    data["test_title"] = _var("test", np.array([t.title for t in tests], object), "1",
                              "what the test reproduces")
    data["panel"] = _var("test", np.array([t.panel for t in tests], object),
                         "1", "figure panel the test is drawn in")
    data["plot"] = _var("test", np.array([t.plot for t in tests], object),
                        "1", "what the panel plots (x-y): " + ", ".join(PLOTS))
    for m in EFFECTS:
        data[f"effect_{m}"] = _var("test", np.array([bool(getattr(mat, m)) for mat in mats]),
                                   "1", f"mechanism switched on: {m.replace('_', ' ')}")
    for table in (CONSTANTS, DAMAGE_CONSTANTS):
        for field, _, unit, long_name in table.values():
            data[field] = _var("test", np.array([float(getattr(mat, field)) for mat in mats]),
                               unit, long_name)
    flow0, flow1 = np.full(nt, np.nan), np.full(nt, np.nan)
    for i, (t, mat) in enumerate(zip(tests, mats)):
        if t.control == "strain" and t.history_kind == "constant_rate":
            rate = abs(float(t.rate))
            flow0[i] = math.copysign(uniaxial_flow_stress(mat, rate), float(t.value))
            if mat.isotropic_hardening:
                flow1[i] = math.copysign(uniaxial_flow_stress(mat, rate, mat.Z1), float(t.value))
    data["flow_stress_initial"] = _var(
        "test", flow0, "Pa", "steady flow stress at the test's strain rate with Z = Z0 "
        "(closed form; constant-rate strain-controlled tests)")
    data["flow_stress_saturated"] = _var(
        "test", flow1, "Pa", "steady flow stress at the test's strain rate with Z = Z1 "
        "(closed form; the bound of isotropic hardening)")
    data["damage_softening"] = _var("test", np.array([mat.damage_softening for mat in mats],
                                                     object), "1",
                                    "softening by damage: report Z sqrt(1 - w^2), bodner Z (1 - w)")
    ds = xr.Dataset(data, coords={
        "test": ("test", np.array(names, object), dict(units="1", long_name="uniaxial test")),
        "step": ("step", np.arange(nmax),
                 dict(units="1", long_name="step index (0: initial state)")),
    })
    return ds


# ------------------------------------------------------------ the ODE reference
def _rhs(mat: BodnerPartom, times, values, control):
    """Right-hand side of the uniaxial problem on segment k (report 3.2.2).

    Uniaxially sigma = diag(s, 0, 0): J2 = s^2 / 3, u = sign(s) e1 e1, so
    beta = b e1 e1, Z^D = b sign(s), and (flow rule)
    eps_n_11_dot = sign(s) (2/sqrt3) D0 exp[-1/2 (Z_eff / |s|)^(2n)];
    W_p_dot = |s| |eps_n_11_dot|; (3.13) for Z^I, (3.14) for b, the rescaled
    damage kappa_dot = rate (Q_hat / H_hat)^nu with Q_hat = (A + C) s^+ + B |s|.
    Strain control: y = (s, eps_n, Z^I, b, kappa), s_dot = E (eps_dot - eps_n_dot);
    stress control: y = (eps_n, Z^I, b, kappa) with s(t) given.
    """
    c = 2.0 / math.sqrt(3.0) * mat.D0
    tn = 2.0 * mat.n

    def soft(kap):
        if not mat.damage or kap <= 0:
            return 1.0
        w = math.exp(-(kap ** -mat.damage_p))
        return math.sqrt(1.0 - w * w) if mat.damage_softening == "report" else 1.0 - w

    def f(t, y, k):
        rate = (values[k + 1] - values[k]) / (times[k + 1] - times[k])
        if control == "strain":
            s, _, zi, b, kap = y
        else:
            _, zi, b, kap = y
            s = values[k] + rate * (t - times[k])
        sg = math.copysign(1.0, s) if s != 0 else 0.0
        a = abs(s)
        Z = zi + (b * sg if mat.directional_hardening else 0.0)
        Z = max(Z * soft(kap), 0.0)
        pd = c * math.exp(-0.5 * (Z / a) ** tn) if a > 0 else 0.0
        wd = a * pd
        dz = mat.m1 * (mat.Z1 - zi) * wd if mat.isotropic_hardening else 0.0
        db = 0.0
        if mat.recovery:
            x = (zi - mat.Z2) / mat.Z1
            dz -= mat.A1 * mat.Z1 * math.copysign(abs(x) ** mat.r1, x)
        if mat.directional_hardening:
            db = mat.m2 * (mat.Z3 * sg - b) * wd
            if mat.recovery:
                db -= mat.A2 * mat.Z1 * math.copysign((abs(b) / mat.Z1) ** mat.r2, b)
        dk = 0.0
        if mat.damage:
            q = (mat.damage_A + mat.damage_C) * max(s, 0.0) + mat.damage_B * a
            dk = mat.damage_rate * (q / mat.damage_H) ** mat.damage_nu if q > 0 else 0.0
        if control == "strain":
            return [mat.E * (rate - sg * pd), sg * pd, dz, db, dk]
        return [sg * pd, dz, db, dk]

    return f


def uniaxial_reference(material: BodnerPartom, history, control: str = "strain", *,
                       rtol: float = 1e-10, method: str = "LSODA",
                       times=None) -> xr.Dataset:
    """The uniaxial history integrated to high accuracy as an ODE system.

    `solve_ivp` (``method``, ``rtol``; absolute tolerances 1e-6 Z0 on
    stresses and hardnesses, 1e-14 on strains, 1e-12 on kappa) segment by
    segment of the piecewise linear history (the rates jump at its
    breakpoints), independent of the two integrators of `run_uniaxial`.
    With damage, the integration stops where w reaches omega_rupture
    (kappa = kappa_r, an event); the creep runaway criterion of
    `BodnerPartom` is not modelled here.

    Returns a Dataset on dim ``step`` at ``times`` (default: the history's
    breakpoints; times after a rupture are dropped): time, strain, stress,
    inelastic_strain, hardness_isotropic, hardness_directional (b sign s),
    hardness, damage; attrs nfev, wall_time, ruptured, rupture_time.
    """
    h = np.asarray(history, float)
    tb, vb = h[:, 0], h[:, 1]
    if control not in ("strain", "stress"):
        raise ValueError("control is 'strain' or 'stress'")
    f = _rhs(material, tb, vb, control)
    fs = 1e-6 * material.Z0
    if control == "strain":
        y = np.array([0.0, 0.0, material.Z0, 0.0, 0.0])
        atol = np.array([fs, 1e-14, fs, fs, 1e-12])
    else:
        y = np.array([0.0, material.Z0, 0.0, 0.0])
        atol = np.array([1e-14, fs, fs, 1e-12])
    want = np.unique(np.asarray(tb if times is None else times, float))
    if want[0] < tb[0] or want[-1] > tb[-1] + 1e-12 * (tb[-1] - tb[0]):
        raise ValueError("reference times must lie within the history")
    events = None
    if material.damage:
        kr = material.kappa_rupture

        def rupture(t, y, k):
            return y[-1] - kr

        rupture.terminal = True
        rupture.direction = 1
        events = rupture
    wall0 = _time.perf_counter()
    out_t, out_y = [], []
    nfev = 0
    rupture_time = None
    if want[0] == tb[0]:
        out_t.append(tb[0])
        out_y.append(y.copy())
    for k in range(len(tb) - 1):
        a, b = tb[k], tb[k + 1]
        sel = want[(want > a) & (want <= b)]
        r = solve_ivp(f, (a, b), y, method=method, rtol=rtol, atol=atol, args=(k,),
                      t_eval=np.union1d(sel, [b]), events=events)
        nfev += int(r.nfev)
        if r.status < 0:
            raise RuntimeError(f"reference integration failed on segment {k}: {r.message}")
        rt = np.asarray(r.t, float)
        ry = np.asarray(r.y, float).reshape(y.size, rt.size)
        keep = np.isin(rt, sel)
        out_t += list(rt[keep])
        out_y += list(ry.T[keep])
        if rt.size:
            y = ry[:, -1]
        if r.status == 1:   # rupture event
            rupture_time = float(r.t_events[0][0])
            out_t.append(rupture_time)
            out_y.append(r.y_events[0][0])
            break
    Y = np.array(out_y)
    t = np.array(out_t)
    if control == "strain":
        s, en = Y[:, 0], Y[:, 1]
        strain = np.interp(t, tb, vb)
    else:
        en = Y[:, 0]
        s = np.interp(t, tb, vb)
        strain = s / material.E + en
    zi, bb, kap = Y[:, -3], Y[:, -2], Y[:, -1]
    zd = bb * np.sign(s) if material.directional_hardening else np.zeros_like(s)
    w = material.damage_from_kappa(np.maximum(kap, 0.0)) if material.damage else 0.0 * s
    ds = xr.Dataset({
        "time": _var("step", t, "s", "time"),
        "strain": _var("step", strain, "1", "axial strain eps_11"),
        "stress": _var("step", s, "Pa", "axial stress sigma_11"),
        "inelastic_strain": _var("step", en, "1", "axial inelastic strain eps_n_11"),
        "hardness_isotropic": _var("step", zi, "Pa", "isotropic hardness Z^I"),
        "hardness_directional": _var("step", zd, "Pa", "directional hardness Z^D"),
        "hardness": _var("step", zi + zd, "Pa", "hardness Z = Z^I + Z^D"),
        "damage": _var("step", np.asarray(w, float), "1", "isotropic damage omega"),
    }, coords={"step": ("step", np.arange(t.size), dict(units="1", long_name="output index"))})
    ds.attrs.update(method=method, rtol=rtol, nfev=nfev,
                    wall_time=_time.perf_counter() - wall0,
                    ruptured=int(rupture_time is not None))
    if rupture_time is not None:
        ds.attrs["rupture_time"] = rupture_time
    return ds


# ------------------------------------------------------------ accuracy study
def _end_error(run: xr.Dataset, ref_value: float, key: str, t_end: float) -> float:
    if abs(float(run.time[-1]) - t_end) > 1e-9 * max(t_end, 1.0):
        return math.nan      # did not reach the end (rupture): no end value
    return abs(float(run[key][-1]) / ref_value - 1.0)


def accuracy_study(study: IntegratorStudy) -> xr.Dataset:
    """Steps, wall time and end error of both integrators, per test and tolerance.

    For each test of `study` (its own integrator and tolerance are ignored): the
    reference end value by `uniaxial_reference` (the study's method and rtol), then
    `run_uniaxial` with each integrator at each of its tolerances (the union is the
    ``indicator_tolerance`` dim, NaN where an integrator was not run; not
    ``tolerance``, which `xarray.Dataset.sel` takes as its own keyword), with the
    study's outputs.  The error is the relative error of the response at the end of
    the history: the stress under strain control, the strain under stress control
    (the stress is prescribed there).

    Two regimes (module docstring): the ``pairing`` tolerances give
    ``steps_ratio_reference`` (explicit reference steps / implicit steps, both must
    be within ``target``) and ``steps_to_target`` (fewest steps of the sweep within
    ``target``), hence ``steps_ratio_matched``.
    """
    tests, tolerances, pairing, target = study.tests, study.tolerances, study.pairing, study.target
    implicit_outputs, explicit_outputs = study.implicit_outputs, study.explicit_outputs
    reference_rtol, reference_method = study.reference_rtol, study.reference_method
    integrators = ("implicit", "explicit")
    tol_sets = {g: sorted({float(x) for x in tolerances[g]} | {float(pairing[g])},
                          reverse=True) for g in integrators}
    tol_all = np.array(sorted(set(tol_sets["implicit"]) | set(tol_sets["explicit"]), reverse=True))
    names = [t.name for t in tests]
    nt, ng, nk = len(tests), len(integrators), tol_all.size
    steps = np.full((ng, nt, nk), np.nan)
    rejected = np.full((ng, nt, nk), np.nan)
    wall = np.full((ng, nt, nk), np.nan)
    error = np.full((ng, nt, nk), np.nan)
    end_value = np.full((ng, nt, nk), np.nan)
    ref_value = np.full(nt, np.nan)
    ref_wall = np.full(nt, np.nan)
    ref_nfev = np.zeros(nt, int)
    responses, controls = [], []
    for i, test in enumerate(tests):
        mat = test.body()
        history, control = list(test.history), test.control
        key = response_name(control)
        responses.append(key)
        controls.append(control)
        t_end = float(history[-1][0])
        ref = uniaxial_reference(mat, history, control, rtol=reference_rtol,
                                 method=reference_method)
        if ref.attrs["ruptured"]:
            raise ValueError(f"test {test.name}: ruptures before the end of its history; "
                             "the accuracy study compares end values")
        ref_value[i] = float(ref[key][-1])
        ref_wall[i] = ref.attrs["wall_time"]
        ref_nfev[i] = ref.attrs["nfev"]
        for g, integ in enumerate(integrators):
            for tol in tol_sets[integ]:
                k = int(np.nonzero(tol_all == tol)[0][0])
                run = run_uniaxial_test(test, integrator=integ, tolerance=tol,
                                        outputs=implicit_outputs if integ == "implicit"
                                        else explicit_outputs)
                steps[g, i, k] = run.attrs["steps"]
                rejected[g, i, k] = run.attrs["rejected_steps"]
                wall[g, i, k] = run.attrs["wall_time"]
                end_value[g, i, k] = float(run[key][-1])
                error[g, i, k] = _end_error(run, ref_value[i], key, t_end)
    ok = error <= target
    masked = np.where(ok, steps, np.inf)
    best = np.argmin(masked, axis=2)                                  # (ng, nt)
    found = np.isfinite(np.min(masked, axis=2))
    take = np.take_along_axis
    steps_to_target = np.where(found, take(steps, best[..., None], 2)[..., 0], np.nan)
    wall_to_target = np.where(found, take(wall, best[..., None], 2)[..., 0], np.nan)
    tol_to_target = np.where(found, tol_all[best], np.nan)
    ki = int(np.nonzero(tol_all == float(pairing["implicit"]))[0][0])
    ke = int(np.nonzero(tol_all == float(pairing["explicit"]))[0][0])
    pair_ok = ok[0, :, ki] & ok[1, :, ke]
    ratio_ref = np.where(pair_ok, steps[1, :, ke] / steps[0, :, ki], np.nan)
    ratio_matched = steps_to_target[1] / steps_to_target[0]
    G, T, K = "integrator", "test", "indicator_tolerance"
    ds = xr.Dataset({
        "steps": _var((G, T, K), steps, "1", "accepted integration steps (explicit: sub-steps)"),
        "rejected_steps": _var((G, T, K), rejected, "1", "rejected integration steps"),
        "wall_time": _var((G, T, K), wall, "s", "wall time of the integration"),
        "error": _var((G, T, K), error, "1",
                      "relative error of the response (strain control: stress; stress "
                      "control: strain) at the end of the history against the ODE reference"),
        "end_value": _var((G, T, K), end_value, "1",
                          "response at the end of the history (Pa for stress, 1 for strain)"),
        "reference_value": _var(T, ref_value, "1",
                                "reference response at the end (Pa for stress, 1 for strain)"),
        "reference_wall_time": _var(T, ref_wall, "s", "wall time of the ODE reference"),
        "reference_nfev": _var(T, ref_nfev, "1", "right-hand side evaluations of the reference"),
        "response": _var(T, np.array(responses, object), "1",
                         "the response whose end error is measured"),
        "control": _var(T, np.array(controls, object), "1", "controlled axial quantity"),
        "material": _var(T, np.array([t.preset for t in tests], object), "1",
                         "constant set of the report"),
        "steps_to_target": _var((G, T), steps_to_target, "1",
                                "fewest steps of the tolerance sweep with the end error "
                                "within the target"),
        "wall_time_to_target": _var((G, T), wall_to_target, "s",
                                    "wall time of that run"),
        "tolerance_to_target": _var((G, T), tol_to_target, "1",
                                    "largest swept tolerance with the end error within the target"),
        "steps_ratio_reference": _var(T, ratio_ref, "1",
                                      "explicit reference steps (pairing tolerance) / implicit "
                                      "steps (pairing tolerance), both within the target"),
        "steps_ratio_matched": _var(T, ratio_matched, "1",
                                    "explicit / implicit steps_to_target (matched accuracy)"),
    }, coords={
        G: (G, np.array(integrators, object),
            dict(units="1", long_name="time integrator (implicit: backward Euler with the "
                                      "consistent tangent; explicit: predictor-corrector "
                                      "3.33-3.36)")),
        T: (T, np.array(names, object), dict(units="1", long_name="uniaxial test")),
        K: (K, tol_all, dict(units="1", long_name="tolerance of the integrator's error "
                                                 "indicator (3.36)")),
    })
    ds.attrs.update(target=float(target), pairing_implicit_tolerance=float(pairing["implicit"]),
                    pairing_explicit_tolerance=float(pairing["explicit"]),
                    explicit_outputs=int(explicit_outputs), implicit_outputs=int(implicit_outputs),
                    reference=f"scipy solve_ivp {reference_method}, rtol {reference_rtol:g}",
                    error_definition="|response(T) / reference(T) - 1| at the end T of the "
                                     "history; response = stress (strain control) or strain "
                                     "(stress control)")
    return ds
