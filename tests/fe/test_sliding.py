"""Sliding resistance of the junction (report 3.21, 3.24-3.27): law, regularization, tangent."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.fe.contact.sliding import (FrictionLaw, ShearResistance, contact_tangent, drag_anchor,
                                 regularized_sign)

MPA = 1e6
EPS = 1e-9   # eps_b [m]


def _points(rng, n, scale):
    b = rng.normal(size=(2, n)) * scale
    tn = np.abs(rng.normal(size=n)) * 500 * MPA
    return b, tn


def test_quadratic_law_and_friction_coefficient():
    """(3.21): h = c0 + c1 s + c2 s^2 above the onset pressure; a friction
    coefficient mu is (0, mu, 0); the c0 ramp is (3.25)'s phi."""
    law = ShearResistance(c0=50 * MPA, c1=0.3, c2=1e-10, onset_pressure=1 * MPA)
    s = np.array([2, 100, 800]) * MPA
    h, dh = law(s)
    np.testing.assert_allclose(h, 50 * MPA + 0.3 * s + 1e-10 * s**2, rtol=1e-15)
    np.testing.assert_allclose(dh, 0.3 + 2e-10 * s, rtol=1e-15)
    h, dh = law(np.array([0.5 * MPA]))      # on the ramp: phi(1/2) = 3/4
    assert h[0] == pytest.approx(0.75 * 50 * MPA + 0.3 * 0.5 * MPA + 1e-10 * (0.5 * MPA) ** 2, rel=1e-14)
    mu = ShearResistance.coulomb(20.0)
    assert (mu.c0, mu.c1, mu.c2) == (0.0, 20.0, 0.0)
    np.testing.assert_allclose(mu(s)[0], 20.0 * s, rtol=1e-15)
    with pytest.raises(ValueError):
        ShearResistance(c0=-1.0)


def test_zero_normal_stress_gives_zero_shear():
    """sigma_n <= 0 (off contact): h = 0 and no NaN, whatever b (also b = 0)."""
    law = FrictionLaw(ShearResistance(c0=80 * MPA, c1=0.5, c2=1e-10), EPS)
    b = np.array([[0.0, 3e-9, -1e-12, 0.0], [0.0, 0.0, 2e-12, -4e-6]])
    tn = np.array([0.0, 0.0, -5.0, 0.0])
    t, dt_db, dt_dtn = law.traction(b, tn)
    assert np.all(t == 0.0) and np.all(dt_db == 0.0)
    assert np.all(np.isfinite(dt_dtn))
    h, dh = law.resistance(np.array([0.0, -1.0]))
    assert np.all(h == 0.0) and np.all(np.isfinite(dh))


def test_regularized_sign_is_c1():
    """phi of (3.25): -1 / 1 beyond eps, odd, continuous with its derivative at 0 and +-eps."""
    x = np.array([-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0]) * EPS
    phi, dphi = regularized_sign(x, EPS)
    np.testing.assert_allclose(phi, [-1, -1, -0.75, 0, 0.75, 1, 1], atol=1e-15)
    np.testing.assert_allclose(dphi * EPS, [0, 0, 1, 2, 1, 0, 0], atol=1e-15)
    h = 1e-6 * EPS
    for x0 in (-EPS, 0.0, EPS):
        lo, dlo = regularized_sign(np.array([x0 - h]), EPS)
        hi, dhi = regularized_sign(np.array([x0 + h]), EPS)
        assert abs(hi[0] - lo[0]) < 5e-6 and abs(dhi[0] - dlo[0]) * EPS < 5e-6


def test_direction_exact_away_from_zero_and_continuous_at_zero():
    """|b| >= eps_b: t = -h b / |b| exactly; continuous at b = 0 (t -> 0 linearly)."""
    law = FrictionLaw(ShearResistance.coulomb(0.4), EPS)
    rng = np.random.default_rng(0)
    b = rng.normal(size=(2, 50))
    b *= EPS * (1.0 + rng.random(50) * 100) / np.hypot(*b)   # |b| in [eps, 101 eps]
    tn = np.full(50, 300 * MPA)
    t, _, _ = law.traction(b, tn)
    np.testing.assert_allclose(t, -0.4 * tn * b / np.hypot(*b), rtol=1e-14)
    for r in (1e-3, 1e-6, 1e-9, 0.0):
        tb, _, _ = law.traction(np.array([[r * EPS], [-0.5 * r * EPS]]), np.array([300 * MPA]))
        assert np.hypot(*tb)[0] <= 2.0 * 0.4 * 300 * MPA * 1.12 * r + 1e-300
    # continuity of the direction at |b| = eps_b (from the stick side)
    u = np.array([[0.6], [0.8]])
    t_in, _, _ = law.traction(u * EPS * (1 - 1e-9), np.array([1.0]))
    t_out, _, _ = law.traction(u * EPS * (1 + 1e-9), np.array([1.0]))
    np.testing.assert_allclose(t_in, t_out, rtol=1e-8)


