"""Bodner-Partom material (report 3.2.2): constants, update, tangent, hard cases."""

from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.uniaxial.point import run_uniaxial

MPA = 1e6

SETS = {
    "b1900": BodnerPartom.b1900_hf_871C(),
    "aluminum": BodnerPartom.aluminum_6061_t4(),
    "sae1020": BodnerPartom.sae_1020(),
    "b1900_damage": BodnerPartom.b1900_hf_871C().with_damage(H=900 * MPA, nu=6.0, p=1.5,
                                                             A=0.5, B=0.3, C=0.2),
    "b1900_damage_bodner": BodnerPartom.b1900_hf_871C().with_damage(
        H=900 * MPA, nu=6.0, p=1.5, A=0.5, B=0.3, C=0.2, softening="bodner"),
}


def test_report_constants():
    b = BodnerPartom.b1900_hf_871C()          # report section 5
    assert (b.E, b.nu, b.D0, b.n) == (132e9, 0.0805, 1e4, 1.03)
    assert (b.Z0, b.Z1, b.Z2, b.Z3) == (2400 * MPA, 3000 * MPA, 2400 * MPA, 1150 * MPA)
    assert b.m1 == pytest.approx(0.270 / MPA) and b.m2 == pytest.approx(1.52 / MPA)
    assert (b.A1, b.A2, b.r1, b.r2) == (0.0055, 0.0055, 2.0, 2.0)
    assert b.isotropic_hardening and b.recovery and b.directional_hardening and not b.damage
    a = BodnerPartom.aluminum_6061_t4()       # report 6.3.1, corrected E and n
    assert (a.E, a.nu, a.D0, a.n, a.Z0, a.Z1) == (65e9, 0.33, 1e8, 5.8, 450 * MPA, 550 * MPA)
    assert a.m1 == pytest.approx(0.12 / MPA)
    assert a.isotropic_hardening and not (a.recovery or a.directional_hardening or a.damage)
    t6 = BodnerPartom.aluminum_6061_t6()
    assert (t6.E, t6.n) == (73.9e9, 5.0)
    s = BodnerPartom.sae_1020()               # report 8.2.1
    assert (s.E, s.nu, s.D0, s.n, s.Z0, s.Z1) == (209e9, 0.3, 1e4, 2.28, 600 * MPA, 1050 * MPA)
    assert s.m1 == pytest.approx(0.05 / MPA)


def test_flags_not_constants_switch_mechanisms():
    b = BodnerPartom.b1900_hf_871C()
    off = b.without("isotropic_hardening", "recovery", "directional_hardening")
    st = off.initial_state(())
    eps = np.array([0.01, -0.005, -0.005, 0.0])
    _, _, new = off.update(eps, st, 10.0)
    assert new.hardness_iso == off.Z0 and np.all(new.beta == 0)
    assert off.m1 == b.m1 and off.Z3 == b.Z3      # constants kept, mechanisms off
    with pytest.raises(ValueError):
        b.with_damage(H=1e9, A=0.5, B=0.6, C=0.0)
    with pytest.raises(ValueError):
        BodnerPartom(E=1e9, nu=0.3, D0=1e4, n=1.0, Z0=1e8, isotropic_hardening=True)  # no Z1
    with pytest.raises(ValueError):
        BodnerPartom(E=1e9, nu=0.3, D0=-1.0, n=1.0, Z0=1e8)


def _plastic_states(mat, rng, shape, size):
    st = mat.initial_state(shape)
    e1 = rng.normal(size=(4,) + shape) * size
    _, _, st = mat.update(e1, st, 1.0)
    e2 = e1 + rng.normal(size=(4,) + shape) * size * 0.5
    return st, e2


@pytest.mark.parametrize("name", list(SETS))
def test_consistent_tangent_matches_finite_differences(name):
    """d sigma / d eps of the backward-Euler update vs central differences (1e-5)."""
    mat = SETS[name]
    rng = np.random.default_rng(3)
    size = {"aluminum": 0.008, "sae1020": 0.004}.get(name, 0.006)
    st, e2 = _plastic_states(mat, rng, (2, 3), size)
    dt = 2.0
    s, D, new = mat.update(e2, st, dt)
    assert np.all(new.converged)
    h = 1e-7
    Dfd = np.empty_like(D)
    for j in range(4):
        ep, em = e2.copy(), e2.copy()
        ep[j] += h
        em[j] -= h
        Dfd[:, j] = (mat.update(ep, st, dt, tangent=False)[0]
                     - mat.update(em, st, dt, tangent=False)[0]) / (2 * h)
    err = np.abs(D - Dfd).max(axis=(0, 1)) / np.abs(D).max(axis=(0, 1))
    assert err.max() < 1e-5, err
    # the points flow: the tangent differs from the elastic one
    C = mat.tangent()
    assert np.abs(D - C[:, :, None, None]).max() > 1e-3 * np.abs(C).max()


