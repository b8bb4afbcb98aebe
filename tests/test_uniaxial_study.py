"""Uniaxial scenes and the integrators' accuracy study (report 5, 6.3.1, 8.2.1; issue 4).

The scene file config/scenes/bodner_partom_uniaxial.yaml is run through the
library (`run_uniaxial_scene`) and checked against closed forms and the ODE
reference; the accuracy study against the issue's claim (same end answer
within 1 %, at least 20 times fewer steps than the explicit reference).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from scipy.integrate import solve_ivp

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.io.netcdf import missing_attributes, read_dataset, write_dataset
from asperity.uniaxial.point import uniaxial_flow_stress
from asperity.scene import Units
from asperity.scene.uniaxial import IntegratorStudy, UniaxialTest
from asperity.studies.uniaxial import accuracy_study, run_uniaxial_scene, uniaxial_reference
from tests.scene_defaults import filled, filled_config

from .test_uniaxial import _creep_ode

REPO = Path(__file__).resolve().parents[1]
SCENE = yaml.safe_load((REPO / "config/scenes/bodner_partom_uniaxial.yaml").read_text())
CONFIG = yaml.safe_load((REPO / "config/config.yaml").read_text())
UNITS = SCENE["units"]
TESTS = {t["name"]: t for t in SCENE["uniaxial"]["tests"]}
MPA = 1e6
#: the ten cycles take three quarters of the scene's time; the workflow test runs them
CHEAP = [t for t in SCENE["uniaxial"]["tests"] if t["name"] != "b1900_cyclic"]


def uniaxial_test(test: dict, units: dict) -> UniaxialTest:
    """A test as the stage reads it, with the schema's defaults (a test without a
    material or effects gets SAE 1020 without mechanisms); its constants are left
    to the library to check."""
    given = {k: test[k] for k in ("constants", "damage") if k in test}
    complete = {"material": "sae_1020", "effects": [],
                **{k: v for k, v in test.items() if k not in given}}
    complete = {**filled("uniaxial", {"tests": [complete]})["tests"][0], **given}
    return UniaxialTest.from_section(complete, Units(units.get("length"), units["pressure"]))


def material_from_test(test: dict, units: dict):
    """The test's `BodnerPartom` material point."""
    return uniaxial_test(test, units).body()


def history_from_test(test: dict, units: dict):
    """The test's history [(time, value SI)] and its control."""
    t = uniaxial_test(test, units)
    return list(t.history), t.control


def run_scene(tests: list[dict], units: dict):
    return run_uniaxial_scene([uniaxial_test(t, units) for t in tests])


@pytest.fixture(scope="module")
def scene_run():
    return run_scene(CHEAP, UNITS)


# ------------------------------------------------------------ the dataset
def test_dataset_dims_units_and_padding(scene_run, tmp_path):
    ds = scene_run
    assert list(ds["test"].values) == [t["name"] for t in CHEAP]
    assert ds["stress"].dims == ("test", "step") and ds["steps"].dims == ("test",)
    assert missing_attributes(ds) == []
    assert ds.stress.attrs["units"] == "Pa" and ds.time.attrs["units"] == "s"
    assert ds.E.attrs["units"] == "Pa" and ds.m1.attrs["units"] == "Pa-1"
    # shorter histories are padded with NaN after their own records
    rec = ds["records"].values
    assert rec.max() == ds.sizes["step"] and rec.min() < rec.max()
    for i, n in enumerate(rec):
        assert np.all(np.isfinite(ds.stress.values[i, :n]))
        assert np.all(np.isnan(ds.stress.values[i, n:]))
    # implicit: one record per accepted step, plus the initial state
    np.testing.assert_array_equal(ds["steps"].values, rec - 1)
    # the scene's MPa constants in SI; mechanisms as the scene's effects say
    b = ds.sel(test="b1900_creep")
    assert float(b.E) == 132e9 and float(b.Z3) == 1150e6
    assert float(b.m1) == pytest.approx(0.270e-6, rel=1e-12)
    assert bool(b.effect_directional_hardening) and not bool(b.effect_damage)
    assert bool(ds.sel(test="b1900_creep_damage").effect_damage)
    assert float(ds.sel(test="b1900_creep_damage").damage_H) == 75e6
    flow = ds.sel(test="sae1020_steady_flow")
    assert not any(bool(flow[f"effect_{m}"]) for m in
                   ("isotropic_hardening", "recovery", "directional_hardening", "damage"))
    assert float(flow.m1) == pytest.approx(0.05e-6)       # constant kept, mechanism off
    # it round-trips through the netCDF contract
    path = write_dataset(ds, tmp_path / "uniaxial.nc", scene="t", title="t")
    back = read_dataset(path)
    assert back["effect_damage"].dtype == bool
    np.testing.assert_array_equal(back["test"].values.astype(str), ds["test"].values.astype(str))


