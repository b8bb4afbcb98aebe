"""Hard cases of the inelastic history solver (`asperity.fe.drivers.inelastic`, issue 4).

Stiff aluminum constants (n = 5.8, D0 = 1e8/s) on a cosine hill, damage
driven to rupture, a load reversal inside one step, unloading to zero
force, a first time step 1000 times too large, and the error when a step
cannot be solved: finite, correct-looking numbers or a clear error naming
the step and the interference.  Draft meshes and small hills (a few
seconds each).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from asperity.fe import ConvergenceError, CosineHill, LinearElastic, Paraboloid, solve_asperity
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.drivers.inelastic import History, solve_asperity_history
from asperity.fe.errors import RuptureError
from asperity.fe.materials.j2 import J2Plasticity

from .test_inelastic import _loading, _unloading

#: report 8.2: SAE 1020 cosine hill, w/h = 13.4, tip curvature 0.042 1/um
SAE_HILL = CosineHill.from_tip(0.042e6, 2 * math.pi**2 / (13.4**2 * 0.042e6))
V = 0.25e-6  # m/s (report 8.2.2)
W = 0.02e-6  # m
RESULTS = ("time", "interference", "force", "contact_radius", "max_equivalent_strain",
           "max_inelastic_strain", "max_von_mises", "time_step")


def _finite(ds):
    for name in RESULTS:
        assert np.all(np.isfinite(ds[name].values)), name


@pytest.fixture(scope="module")
def sae():
    """SAE 1020 (Bodner-Partom, no damage) hill loaded to 0.02 um and unloaded."""
    return solve_asperity_history(SAE_HILL, BodnerPartom.sae_1020(), History.load_unload(W, V),
                                  accuracy="draft")


#: damage driven by the Mises stress (B = 1), rupture at w = 0.5; the runaway
#: criterion out of the way (contact edges flow faster than its 1/s)
DAMAGED = replace(BodnerPartom.sae_1020().with_damage(H=220e6, nu=10.0, p=1.0, A=0.0, B=1.0,
                                                      C=0.0, omega_rupture=0.5),
                  rupture_strain_rate=1e6)


@pytest.fixture(scope="module")
def ruptured():
    return solve_asperity_history(SAE_HILL, DAMAGED, History.load_unload(W, V),
                                  accuracy="draft")


# --- stiff aluminum -------------------------------------------------------------
def test_stiff_aluminum_hill_below_the_elastic_force():
    """Aluminum 6061-T4 (report 6.3.1: n = 5.8, D0 = 1e8/s) on the aluminum
    hill of report 7.2 (w/h = pi/(sqrt 2 0.13) = 17.1, tip curvature
    0.018 1/um), pressed to 2 % of its height at 0.25 um/s and unloaded.
    Measured: F / F_elastic = 0.987, 0.913, 0.818 at a quarter, half and all
    of the loading; residual interference 0.37 w_max; 72 steps."""
    mat = BodnerPartom.aluminum_6061_t4()
    ratio = math.pi / (math.sqrt(2) * 0.13)
    amplitude = math.pi**2 / (ratio**2 * 0.018e6)
    hill = CosineHill.from_aspect(ratio, 2 * amplitude)
    w_max = 0.02 * hill.height
    ds = solve_asperity_history(hill, mat, History.load_unload(w_max, V), accuracy="draft")
    _finite(ds)
    load, unload = _loading(ds), _unloading(ds)
    assert float(load.interference[-1]) == pytest.approx(w_max, rel=1e-12)
    w, F = load.interference.values, load.force.values
    assert np.all(np.diff(F) >= 0) and F[-1] > 0                   # loading: monotone
    assert np.all(np.diff(unload.force.values) <= 0)               # unloading: monotone
    k = len(w) - 1
    pick = [k // 4, k // 2, k]
    elastic = solve_asperity(hill, LinearElastic(mat.E, mat.nu), w[pick], accuracy="draft")
    ratio_F = F[pick] / elastic.force.values
    assert np.all(ratio_F < 1.0) and np.all(ratio_F > 0.5)         # softer than elastic
    assert np.all(np.diff(ratio_F) < 0)                           # more so the deeper
    assert 0.05 * w_max < ds.attrs["residual_interference"] < 0.8 * w_max
    assert not bool(ds.elastic[-1]) and bool(ds.small_strain.all())
    assert ds.attrs["time_error_rejections"] <= ds.attrs["steps"]


# --- damage and rupture -----------------------------------------------------------
def test_damage_driven_to_rupture_is_reported_and_the_run_goes_on(sae, ruptured):
    """Measured: rupture at step 60 (t = 0.049 s, w = 12.6 nm of 20 nm), the
    first point 0.49 um from the axis (contact radius 0.69 um) and 92 nm
    below the surface (damage driven by the Mises stress, largest below
    the surface); 1034 points ruptured at the end; force at the top 0.7 %
    below the undamaged hill's."""
    ds = ruptured
    _finite(ds)
    assert ds.attrs["ruptured"] == 1 and ds.attrs["completed"] == 1
    k = ds.attrs["rupture_step"]
    assert 1 <= k <= ds.attrs["steps"]
    n_rup = ds.ruptured_points.values
    assert n_rup[k - 1] == 0 < n_rup[k] and np.all(np.diff(n_rup) >= 0)
    assert float(ds.interference[k]) == ds.attrs["rupture_interference"]
    assert 0 < ds.attrs["rupture_interference"] <= W
    assert float(ds.time[k - 1]) <= ds.attrs["rupture_time"] <= float(ds.time[k])
    # where: inside the contact, below the surface
    assert 0 <= ds.attrs["rupture_position"] < float(ds.contact_radius[k])
    assert ds.attrs["rupture_depth"] > 0
    # ruptured points keep w = omega_rupture (frozen), the rest below it
    assert float(ds.max_damage[-1]) == pytest.approx(DAMAGED.omega_rupture, rel=1e-12)
    assert float(ds.max_damage[k - 1]) < DAMAGED.omega_rupture
    # damage softens the hill; unloading still ends in a permanent indentation
    F_top, F_sound = float(_loading(ds).force[-1]), float(_loading(sae).force[-1])
    assert 0.9 * F_sound < F_top < F_sound
    assert 0 < ds.attrs["residual_interference"] < W


