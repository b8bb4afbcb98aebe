"""Inelastic asperity along a loading-unloading history (`asperity.fe.drivers.inelastic`)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from asperity.fe import CosineHill, Cylinder, LinearElastic, Paraboloid, solve_asperity
from asperity.fe import ConvergenceError
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.drivers.inelastic import OUTPUTS, History, solve_asperity_history
from asperity.fe.materials.j2 import J2Plasticity

E, NU = 1000.0, 0.3
E_STAR = E / (1 - NU**2)
W_MAX = 0.02
LEVELS = (0.005, 0.01, 0.015, 0.02)
Y = 30.0  # Hertz first yield near w = 0.0047 (p0 = 1.6 Y)
#: a draft mesh a little finer (about 2 000 dofs): the fixed mesh must serve
#: the whole range of contact radii
ACC = dict(base="draft", growth=1.3, n_theta=6, sweeps=3, adapt_levels=6)


def _loading(ds):
    k = int(np.argmax(ds.interference.values))
    return ds.isel(step=slice(0, k + 1))


def _unloading(ds):
    k = int(np.argmax(ds.interference.values))
    return ds.isel(step=slice(k, None))


@pytest.fixture(scope="module")
def j2_elastic():
    """J2 with a yield stress so high that nothing yields."""
    mat = J2Plasticity(E, NU, 1e9)
    return solve_asperity_history(Paraboloid(1.0), mat, History.load_unload(W_MAX, 1.0),
                                  accuracy=ACC)


@pytest.fixture(scope="module")
def j2_plastic():
    mat = J2Plasticity(E, NU, Y, H=0.05 * E)
    return solve_asperity_history(Paraboloid(1.0), mat, History.load_unload(W_MAX, 1.0),
                                  accuracy=ACC)


#: report 8.2: SAE 1020 cosine hill, w/h = 13.4, tip curvature 0.042 1/um
SAE_HILL = CosineHill.from_tip(0.042e6, 2 * math.pi**2 / (13.4**2 * 0.042e6))
SAE_VELOCITY = 0.25e-6  # m/s (report 8.2.2)
SAE_W = 0.02e-6


@pytest.fixture(scope="module")
def bodner_partom_hill():
    return solve_asperity_history(SAE_HILL, BodnerPartom.sae_1020(),
                                  History.load_unload(SAE_W, SAE_VELOCITY), accuracy="draft")


# --- history ------------------------------------------------------------------
def test_history_load_unload():
    h = History.load_unload(2.0, 0.5, final_interference=1.0)
    assert h.times == (0.0, 4.0, 6.0)
    assert h(2.0) == pytest.approx(1.0)
    assert h(5.0) == pytest.approx(1.5)
    assert h.branch(1.0) == "loading" and h.branch(4.5) == "unloading"
    assert h.velocity(5.0) == pytest.approx(0.5)
    assert h.next_knot(1.0) == 4.0
    with pytest.raises(ValueError):
        History((0.0, 0.0), (0.0, 1.0))


@pytest.mark.parametrize("extra", [dict(edge_size=0.0), dict(edge_size=1.5)])
def test_rejects_an_edge_band_it_cannot_build(extra):
    with pytest.raises(ValueError, match="edge_size"):
        solve_asperity_history(Paraboloid(1.0), J2Plasticity(E, NU, 30.0),
                               History.load_unload(W_MAX, 1.0),
                               accuracy=dict(base="draft", **extra))


def test_rejects_elastic_material():
    with pytest.raises(TypeError):
        solve_asperity_history(Paraboloid(1.0), LinearElastic(E, NU),
                               History.load_unload(W_MAX, 1.0), accuracy="draft")


# --- (1) no yield: the elastic solution, both ways ------------------------------
def test_no_yield_reproduces_elastic_solver(j2_elastic):
    ds = j2_elastic
    assert bool(ds.elastic.all())
    load = _loading(ds)
    # the steps nearest to LEVELS, solved by the elastic solver at their w
    w_all = load.interference.values
    pick = np.unique([int(np.argmin(np.abs(w_all - lv))) for lv in LEVELS])
    w = w_all[pick]
    ref = solve_asperity(Paraboloid(1.0), LinearElastic(E, NU), w, accuracy="draft")
    np.testing.assert_allclose(load.force.values[pick], ref.force.values, rtol=5e-3)
    # the top of the history is a step of its own
    assert float(load.interference[-1]) == pytest.approx(W_MAX, rel=1e-12)
    assert float(load.force[-1]) == pytest.approx(float(ref.force[-1]), rel=5e-3)


def test_no_yield_unloads_along_the_loading_path(j2_elastic):
    ds = j2_elastic
    load, unload = _loading(ds), _unloading(ds)
    assert set(unload.branch.values[1:]) == {"unloading"}
    w_un = unload.interference.values
    F_back = np.interp(w_un[::-1], load.interference.values, load.force.values)[::-1]
    Fmax = float(load.force.max())
    assert np.max(np.abs(unload.force.values - F_back)) < 2e-3 * Fmax
    # zero force at zero interference (to 1 % of the largest interference)
    assert float(ds.force[-1]) <= 1e-6 * Fmax
    assert abs(ds.attrs["residual_interference"]) < 0.01 * W_MAX


def test_outputs_have_units_and_names(j2_elastic):
    ds = j2_elastic
    for name in OUTPUTS:
        assert name in ds
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
    assert ds.attrs["steps"] == ds.sizes["step"] - 1
    assert np.all(ds.dofs.values == ds.dofs.values[0]) and ds.dofs.values[0] > 100
    assert np.all(np.diff(ds.time.values) > 0)
    assert np.all(ds.wall_time.values >= 0)
    assert bool(ds.small_strain.all())
    a = ds.contact_radius.values
    np.testing.assert_allclose(ds.contact_area.values, np.pi * a**2)
    # Hertz contact radius at the top (draft mesh)
    assert float(a[np.argmax(ds.interference.values)]) == pytest.approx(math.sqrt(W_MAX), rel=0.05)


# --- (2) J2 on the Hertz paraboloid ----------------------------------------------
def test_first_yield_at_hertz_p0_1_6_Y(j2_elastic, j2_plastic):
    load = _loading(j2_elastic)
    vm = load.max_von_mises.values
    w = load.interference.values
    # the elastic solution's largest Mises stress reaches Y at w_y
    w_y = float(np.interp(Y, vm, w))
    p0 = 2 * E_STAR * math.sqrt(w_y) / math.pi  # Hertz, R = 1
    assert p0 / Y == pytest.approx(1.60, rel=0.04)
    # the plastic run is elastic up to w_y and yields right after it
    pl = _loading(j2_plastic)
    el = pl.elastic.values
    assert el[0] and not el[-1]
    first = int(np.argmin(el))
    assert float(pl.interference[first - 1]) <= w_y * 1.001
    assert float(pl.interference[first]) >= w_y * 0.999
    assert float(pl.interference[first]) <= w_y * 1.3
    # until then the same forces as the elastic run
    np.testing.assert_allclose(pl.force.values[:first], load.force.values[:first], rtol=1e-6)


def test_plastic_residual_interference_and_stiffer_unloading(j2_elastic, j2_plastic):
    ds = j2_plastic
    load, unload = _loading(ds), _unloading(ds)
    assert float(ds.max_inelastic_strain[-1]) > 1e-3
    # softer than the elastic body at the top
    assert float(load.force[-1]) < 0.97 * float(_loading(j2_elastic).force[-1])
    res = ds.attrs["residual_interference"]
    assert 0.05 * W_MAX < res < 0.6 * W_MAX
    assert float(ds.force[-1]) <= 1e-6 * float(ds.force.max())
    assert float(ds.interference[-1]) == pytest.approx(res, abs=2e-3 * W_MAX)
    # stiffness dF/dw at the same force (half the largest) on both branches
    F_star = 0.5 * float(load.force.max())

    def slope(part):
        w, F = part.interference.values, part.force.values
        o = np.argsort(F)
        w, F = w[o], F[o]
        return float(np.interp(F_star, F, np.gradient(F, w)))

    k_load, k_unload = slope(load), slope(unload)
    assert k_unload > 1.1 * k_load
    # the inelastic strain does not go back on unloading
    assert float(unload.max_inelastic_strain[-1]) >= float(unload.max_inelastic_strain[0]) - 1e-12


# --- (3) Bodner-Partom SAE 1020 hill at 0.25 um/s ---------------------------------
def test_bodner_partom_hill_load_unload(bodner_partom_hill):
    ds = bodner_partom_hill
    for name in ("time", "interference", "force", "contact_radius", "max_equivalent_strain",
                 "max_inelastic_strain", "max_von_mises", "wall_time"):
        assert np.all(np.isfinite(ds[name].values)), name
    steps = ds.attrs["steps"]
    assert steps == ds.sizes["step"] - 1 and steps >= 20
    load = _loading(ds)
    assert float(load.interference[-1]) == pytest.approx(SAE_W, rel=1e-9)
    # loading at the prescribed velocity
    np.testing.assert_allclose(load.interference.values, SAE_VELOCITY * load.time.values,
                               rtol=1e-9, atol=1e-18)
    F = load.force.values
    assert F[-1] > 0
    assert np.all(np.diff(F) >= -1e-6 * F[-1])
    assert F[-1] > F[len(F) // 2] > 0
    # yields (viscoplastic flow), small strain, permanent indentation
    assert not bool(ds.elastic[-1])
    assert bool(ds.small_strain.all())
    assert 0 < ds.attrs["residual_interference"] < SAE_W
    assert set(ds.branch.values[1:]) == {"loading", "unloading"}


# --- (4) a far too large first step is cut and recorded ---------------------------
def test_too_large_first_step_is_cut_and_recorded():
    mat = J2Plasticity(E, NU, Y, H=0.05 * E)
    hist = History.load_unload(W_MAX, 1.0)
    default_dt = 0.25 * 0.025 * W_MAX / 1.0
    lines = []
    ds = solve_asperity_history(Paraboloid(1.0), mat, hist, accuracy=ACC,
                                initial_time_step=1000 * default_dt, progress=lines.append)
    cuts = ds.step_cuts.values
    assert cuts[1] >= 5
    # one progress line per accepted step, with its time of the history's, its
    # interference, force and cuts
    assert len(lines) == ds.attrs["steps"]
    for k, line in enumerate(lines, start=1):
        t, end = re.search(r"t = (\S+) of (\S+) s,", line).groups()
        assert float(t) == pytest.approx(float(ds.time[k]), rel=1e-5)
        assert float(end) == pytest.approx(hist.end, rel=1e-5)
        w, f, c = re.search(r"w = (\S+) m, force (\S+) N, \d+ Newton iterations, (\d+) cuts",
                            line).groups()
        assert float(w) == pytest.approx(float(ds.interference[k]), rel=1e-5, abs=1e-12)
        assert float(f) == pytest.approx(float(ds.force[k]), rel=1e-5, abs=1e-12)
        assert int(c) == cuts[k]
    assert ds.attrs["total_step_cuts"] >= cuts[1]
    for name in ("force", "interference", "max_inelastic_strain", "contact_radius"):
        assert np.all(np.isfinite(ds[name].values))
    assert float(ds.interference[1]) <= 0.025 * W_MAX * (1 + 1e-9)
    assert float(_loading(ds).force[-1]) > 0
    assert 0.05 * W_MAX < ds.attrs["residual_interference"] < 0.6 * W_MAX


def test_gives_up_with_convergence_error_when_cuts_run_out():
    mat = J2Plasticity(E, NU, Y, H=0.05 * E)
    with pytest.raises(ConvergenceError) as info:
        solve_asperity_history(Paraboloid(1.0), mat, History.load_unload(W_MAX, 1.0),
                               accuracy="draft", initial_time_step=1.0, max_cuts=2)
    assert info.value.step == 1 and info.value.cuts == 2


def test_package_exports():
    import asperity.fe as fe

    assert fe.solve_asperity_history is solve_asperity_history and fe.History is History
    assert fe.J2Plasticity is J2Plasticity and fe.BodnerPartom is BodnerPartom
    for name in ("solve_asperity", "solve_asperity_adhesive", "solve_sliding", "LinearElastic",
                 "Sphere", "Paraboloid", "CosineHill", "Cylinder", "TruncatedV", "LennardJones"):
        assert name in fe.__all__ and hasattr(fe, name)


def test_unloading_to_a_prescribed_interference_and_past_zero_force():
    mat = J2Plasticity(E, NU, Y, H=0.05 * E)
    # unloading stops at a prescribed interference, still in contact
    part = solve_asperity_history(Paraboloid(1.0), mat,
                                  History.load_unload(W_MAX, 1.0, final_interference=0.6 * W_MAX),
                                  accuracy="draft")
    assert float(part.interference[-1]) == pytest.approx(0.6 * W_MAX, rel=1e-9)
    assert float(part.force[-1]) > 0 and math.isnan(part.attrs["residual_interference"])
    assert part.attrs["completed"] == 1
    # the whole history, on past the zero force crossing (detached at the end)
    full = solve_asperity_history(Paraboloid(1.0), mat, History.load_unload(W_MAX, 1.0),
                                  accuracy="draft", stop_at_zero_force=False)
    assert float(full.interference[-1]) == pytest.approx(0.0, abs=1e-15)
    assert float(full.force[-1]) == 0.0 and float(full.contact_radius[-1]) == 0.0  # detached
    res = full.attrs["residual_interference"]
    assert 0.05 * W_MAX < res < 0.6 * W_MAX
    w = full.interference.values
    after = (full.branch.values == "unloading") & (w < res - 0.002 * W_MAX)
    assert after.sum() >= 3 and np.all(full.force.values[after] == 0.0)
    assert np.all(full.force.values[(full.branch.values == "unloading") & (w > res)] > 0)


def test_plane_strain_ridge_elastic_round_trip():
    ds = solve_asperity_history(Cylinder(1.0), J2Plasticity(E, NU, 1e9),
                                History.load_unload(W_MAX, 1.0), accuracy="draft")
    assert ds.force.attrs["units"] == "N/m" and ds.contact_area.attrs["units"] == "m"
    load = _loading(ds)
    ref = solve_asperity(Cylinder(1.0), LinearElastic(E, NU), [W_MAX], accuracy="draft")
    assert float(load.force[-1]) == pytest.approx(float(ref.force[0]), rel=5e-3)
    np.testing.assert_allclose(ds.contact_area.values, 2 * ds.contact_radius.values)
    # the smoothed penalty leaves a vanishing force at first touch: counted as zero
    assert float(ds.force[-1]) <= 1e-6 * float(load.force[-1])
    assert abs(ds.attrs["residual_interference"]) < 0.01 * W_MAX


# --- the global tangent ---------------------------------------------------------
@pytest.fixture(scope="module")
def plastic_point():
    """A model and a trial field with yielding points and contact."""
    from asperity.fe.drivers.inelastic_model import InelasticModel, elastic_part
    from asperity.fe.presets import resolve
    from asperity.fe.drivers.elastic import adapted_model

    pre = resolve("inelastic", "draft")
    mat = J2Plasticity(E, NU, 5.0, H=0.1 * E)
    em, _ = adapted_model(Paraboloid(1.0), elastic_part(mat), [0.005, W_MAX], pre)
    model = InelasticModel(em.disc, Paraboloid(1.0), mat, pre, 0.2)
    u = np.zeros(em.disc.ndofs)
    zd = model.zone.dofs
    u[zd] = -0.01 * np.linspace(1.0, 0.0, len(zd))
    state = mat.initial_state(model.shape)
    return model, u, state


def test_pattern_assembly_equals_general_assembly(plastic_point):
    model, u, state = plastic_point
    _, out = model.evaluate(u, W_MAX, state, 1.0)
    assert 0.01 < float(np.mean(out["state"].alpha > 0)) < 0.9  # some points yield
    assert np.any(out["dtraction"] > 0)  # some contact
    A, B = model.jacobian(out), model.jacobian_reference(out)
    assert abs(A - B).max() <= 1e-12 * abs(B).max()


def test_tangent_is_consistent_with_the_residual(plastic_point):
    model, u, state = plastic_point
    free = model.free
    R0, out = model.evaluate(u, W_MAX, state, 1.0)
    J = model.jacobian(out)
    rng = np.random.default_rng(0)
    d = np.zeros_like(u)
    d[free] = rng.standard_normal(len(free))
    h = 1e-7 * np.linalg.norm(u) / np.linalg.norm(d)
    Rp, _ = model.evaluate(u + h * d, W_MAX, state, 1.0, tangent=False)
    Rm, _ = model.evaluate(u - h * d, W_MAX, state, 1.0, tangent=False)
    fd = (Rp - Rm)[free] / (2 * h)
    Jd = J @ d[free]
    assert np.linalg.norm(fd - Jd) <= 1e-5 * np.linalg.norm(Jd)


# --- the step control reads Newton's iterations to PACE_TOLERANCE -------------------
def _j2_sphere_steps(tolerance):
    """The J2 body of `asperity.studies.inelastic_accuracy` (E / Y = 400, perfectly plastic; here a
    paraboloid of its tip radius) at draft, pressed to 50 times its critical
    interference."""
    y = E / 400
    w_c = (math.pi * 1.6 * y / (2 * E_STAR)) ** 2
    return solve_asperity_history(Paraboloid(1.0), J2Plasticity(E, NU, y),
                                  History.loading(50 * w_c, 1.0),
                                  accuracy=dict(base="draft", tolerance=tolerance))


def test_a_tighter_newton_tolerance_does_not_shorten_the_steps(monkeypatch):
    import asperity.fe.drivers.inelastic_model as inelastic_model

    loose, tight = _j2_sphere_steps(1e-8), _j2_sphere_steps(1e-10)
    # the tighter tolerance costs iterations ...
    assert int(tight.newton_iterations.sum()) > int(loose.newton_iterations.sum())
    # ... but not steps: the same steps, the forces within the looser tolerance
    np.testing.assert_array_equal(tight.time_step.values, loose.time_step.values)
    np.testing.assert_allclose(tight.force.values[1:], loose.force.values[1:], rtol=1e-7)
    # counted to its own tolerance (the rule before), the tighter run takes other steps
    monkeypatch.setattr(inelastic_model, "PACE_TOLERANCE", 0.0)
    assert _j2_sphere_steps(1e-10).attrs["steps"] != loose.attrs["steps"]
