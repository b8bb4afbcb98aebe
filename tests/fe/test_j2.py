"""J2 plasticity with linear isotropic hardening: radial return and tangent."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.fe.materials.j2 import J2Plasticity
from asperity.uniaxial.point import run_uniaxial

E, NU, SY = 200e9, 0.3, 250e6


@pytest.mark.parametrize("H", [0.0, 2e9, 50e9])
def test_uniaxial_linear_hardening_exact(H):
    """sigma = sy + E H / (E + H) (eps - sy / E) past yield, to 1e-10."""
    mat = J2Plasticity(E, NU, SY, H)
    emax = 0.02
    ds = run_uniaxial(mat, [(0.0, 0.0), (1.0, emax)], steps=37, adaptive=False,
                      newton_tol=1e-14)
    eps = ds.strain.values
    exact = np.where(eps <= SY / E, E * eps, SY + E * H / (E + H) * (eps - SY / E))
    np.testing.assert_allclose(ds.stress.values, exact, rtol=1e-10, atol=1e-10 * SY)
    np.testing.assert_allclose(exact, mat.uniaxial_stress(eps), rtol=1e-14)
    # plastic strain: eps - sigma / E; lateral stresses are zero so eps_22 follows
    np.testing.assert_allclose(ds.inelastic_strain.values, eps - ds.stress.values / E,
                               rtol=1e-9, atol=1e-14)
    assert ds.attrs["steps"] == 37 and ds.attrs["rejected_steps"] == 0


def test_uniaxial_unloading_and_reversal():
    """Elastic unloading with slope E; reverse yield at sigma_n - 2 sigma_y(alpha)."""
    H = 10e9
    mat = J2Plasticity(E, NU, SY, H)
    ds = run_uniaxial(mat, [(0.0, 0.0), (1.0, 0.01), (3.0, -0.01)], steps=60, adaptive=False,
                      newton_tol=1e-14)
    s, e = ds.stress.values, ds.strain.values
    i = int(np.argmax(e))
    smax = s[i]
    Et = E * H / (E + H)
    np.testing.assert_allclose(smax, SY + Et * (0.01 - SY / E), rtol=1e-10)
    # unloading stays elastic until sigma = -(sy + H alpha_max)
    alpha = 0.01 - smax / E
    reverse = -(SY + H * alpha)
    el = (np.arange(len(e)) > i) & (s > reverse * (1 - 1e-12))
    np.testing.assert_allclose(s[el], smax + E * (e[el] - e[i]), rtol=1e-9, atol=1e-6 * SY)
    assert s[-1] < reverse


def _finite_difference_tangent(mat, strain, state, h=1e-8):
    """d stress / d strain by central differences in each strain component (step h)."""
    D = np.empty((strain.shape[0],) + strain.shape)
    for j in range(strain.shape[0]):
        ep, em = strain.copy(), strain.copy()
        ep[j] += h
        em[j] -= h
        D[:, j] = (mat.update(ep, state, tangent=False)[0]
                   - mat.update(em, state, tangent=False)[0]) / (2 * h)
    return D


def _random_strains(rng, n, size):
    e = rng.normal(size=(4, n)) * size
    return e


@pytest.mark.parametrize("H", [0.0, 5e9])
def test_consistent_tangent_matches_finite_differences(H):
    mat = J2Plasticity(E, NU, SY, H)
    rng = np.random.default_rng(0)
    n = 12
    st = mat.initial_state((n,))
    # a plastic history first, then a new increment
    e1 = _random_strains(rng, n, 0.004)
    _, _, st = mat.update(e1, st)
    e2 = e1 + _random_strains(rng, n, 0.003)
    s, D, new = mat.update(e2, st)
    assert np.all(new.alpha > st.alpha - 1e-300)
    Dfd = _finite_difference_tangent(mat, e2, st)
    plastic = new.alpha > st.alpha
    assert plastic.sum() >= n // 2
    err = np.abs(D - Dfd).max(axis=(0, 1)) / np.abs(D).max(axis=(0, 1))
    assert err.max() < 1e-6, err


def test_vectorized_shapes_and_elastic_points():
    mat = J2Plasticity(E, NU, SY, 1e9)
    rng = np.random.default_rng(1)
    e = rng.normal(size=(4, 3, 5)) * 0.003
    e[:, 0, 0] = 1e-5          # elastic point
    st = mat.initial_state((3, 5))
    s, D, new = mat.update(e, st, 0.1)
    assert s.shape == (4, 3, 5) and D.shape == (4, 4, 3, 5)
    np.testing.assert_allclose(D[:, :, 0, 0], mat.tangent(), rtol=1e-14)
    # point by point equals the vectorized update
    for i in range(3):
        for k in range(5):
            s1, D1, _ = mat.update(e[:, i, k], mat.initial_state(()), 0.1)
            np.testing.assert_allclose(s1, s[:, i, k], rtol=1e-13, atol=1e-6)
            np.testing.assert_allclose(D1, D[:, :, i, k], rtol=1e-13, atol=1e-3)
    np.testing.assert_allclose(new.time, 0.1)


def test_load_reversal_in_one_step_is_finite():
    mat = J2Plasticity(E, NU, SY, 0.0)
    st = mat.initial_state(())
    _, _, st = mat.update(np.array([0.02, -0.01, -0.01, 0.0]), st)
    s, D, st2 = mat.update(np.array([-0.02, 0.01, 0.01, 0.003]), st)
    assert np.all(np.isfinite(s)) and np.all(np.isfinite(D))
    from asperity.fe.materials.elastic import von_mises
    np.testing.assert_allclose(von_mises(s), SY, rtol=1e-12)


def test_validation():
    with pytest.raises(ValueError):
        J2Plasticity(E, NU, -1.0)
    with pytest.raises(ValueError):
        J2Plasticity(E, NU, SY, -1.0)
    with pytest.raises(ValueError):
        J2Plasticity(E, 0.5, SY)


# --------------------------------------------------------------- 6 components (3-D bodies)
@pytest.mark.parametrize("H", [0.0, 5e9])
def test_six_components_with_zero_out_of_plane_shears_equal_four(H):
    """The 6-component update (11, 22, 33, 12, 13, 23) with e13 = e23 = 0 is the
    4-component one: stresses, tangents and state to round-off (1e-13 relative:
    the same operations on two more zero components); the out-of-plane parts zero."""
    mat = J2Plasticity(E, NU, SY, H)
    rng = np.random.default_rng(3)
    n = 9
    e4 = _random_strains(rng, n, 0.004)
    e6 = np.zeros((6, n))
    e6[:4] = e4
    s4, D4, st4 = mat.update(e4, mat.initial_state((n,)), 1.0)
    s6, D6, st6 = mat.update(e6, mat.initial_state((n,), components=6), 1.0)
    assert st6.inelastic_strain.shape == (6, n) and D6.shape == (6, 6, n)
    np.testing.assert_allclose(s6[:4], s4, rtol=1e-13, atol=1e-13 * SY)
    np.testing.assert_allclose(D6[:4, :4], D4, rtol=1e-13, atol=1e-13 * E)
    np.testing.assert_allclose(st6.inelastic_strain[:4], st4.inelastic_strain, rtol=1e-13,
                               atol=1e-16)
    np.testing.assert_allclose(st6.alpha, st4.alpha, rtol=1e-13, atol=1e-16)
    assert np.all(s6[4:] == 0.0) and np.all(st6.inelastic_strain[4:] == 0.0)
    assert np.all(D6[4:, :4] == 0.0) and np.all(D6[:4, 4:] == 0.0)
    assert np.all(st4.alpha > 0)            # every point yielded
    with pytest.raises(ValueError, match="components"):
        mat.update(e4, st6)


@pytest.mark.parametrize("H", [0.0, 2e9])
def test_six_components_uniaxial_stress_along_a_rotated_axis(H):
    """Uniaxial stress sigma n x n along an axis n out of every coordinate plane (all six
    components nonzero): the closed-form strain of the proportional path, elastic
    sigma / E ((1 + nu) n x n - nu I) plus plastic 3/2 alpha (n x n - I / 3) with
    sigma = sy + H alpha (associated flow, dev(n x n) / |dev(n x n)| sqrt(3/2)), imposed
    in one step or in 20, returns sigma n x n to 1e-12 (the radial return is exact on a
    proportional path with linear hardening)."""
    mat = J2Plasticity(E, NU, SY, H)
    nvec = np.array([1.0, 2.0, 2.0]) / 3.0
    nn = np.outer(nvec, nvec)
    alphas = np.linspace(0.0, 0.01, 21)[1:]
    sig = SY + H * alphas

    def vec(T):
        return np.array([T[0, 0], T[1, 1], T[2, 2], T[0, 1], T[0, 2], T[1, 2]])

    eps = np.array([vec(s / E * ((1 + NU) * nn - NU * np.eye(3))
                        + 1.5 * a * (nn - np.eye(3) / 3.0)) for s, a in zip(sig, alphas)]).T
    exact = np.outer(vec(nn), sig)
    s1, _, st1 = mat.update(eps, mat.initial_state((alphas.size,), components=6))
    np.testing.assert_allclose(s1, exact, rtol=0, atol=1e-12 * SY)
    np.testing.assert_allclose(st1.alpha, alphas, rtol=1e-12)
    st = mat.initial_state((), components=6)
    for k in range(alphas.size):
        s, _, st = mat.update(eps[:, k], st)
        np.testing.assert_allclose(s, exact[:, k], rtol=0, atol=1e-12 * SY)
    np.testing.assert_allclose(st.alpha, alphas[-1], rtol=1e-12)


@pytest.mark.parametrize("H", [0.0, 5e9])
def test_six_component_tangent_matches_finite_differences(H):
    """The 6 x 6 consistent tangent (tensor shears) against central differences of the
    update (step 1e-8 on strains of 1e-3: truncation and round-off below 1e-6 relative)
    after a plastic history with all six components."""
    mat = J2Plasticity(E, NU, SY, H)
    rng = np.random.default_rng(4)
    n = 12
    e1 = rng.normal(size=(6, n)) * 0.004
    _, _, st = mat.update(e1, mat.initial_state((n,), components=6))
    e2 = e1 + rng.normal(size=(6, n)) * 0.003
    s, D, new = mat.update(e2, st)
    assert D.shape == (6, 6, n)
    Dfd = _finite_difference_tangent(mat, e2, st)
    assert (new.alpha > st.alpha).sum() >= n // 2
    err = np.abs(D - Dfd).max(axis=(0, 1)) / np.abs(D).max(axis=(0, 1))
    assert err.max() < 1e-6, err