def test_rupture_stops_or_raises_with_the_step_and_interference(ruptured):
    k = ruptured.attrs["rupture_step"]
    w_r = ruptured.attrs["rupture_interference"]
    stopped = solve_asperity_history(SAE_HILL, DAMAGED, History.load_unload(W, V),
                                     accuracy="draft", on_rupture="stop")
    assert stopped.attrs["completed"] == 0 and stopped.attrs["steps"] == k
    assert float(stopped.interference[-1]) == pytest.approx(w_r, rel=1e-12)
    reason = stopped.attrs["stop_reason"]
    assert f"step {k}" in reason and f"{w_r:.6g} m" in reason
    np.testing.assert_allclose(stopped.force.values, ruptured.force.values[:k + 1], rtol=1e-12)
    with pytest.raises(RuptureError) as info:
        solve_asperity_history(SAE_HILL, DAMAGED, History.load_unload(W, V), accuracy="draft",
                               on_rupture="raise")
    err = info.value
    assert isinstance(err, ConvergenceError)  # the pipeline names the sample
    assert err.step == k and err.interference == pytest.approx(w_r, rel=1e-12)
    assert f"step {k}" in str(err) and "interference" in str(err) and "below the surface" in str(err)
    assert err.position == pytest.approx((ruptured.attrs["rupture_position"],
                                          ruptured.attrs["rupture_depth"]), rel=1e-12)


def test_creep_runaway_counts_as_rupture_below_the_contact():
    """With the default rupture_strain_rate (1/s) the material declares the
    runaway of tertiary creep rupture; at 0.25 um/s the hill flows faster
    than that within the first steps, where the Mises stress is largest:
    on the axis, below the surface (Hertz: 0.48 a).  Measured: step 3,
    w = 0.375 nm, r = 1.4 nm, depth 54 nm = 0.56 a; w still 7e-21."""
    mat = BodnerPartom.sae_1020().with_damage(H=220e6, nu=10.0, A=0.0, B=1.0, C=0.0)
    ds = solve_asperity_history(SAE_HILL, mat, History.load_unload(W, V), accuracy="draft",
                                on_rupture="stop")
    _finite(ds)
    k = ds.attrs["rupture_step"]
    assert 1 <= k <= 5 and ds.attrs["steps"] == k and ds.attrs["completed"] == 0
    assert float(ds.max_damage[-1]) < 1e-6  # not by damage
    a = float(ds.contact_radius[k])
    assert ds.attrs["rupture_position"] < 0.1 * a
    assert 0.3 * a < ds.attrs["rupture_depth"] < 0.8 * a