def test_vectorized_equals_pointwise():
    mat = SETS["b1900_damage"]
    rng = np.random.default_rng(5)
    st, e2 = _plastic_states(mat, rng, (3, 2), 0.006)
    s, D, new = mat.update(e2, st, 3.0)
    for i in range(3):
        for k in range(2):
            sub = type(st)(**{f: np.asarray(getattr(st, f))[..., i, k]
                              for f in st.__dataclass_fields__})
            s1, D1, n1 = mat.update(e2[:, i, k], sub, 3.0)
            np.testing.assert_allclose(s1, s[:, i, k], rtol=1e-9, atol=1e-3)
            np.testing.assert_allclose(D1, D[:, :, i, k], rtol=1e-8, atol=1e-6 * mat.E)
            np.testing.assert_allclose(n1.hardness_iso, new.hardness_iso[i, k], rtol=1e-12)


def test_elastic_limits_zero_strain_and_zero_dt():
    mat = SETS["b1900_damage"]
    st = mat.initial_state((5,))
    s, D, new = mat.update(np.zeros((4, 5)), st, 1.0)
    assert np.all(s == 0) and np.all(np.isfinite(D))
    np.testing.assert_allclose(D, np.broadcast_to(mat.tangent()[:, :, None], D.shape))
    eps = np.array([0.01, -0.004, -0.004, 0.002])
    s, D, new = mat.update(eps, mat.initial_state(()), 0.0)   # dt = 0: elastic
    np.testing.assert_allclose(s, mat.tangent() @ eps, rtol=1e-12)
    assert np.all(new.inelastic_strain == 0)
    s_e, new_e, info = mat.explicit(eps, mat.initial_state(()), 0.0)
    np.testing.assert_allclose(s_e, s, rtol=1e-12)
    assert info["substeps"] == 0


def test_explicit_reference_agrees_with_implicit():
    """A 3-D strain path in many small steps: both integrators, same stress."""
    mat = SETS["b1900"]
    path = np.array([0.008, -0.003, -0.003, 0.004])
    n, T = 200, 100.0
    si = mat.initial_state(())
    se = mat.initial_state(())
    for k in range(1, n + 1):
        eps = path * math.sin(math.pi * k / n * 1.5)
        s_i, _, si = mat.update(eps, si, T / n, tangent=False)
        s_e, se, info = mat.explicit(eps, se, T / n, tol=1e-6)
    assert np.all(se.converged)
    np.testing.assert_allclose(s_i, s_e, rtol=0, atol=5e-3 * np.abs(s_e).max())
    np.testing.assert_allclose(si.hardness_iso, se.hardness_iso, rtol=1e-3)


def test_rupture_by_damage_at_analytic_time():
    """w reaches omega_rupture: the rescaled damage kappa grows as (Q/H)^nu t,
    Q = sigma uniaxially (A + B + C = 1), so t_r is known in closed form.
    Driver (implicit) and material explicit integrator both report it; no NaN."""
    H, nu, p = 800 * MPA, 8.0, 1.5
    mat = BodnerPartom.b1900_hf_871C().with_damage(H=H, nu=nu, p=p, A=0.2, B=0.5, C=0.3,
                                                   omega_rupture=0.5)
    S, t1 = 400 * MPA, 1e-6
    k = (S / H) ** nu
    kr = math.log(2.0) ** (-1.0 / p)
    t_exact = t1 + (kr - k * t1 / (nu + 1)) / k
    ds = run_uniaxial(mat, [(0.0, 0.0), (t1, S), (10 * t_exact, S)], control="stress")
    assert ds.attrs["ruptured"] == 1
    assert ds.attrs["rupture_time"] == pytest.approx(t_exact, rel=1e-6)
    assert float(ds.damage[-1]) == pytest.approx(0.5, rel=1e-12)
    assert not bool(ds.to_array().isnull().any())
    assert float(ds.time[-1]) < 10 * t_exact          # the driver stopped there
    # the explicit integrator at the material level, several points at once
    st = mat.initial_state((3,))
    sig = np.zeros((4, 3))
    sig[0] = S
    eps = np.zeros((4, 3))
    with np.errstate(all="raise"):
        _, st, _ = mat.explicit(eps, st, t1, stress=sig, stress_mask=[True] * 4, tol=1e-5)
        _, st, _ = mat.explicit(eps, st, 2 * t_exact, stress=sig, stress_mask=[True] * 4, tol=1e-5)
    assert np.all(st.ruptured)
    np.testing.assert_allclose(st.rupture_time, t_exact, rtol=1e-6)
    assert np.all(np.isfinite(st.stress)) and np.all(np.isfinite(st.strain))