def test_constants_units_and_effects_from_a_scene():
    t = dict(TESTS["aluminum_t4_tension"], constants={"E": 70.0, "Z0": 0.5}, effects=[])
    m = material_from_test(t, {"pressure": "GPa"})
    assert m.E == 70e9 and m.Z0 == 5e8 and m.n == 5.8
    assert not m.isotropic_hardening and m.m1 == pytest.approx(0.12e-6)
    m = material_from_test(dict(t, constants={"m1": 120.0}), {"pressure": "GPa"})
    assert m.m1 == pytest.approx(0.12e-6, rel=1e-12)           # 1/GPa -> 1/Pa
    # every constant of the report's tables is settable
    b = material_from_test(TESTS["b1900_creep"], UNITS)
    ref = BodnerPartom.b1900_hf_871C()
    for k in ("E", "nu", "D0", "n", "Z0", "Z1", "Z2", "Z3", "m1", "m2", "A1", "A2", "r1", "r2"):
        assert getattr(b, k) == pytest.approx(getattr(ref, k), rel=1e-12), k
    with pytest.raises(ValueError, match="test b1900_creep: .*damage_H"):
        material_from_test(dict(TESTS["b1900_creep"], effects=["damage"]), UNITS)
    with pytest.raises(ValueError, match="test aluminum_t4_tension: .*Z2"):
        material_from_test(dict(TESTS["aluminum_t4_tension"], effects=["recovery"]), UNITS)
    with pytest.raises(ValueError, match="unknown constant 'Z9'"):
        material_from_test(dict(TESTS["b1900_creep"], constants={"Z9": 1.0}), UNITS)


def test_history_kinds():
    h, c = history_from_test(TESTS["b1900_cyclic"], UNITS)
    assert c == "strain" and len(h) == 31
    assert h[1] == (80.0, 0.008) and h[2] == (240.0, -0.008) and h[-1] == (3200.0, 0.0)
    h, c = history_from_test(TESTS["b1900_creep"], UNITS)
    assert c == "stress" and h == [(0.0, 0.0), (10.0, 600e6), (1000.0, 600e6)]
    h, _ = history_from_test(TESTS["aluminum_t4_tension"], UNITS)
    assert h == [(0.0, 0.0), (50.0, 0.05)]
    pts = {"name": "p", "control": "stress",
           "history": {"kind": "points", "points": [[1.0, 2.0], [3.0, -1.0]]}}
    assert history_from_test(pts, UNITS)[0] == [(0.0, 0.0), (1.0, 2e6), (3.0, -1e6)]


def test_explicit_integrator_from_the_scene():
    """A test may ask for the explicit reference: `outputs` intervals, each
    sub-stepped to its tolerance; same plateau as the closed form (1e-4)."""
    t = dict(TESTS["sae1020_steady_flow"], integrator="explicit", tolerance=1e-4, outputs=10)
    ds = run_scene([t], UNITS)
    assert str(ds.integrator.values[0]) == "explicit" and int(ds.records[0]) == 11
    assert int(ds.steps[0]) > 10                     # sub-steps are counted
    exact = uniaxial_flow_stress(BodnerPartom.sae_1020(), 1e-3)
    assert float(ds.stress[0, -1]) == pytest.approx(exact, rel=1e-4)
    with pytest.raises(ValueError, match="names must be unique"):
        run_scene([t, t], UNITS)


