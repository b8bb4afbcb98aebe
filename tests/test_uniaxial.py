"""Uniaxial driver: closed forms, an ODE reference, implicit vs explicit (report 5)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.materials.j2 import J2Plasticity
from asperity.uniaxial.point import (
    aluminum_tension,
    b1900_histories,
    run_uniaxial,
    sae1020_tension,
    uniaxial_flow_stress,
)

MPA = 1e6


# ------------------------------------------------------------ closed forms
def test_flow_stress_formula_inverts_the_flow_law():
    """Uniaxially J2 = sigma^2/3, s_11 = 2 sigma / 3, and the report's
    lambda = D0 / sqrt(J2) exp(-1/2 (Z^2 / 3 J2)^n) give
    eps_n_11_dot = lambda s_11 = (2/sqrt3) D0 exp(-1/2 (Z/sigma)^(2n))."""
    mat = BodnerPartom.aluminum_6061_t4()
    rate = 1e-3
    s = uniaxial_flow_stress(mat, rate)
    J2 = s**2 / 3.0
    lam = mat.D0 / math.sqrt(J2) * math.exp(-0.5 * (mat.Z0**2 / (3.0 * J2)) ** mat.n)
    assert lam * (2.0 * s / 3.0) == pytest.approx(rate, rel=1e-12)


@pytest.mark.parametrize("name,rate,emax", [("aluminum", 1e-3, 0.02), ("b1900", 1e-4, 0.01),
                                            ("sae1020", 1e-2, 0.02)])
def test_steady_flow_plateau(name, rate, emax):
    """No hardening (Z = Z0): the stress at constant strain rate reaches
    sigma = Z0 (2 ln((2/sqrt3) D0 / eps_dot))^(-1/(2n)) to 1e-4."""
    mat = {"aluminum": BodnerPartom.aluminum_6061_t4(), "b1900": BodnerPartom.b1900_hf_871C(),
           "sae1020": BodnerPartom.sae_1020()}[name]
    mat = mat.without("isotropic_hardening", "recovery", "directional_hardening")
    ds = run_uniaxial(mat, [(0.0, 0.0), (emax / rate, emax)])
    exact = uniaxial_flow_stress(mat, rate)
    assert float(ds.stress[-1]) == pytest.approx(exact, rel=1e-4)
    assert float(ds.hardness[-1]) == mat.Z0
    # the inelastic strain rate equals the total one on the plateau
    e, en, t = ds.strain.values, ds.inelastic_strain.values, ds.time.values
    assert (en[-1] - en[-2]) / (t[-1] - t[-2]) == pytest.approx(rate, rel=1e-4)


# ------------------------------------------------------------ ODE reference
def _creep_ode(mat, S, t1):
    """The uniaxial creep problem as an ODE in (eps_n, Z^I, beta_11) (sigma > 0:
    u = e_1, Z^D = beta_11)."""

    def sgnpow(x, r):
        return math.copysign(abs(x) ** r, x)

    def f(t, y):
        en, zi, b = y
        s = S * min(t / t1, 1.0)
        Z = max(zi + b, 0.0)
        if s > 0:
            pd = 2.0 / math.sqrt(3.0) * mat.D0 * math.exp(-0.5 * (Z / s) ** (2 * mat.n))
        else:
            pd = 0.0
        wd = s * pd
        dz = mat.m1 * (mat.Z1 - zi) * wd - mat.A1 * mat.Z1 * sgnpow((zi - mat.Z2) / mat.Z1, mat.r1)
        db = mat.m2 * (mat.Z3 - b) * wd - mat.A2 * mat.Z1 * sgnpow(b / mat.Z1, mat.r2)
        return [pd, dz, db]

    return f


def test_creep_matches_high_accuracy_ode():
    """B1900+Hf (hardening, recovery, directional hardening) under 600 MPa:
    the driver's final strain within 1e-3 of solve_ivp (Radau, rtol 1e-10)."""
    mat = BodnerPartom.b1900_hf_871C()
    S, t1, T = 600 * MPA, 10.0, 1000.0
    f = _creep_ode(mat, S, t1)
    atol = [1e-14, 1e-4, 1e-4]
    r1 = solve_ivp(f, (0.0, t1), [0.0, mat.Z0, 0.0], method="Radau", rtol=1e-10, atol=atol)
    r2 = solve_ivp(f, (t1, T), r1.y[:, -1], method="Radau", rtol=1e-10, atol=atol)
    assert r1.status == 0 and r2.status == 0
    eps_ref = S / mat.E + r2.y[0, -1]
    ds = run_uniaxial(mat, [(0.0, 0.0), (t1, S), (T, S)], control="stress")
    print(f"creep: steps {ds.attrs['steps']} (+{ds.attrs['rejected_steps']} rejected), "
          f"strain {float(ds.strain[-1]):.6e} vs {eps_ref:.6e}")
    assert float(ds.strain[-1]) == pytest.approx(eps_ref, rel=1e-3)
    assert float(ds.hardness_isotropic[-1]) == pytest.approx(r2.y[1, -1], rel=1e-3)
    assert float(ds.hardness_directional[-1]) == pytest.approx(r2.y[2, -1], rel=1e-2)