def test_rupture_by_creep_runaway_is_finite():
    """A load the damaged hardness cannot carry: tertiary creep runs away and
    rupture is reported at a finite time, before w reaches omega_rupture."""
    mat = BodnerPartom.b1900_hf_871C().with_damage(H=705 * MPA, nu=10.0, p=1.0)
    with np.errstate(all="raise"):
        ds = run_uniaxial(mat, [(0.0, 0.0), (1.0, 600 * MPA), (2000.0, 600 * MPA)],
                          control="stress")
    assert ds.attrs["ruptured"] == 1
    assert 15.0 < ds.attrs["rupture_time"] < 40.0
    assert float(ds.damage[-1]) < mat.omega_rupture
    assert not bool(ds.to_array().isnull().any())


def test_stiff_aluminum_one_huge_step():
    """n = 5.8, D0 = 1e8: 5 % strain in one 50 s step converges, finite."""
    mat = BodnerPartom.aluminum_6061_t4()
    eps = np.array([0.05, -0.02, -0.02, 0.0])
    with np.errstate(all="raise"):
        s, D, st = mat.update(eps, mat.initial_state(()), 50.0)
    assert st.converged and np.all(np.isfinite(s)) and np.all(np.isfinite(D))
    assert 0 < s[0] < 2 * mat.Z1


def test_stiff_aluminum_too_large_first_step_is_cut():
    mat = BodnerPartom.aluminum_6061_t4()
    hist = [(0.0, 0.0), (50.0, 0.05)]
    ref = run_uniaxial(mat, hist)
    dt_ok = float(ref.dt[1:].min())
    ds = run_uniaxial(mat, hist, dt0=1000 * dt_ok)
    assert ds.attrs["rejected_steps"] >= 1
    assert float(ds.dt[1]) < 1000 * dt_ok                 # the first step was cut
    assert np.all(np.isfinite(ds.stress.values))
    assert float(ds.stress[-1]) == pytest.approx(float(ref.stress[-1]), rel=1e-2)


def test_load_reversal_in_one_step():
    for mat in (SETS["b1900"], SETS["aluminum"], SETS["b1900_damage"]):
        st = mat.initial_state(())
        _, _, st = mat.update(np.array([0.01, -0.005, -0.005, 0.0]), st, 10.0)
        with np.errstate(all="raise"):
            s, D, st2 = mat.update(np.array([-0.01, 0.005, 0.005, 0.0]), st, 1e-3)
            s3, D3, st3 = mat.update(np.array([-0.01, 0.005, 0.005, 0.0]), st, 1e4)
        for x in (s, D, s3, D3):
            assert np.all(np.isfinite(x))
        assert st2.converged and st3.converged and s[0] < 0 and s3[0] < 0
    # through the driver: the reversal segment in one step
    ds = run_uniaxial(SETS["b1900"], [(0.0, 0.0), (100.0, 0.01), (101.0, -0.01)],
                      steps=2, adaptive=False)
    assert ds.attrs["steps"] == 3 and float(ds.dt[-1]) == pytest.approx(1.0)
    assert np.all(np.isfinite(ds.stress.values)) and float(ds.stress[-1]) < 0


def test_state_properties_and_rates():
    mat = SETS["b1900"]
    st = mat.initial_state(())
    _, _, st = mat.update(np.array([0.01, -0.005, -0.005, 0.0]), st, 50.0)
    assert st.hardness == pytest.approx(st.hardness_iso + st.hardness_dir)
    assert st.hardness_dir > 0                  # beta along the tensile stress
    r = mat.rates(st)
    assert r["inelastic_strain"].shape == (4,) and r["inelastic_strain"][0] > 0
    # deviatoric flow
    assert abs(r["inelastic_strain"][:3].sum()) < 1e-12 * abs(r["inelastic_strain"][0])
    assert mat.contact_modulus == pytest.approx(mat.E / (1 - mat.nu**2))