@pytest.mark.parametrize("scale", [0.3 * EPS, 3 * EPS, 1e-6])
def test_tangent_matches_finite_differences(scale):
    """d t / d b and d t / d t_N (3.26, 3.27) against central differences (1e-6)."""
    law = FrictionLaw(ShearResistance(c0=40 * MPA, c1=0.3, c2=2e-10, onset_pressure=5 * MPA), EPS)
    rng = np.random.default_rng(1)
    b, tn = _points(rng, 40, scale)
    t, dt_db, dt_dtn = law.traction(b, tn)
    hb = 1e-7 * scale
    for j in range(2):
        e = np.zeros((2, 1))
        e[j] = hb
        fd = (law.traction(b + e, tn)[0] - law.traction(b - e, tn)[0]) / (2 * hb)
        ref = np.abs(dt_db).max()
        assert np.abs(fd - dt_db[:, j]).max() <= 1e-6 * ref
    hs = 1e-6 * tn
    fd = (law.traction(b, tn + hs)[0] - law.traction(b, tn - hs)[0]) / (2 * hs)
    assert np.abs(fd - dt_dtn).max() <= 1e-6 * np.abs(dt_dtn).max()


def test_contact_tangent_against_finite_differences():
    """The 3 x 3 alpha_ij of (3.26, 3.27) for traction (t_x, t_y, -t_N(a)) with a C1 penalty."""
    from asperity.fe.contact.penalty import C1Penalty

    law = FrictionLaw(ShearResistance(c0=0.0, c1=0.5, c2=1e-10), EPS)
    pen = C1Penalty(np.array([1e17]), 1e8)
    rng = np.random.default_rng(2)
    a = np.abs(rng.normal(size=(1, 30))) * 1e-9 + 2e-9
    b = rng.normal(size=(2, 1, 30)) * EPS

    def traction(u):
        tn, dtn = pen.traction(a + u[2])
        txy, dt_db, dt_dtn = law.traction(b + u[:2], tn)
        return np.stack((txy[0], txy[1], -tn)), (tn, dtn, dt_db, dt_dtn)

    t0, (tn, dtn, dt_db, dt_dtn) = traction(np.zeros((3, 1, 30)))
    A = contact_tangent(dtn, dt_db, dt_dtn)
    h = 1e-6 * EPS
    for j in range(3):
        e = np.zeros((3, 1, 30))
        e[j] = h
        fd = (traction(e)[0] - traction(-e)[0]) / (2 * h)
        assert np.abs(fd - A[:, j]).max() <= 1e-6 * np.abs(A).max()


def test_anchor_drag_keeps_traction_and_reverses():
    """Dragging the anchor after a slipping step leaves the traction unchanged;
    reversing the motion turns the traction after 2 eps_b; off contact the
    anchor follows the point."""
    law = FrictionLaw(ShearResistance.coulomb(0.5), EPS)
    tn = np.array([100 * MPA])
    anchor = np.zeros((2, 1))
    pos = np.array([[5 * EPS], [0.0]])                 # slid 5 eps_b along +x
    t_before, _, _ = law.traction(pos - anchor, tn)
    anchor = drag_anchor(anchor, pos, tn, EPS)
    np.testing.assert_allclose(anchor, [[4 * EPS], [0.0]], rtol=1e-15)
    t_after, _, _ = law.traction(pos - anchor, tn)
    np.testing.assert_allclose(t_after, t_before, rtol=1e-15)
    assert t_after[0, 0] == pytest.approx(-0.5 * 100 * MPA)
    # reversal: back by 1.9 eps_b still resists +x motion (partly), by 2.1 eps_b it is reversed
    t_mid, _, _ = law.traction(pos - 1.9 * EPS * np.array([[1.0], [0.0]]) - anchor, tn)
    t_rev, _, _ = law.traction(pos - 2.1 * EPS * np.array([[1.0], [0.0]]) - anchor, tn)
    assert t_mid[0, 0] > 0 and t_rev[0, 0] == pytest.approx(0.5 * 100 * MPA)
    off = drag_anchor(anchor, pos, np.array([0.0]), EPS)
    np.testing.assert_allclose(off, pos)