# --- load reversal inside a step ------------------------------------------------------
def test_a_step_that_would_cross_the_reversal_ends_on_it():
    """J2 on a Hertz paraboloid, first time step twice the loading time and
    no interference cap: the step ends on the knot (not a cut), the next
    ones unload."""
    mat = J2Plasticity(1000.0, 0.3, 30.0, H=50.0)
    hist = History.load_unload(0.02, 1.0)
    t1 = hist.times[1]
    ds = solve_asperity_history(Paraboloid(1.0), mat, hist, accuracy="draft",
                                initial_time_step=2 * t1, max_interference_step=1.0)
    _finite(ds)
    assert float(ds.time[1]) == t1 and float(ds.interference[1]) == 0.02
    assert int(ds.step_cuts[1]) == 0 and ds.branch.values[1] == "loading"
    assert set(ds.branch.values[2:]) == {"unloading"}
    assert np.all(np.diff(ds.interference.values[1:]) < 0)
    assert 0 < ds.attrs["residual_interference"] < 0.02


def test_knots_are_step_ends_and_restart_the_integration(sae):
    """Bodner-Partom: the reversal is a step boundary; the step after it is
    backward Euler (the loading rate jumps there), BDF2 elsewhere."""
    t = sae.time.values
    t1 = sae.attrs["history_times"][1]
    k = int(np.flatnonzero(t == t1)[0])
    assert float(sae.interference[k]) == W
    order = sae.integration_order.values
    assert order[1] == 1 and order[k + 1] == 1
    assert np.all(order[2:k + 1] == 2) and np.all(order[k + 2:] == 2)


# --- unloading to zero force ----------------------------------------------------------
def test_unloading_to_zero_force_locates_the_residual_interference(sae):
    """Measured: residual 13.47 nm of 20 nm, 99 steps; with event_tolerance
    1e-5 the estimate moves by 7e-5 w_max (bound 1e-3)."""
    ds = sae
    _finite(ds)
    res = ds.attrs["residual_interference"]
    assert 0.3 * W < res < W
    unload = _unloading(ds)
    F = unload.force.values
    assert np.all(np.diff(F) <= 0)
    assert F[-1] <= 1e-6 * float(ds.force.max()) and F[-2] > F[-1]
    assert float(ds.interference[-1]) == pytest.approx(res, abs=2e-3 * W)
    fine = solve_asperity_history(SAE_HILL, BodnerPartom.sae_1020(), History.load_unload(W, V),
                                  accuracy="draft", event_tolerance=1e-5)
    assert fine.attrs["residual_interference"] == pytest.approx(res, abs=1e-3 * W)


# --- a first step 1000 times too large --------------------------------------------------
def test_first_step_1000_times_too_large_is_cut_and_recovers(sae):
    default_dt = 0.25 * 0.025 * W / V
    ds = solve_asperity_history(SAE_HILL, BodnerPartom.sae_1020(), History.load_unload(W, V),
                                accuracy="draft", initial_time_step=1000 * default_dt)
    _finite(ds)
    # the step is clipped at the reversal (w_max, 40 times the interference
    # cap) and halved six times
    assert int(ds.step_cuts[1]) >= 6
    assert float(ds.interference[1]) <= 0.025 * W * (1 + 1e-9)
    assert float(_loading(ds).force[-1]) == pytest.approx(float(_loading(sae).force[-1]), rel=0.01)
    assert ds.attrs["residual_interference"] == pytest.approx(sae.attrs["residual_interference"],
                                                              rel=0.01)


def test_a_step_that_cannot_be_solved_names_step_and_interference():
    with pytest.raises(ConvergenceError) as info:
        solve_asperity_history(SAE_HILL, BodnerPartom.sae_1020(), History.load_unload(W, V),
                               accuracy="draft", initial_time_step=1.0, max_cuts=3)
    err = info.value
    assert err.step == 1 and err.cuts == 3
    assert "step 1" in str(err) and "interference" in str(err)