# ------------------------------------------------------------ closed forms
def test_steady_flow_stress_closed_form(scene_run):
    """No hardening (Z = Z0), strain rate 1e-3/s: the scene's run reaches
    sigma = Z0 (2 ln((2/sqrt3) D0 / eps_dot))^(-1/(2n)) (279.59 MPa for SAE
    1020) within 1e-6 (measured 7.5e-9); the hardening tests lie between the
    closed forms at Z0 and Z1."""
    ds = scene_run
    t = ds.sel(test="sae1020_steady_flow")
    n = int(t.records)
    exact = uniaxial_flow_stress(BodnerPartom.sae_1020(), 1e-3)
    assert float(t.flow_stress_initial) == pytest.approx(exact, rel=1e-12)
    assert float(t.stress[n - 1]) == pytest.approx(exact, rel=1e-6)
    for name in ("sae1020_tension", "aluminum_t4_tension", "aluminum_t6_tension"):
        t = ds.sel(test=name)
        n = int(t.records)
        s = t.stress.values[:n]
        assert np.all(np.diff(s) > 0), name
        assert float(t.flow_stress_initial) < s[-1] < float(t.flow_stress_saturated), name


def test_reference_is_the_scalar_creep_ode():
    """`uniaxial_reference` (LSODA) against the creep ODE of
    tests/test_uniaxial.py (Radau, rtol 1e-10), written independently: end
    strain and hardnesses within 1e-8; Radau in the reference within 1e-8."""
    mat = material_from_test(TESTS["b1900_creep"], UNITS)
    S, t1, T = 600 * MPA, 10.0, 1000.0
    f = _creep_ode(mat, S, t1)
    atol = [1e-14, 1e-4, 1e-4]
    r1 = solve_ivp(f, (0.0, t1), [0.0, mat.Z0, 0.0], method="Radau", rtol=1e-10, atol=atol)
    r2 = solve_ivp(f, (t1, T), r1.y[:, -1], method="Radau", rtol=1e-10, atol=atol)
    history, control = history_from_test(TESTS["b1900_creep"], UNITS)
    for method in ("LSODA", "Radau"):
        ref = uniaxial_reference(mat, history, control, method=method)
        assert float(ref.strain[-1]) == pytest.approx(S / mat.E + r2.y[0, -1], rel=1e-8)
        assert float(ref.hardness_isotropic[-1]) == pytest.approx(r2.y[1, -1], rel=1e-8)
        assert float(ref.hardness_directional[-1]) == pytest.approx(r2.y[2, -1], rel=1e-8)


def test_scene_creep_against_the_ode_reference(scene_run):
    """The scene's creep curve (implicit, tol 1e-3, 76 steps) against the ODE
    reference at its own times: end strain within 1e-3 (measured 1.8e-4),
    the whole curve within 5e-3 of its largest strain (measured 2.3e-3),
    Z^I within 1e-3 and Z^D within 1e-2 at the end."""
    run = scene_run.sel(test="b1900_creep")
    n = int(run.records)
    mat = material_from_test(TESTS["b1900_creep"], UNITS)
    history, control = history_from_test(TESTS["b1900_creep"], UNITS)
    ref = uniaxial_reference(mat, history, control, times=run.time.values[:n])
    e, er = run.strain.values[:n], ref.strain.values
    assert e[-1] == pytest.approx(er[-1], rel=1e-3)
    assert np.abs(e - er).max() < 5e-3 * er.max()
    assert float(run.hardness_isotropic[n - 1]) == pytest.approx(
        float(ref.hardness_isotropic[-1]), rel=1e-3)
    assert float(run.hardness_directional[n - 1]) == pytest.approx(
        float(ref.hardness_directional[-1]), rel=1e-2)