# --------------------------------------------------- implicit vs explicit (report 5)
@pytest.mark.slow
@pytest.mark.parametrize("name", ["creep", "cyclic", "relaxation", "load_creep"])
def test_section5_implicit_vs_explicit_reference(name):
    """Backward Euler (default tol 1e-3) reaches the final stress (strain
    control) or strain (stress control) of the explicit predictor-corrector
    reference (tol 1e-6) within 1 %, with at least 20 times fewer steps."""
    mat = BodnerPartom.b1900_hf_871C()
    history, control = b1900_histories()[name]
    imp = run_uniaxial(mat, history, control=control, integrator="implicit")
    ref = run_uniaxial(mat, history, control=control, integrator="explicit", steps=20,
                       explicit_tol=1e-6)
    key = "stress" if control == "strain" else "strain"
    err = float(imp[key][-1]) / float(ref[key][-1]) - 1.0
    ratio = ref.attrs["steps"] / imp.attrs["steps"]
    print(f"{name}: implicit {imp.attrs['steps']} steps (+{imp.attrs['rejected_steps']} rejected,"
          f" {imp.attrs['wall_time']:.2f} s), explicit {ref.attrs['steps']} "
          f"(+{ref.attrs['rejected_steps']}, {ref.attrs['wall_time']:.2f} s), "
          f"ratio {ratio:.1f}, final {key} error {err:.2e}")
    assert abs(err) < 1e-2
    assert ratio >= 20
    # the whole curves agree too: the (dense) implicit curve at the
    # reference's output times, relative to the range of the reference
    yimp = np.interp(ref.time.values, imp.time.values, imp[key].values)
    scale = np.abs(ref[key].values).max()
    assert np.abs(yimp - ref[key].values).max() < 1e-2 * scale


# ------------------------------------------------------------ data contract
def test_dataset_contract(tmp_path):
    ds = aluminum_tension(max_strain=0.01)
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs.get("units"), name
        assert ds[name].attrs.get("long_name"), name
    for k in ("integrator", "steps", "rejected_steps", "wall_time", "ruptured", "control"):
        assert k in ds.attrs
    assert ds.attrs["integrator"] == "implicit" and ds.attrs["steps"] == ds.sizes["step"] - 1
    assert set(ds.data_vars) >= {"time", "strain", "stress", "inelastic_strain", "hardness",
                                 "damage"}
    assert ds.stress.attrs["units"] == "Pa" and ds.time.attrs["units"] == "s"
    ds.to_netcdf(tmp_path / "u.nc")


def test_named_tension_tests():
    """Figs. 6.14, 8.13: stress rises monotonically, between the steady flow
    stresses at Z0 and at the saturation Z1."""
    for fn, mat in ((aluminum_tension, BodnerPartom.aluminum_6061_t4()),
                    (sae1020_tension, BodnerPartom.sae_1020())):
        ds = fn()
        s = ds.stress.values
        assert np.all(np.diff(s) > 0)
        assert uniaxial_flow_stress(mat, 1e-3) < s[-1] < uniaxial_flow_stress(mat, 1e-3, mat.Z1)
        assert mat.Z0 < float(ds.hardness[-1]) < mat.Z1
        assert ds.attrs["steps"] < 100


def test_stiff_set_implicit_needs_far_fewer_steps():
    """Aluminum (n = 5.8, D0 = 1e8) is stiff: the explicit reference is
    stability-limited, backward Euler is not."""
    imp = aluminum_tension(max_strain=0.02)
    exp = aluminum_tension(max_strain=0.02, integrator="explicit", explicit_tol=1e-4, steps=10)
    assert float(imp.stress[-1]) == pytest.approx(float(exp.stress[-1]), rel=1e-2)
    assert exp.attrs["steps"] > 10 * imp.attrs["steps"]


def test_j2_through_the_driver_and_validation():
    mat = J2Plasticity(200e9, 0.3, 250e6, 1e9)
    ds = run_uniaxial(mat, [(0.0, 0.0), (1.0, 300e6)], control="stress", steps=10)
    assert float(ds.strain[-1]) == pytest.approx(250e6 / 200e9 + 50e6 / 1e9 + 50e6 / 200e9,
                                                 rel=1e-8)
    with pytest.raises(ValueError):
        run_uniaxial(mat, [(0.0, 0.0), (1.0, 0.01)], integrator="explicit")
    with pytest.raises(ValueError):
        run_uniaxial(mat, [(0.0, 0.1), (1.0, 0.01)])
    with pytest.raises(ValueError):
        run_uniaxial(mat, [(0.0, 0.0), (0.0, 0.01)])