def test_rupture_reported(scene_run):
    """Damage test (3.15, constants ours): under 60 MPa the rescaled damage
    grows as kappa_dot = (S/H)^nu, so w = exp(-1/kappa) reaches
    omega_rupture = 0.99 at t_r = t1 + (kappa_r - k t1/(nu+1)) / k = 935.75 s.
    The scene's run reports rupture there within 1e-3 (measured 2.4e-4; the
    ODE reference within 1e-9), w = 0.99 at the last record, and no NaN."""
    t = TESTS["b1900_creep_damage"]
    d = t["damage"]
    S, t1 = t["history"]["value"], t["history"]["ramp_time"]
    k = (S / d["H"]) ** d["nu"]
    kr = math.log(1.0 / d["omega_rupture"]) ** (-1.0 / d["p"])
    t_exact = t1 + (kr - k * t1 / (d["nu"] + 1.0)) / k
    run = scene_run.sel(test="b1900_creep_damage")
    n = int(run.records)
    assert bool(run.ruptured)
    assert float(run.rupture_time) == pytest.approx(t_exact, rel=1e-3)
    assert float(run.damage[n - 1]) == pytest.approx(0.99, abs=1e-9)
    assert float(run.time[n - 1]) < t1 + t["history"]["hold_time"]     # stopped there
    for v in ("strain", "stress", "hardness", "damage"):
        assert np.all(np.isfinite(run[v].values[:n])), v
    mat = material_from_test(t, UNITS)
    ref = uniaxial_reference(mat, *history_from_test(t, UNITS))
    assert ref.attrs["ruptured"] == 1
    assert ref.attrs["rupture_time"] == pytest.approx(t_exact, rel=1e-9)
    # the other tests do not rupture
    others = scene_run.drop_sel(test="b1900_creep_damage")
    assert not others["ruptured"].values.any()


# ------------------------------------------------------------ accuracy study
@pytest.mark.slow
def test_implicit_reaches_1_percent_with_20x_fewer_steps():
    """The issue's pairing, on the histories of config/config.yaml
    (accuracy_bodner_partom): implicit at its default tolerance (1e-3) and
    the explicit reference (1e-6) both end within 1 % of the ODE reference,
    the implicit one with at least 20 times fewer steps (measured 26-47).
    And the other regime, honestly: at the same tolerance 1e-3 the adaptive
    explicit integrator is as good on B1900+Hf (within 1 %, at most 2.5
    times the implicit steps; measured 1.1-1.7), but takes more than 20
    times the steps on the stiff aluminum and steel sets (measured 38-39)."""
    cfg = CONFIG["accuracy_bodner_partom"]
    ds = accuracy_study(IntegratorStudy.from_section(filled_config("accuracy_bodner_partom", {
        **cfg, "tolerances": {"implicit": [1e-3], "explicit": [1e-3, 1e-6]}, "target": 0.01})))
    assert missing_attributes(ds) == []
    imp = ds.sel(integrator="implicit", indicator_tolerance=1e-3)
    ref = ds.sel(integrator="explicit", indicator_tolerance=1e-6)
    same = ds.sel(integrator="explicit", indicator_tolerance=1e-3)
    print(ds[["steps", "error"]].to_dataframe().dropna())
    assert np.all(imp.error.values < 0.01) and np.all(ref.error.values < 0.01)
    assert np.all(ds.steps_ratio_reference.values >= 20), ds.steps_ratio_reference.values
    np.testing.assert_allclose(ds.steps_ratio_reference.values,
                               ref.steps.values / imp.steps.values)
    ratio_same = same.steps.values / imp.steps.values
    b1900 = ds["material"].values == "b1900_hf_871C"
    assert np.all(same.error.values[b1900] < 0.01)
    assert np.all(ratio_same[b1900] < 2.5), ratio_same
    assert np.all(ratio_same[~b1900] > 20), ratio_same
