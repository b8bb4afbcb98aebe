"""Adhesive asperities in the pipeline (report 3.3.3, 7.3): grid, plan, gather, interface.

The samples here are synthetic, built from closed forms in the shape of
`solve_asperity_adhesive`'s output: out of contact a rigid paraboloid pulled
by the Derjaguin force -2 pi R W_c(s) of the law (`derjaguin_force`, the
closed form tests/fe/test_adhesion.py checks the FE solver against); in
contact a Hertz-like branch.  ``dmt``: no jump, approach = retract;
``jkr``: the asperity jumps in at w_in < 0 and, retracting, hangs on to
w_off < w_in, where it jumps off (pull-off force P0).  Each sample's
``elastic`` flag holds below the interference `YIELD` of its branch (a hanging
contact yields earlier on retraction), its strain grows linearly to 8 % at
`LARGE_STRAIN`.  The gather and the homogenized interface are checked against
these closed forms and a direct quadrature over the peak density.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import xarray as xr

from asperity import homogenize
from asperity.population import density as population_density
from asperity.stages import homogenize as homogenize_stage
from asperity.stages import population as population_stage
from asperity.stages import surface as surface_stage
from asperity.population.kinds import adhesive as adhesive_interface
from asperity.fe.contact.adhesion import LennardJones, derjaguin_force
from asperity.peaks import JointDensity
from asperity.population.plan import interference_grid as contact_grid
from asperity.scene import Adhesion, Population, Units
from tests.scene_defaults import filled

UNITS = {"length": "um", "pressure": "MPa"}
SMOOTH = filled("surface", {"statistics": {
    "sigma": 0.013, "sigma_slope": 0.013, "sigma_curvature": 0.018,
    "peak_density": 0.058}})
MATERIAL = {"youngs_modulus": 65000.0, "poisson": 0.33}
E_STAR = 65e9 / (1 - 0.33**2)
ADHESION = {"work_of_adhesion": 1.0, "spacing": 0.5, "cutoff": 16.0}
LAW = LennardJones(1.0, 0.5e-9, 16.0)
D = LAW.d
REACH = LAW.range - D
ASPERITY = filled("asperity", {"model": "fe", "geometry": "paraboloid"})
#: the synthetic samples' first yield, per branch, and where their strain reaches 8 %
YIELD = {"approach": 20 * D, "retract": 10 * D}
LARGE_STRAIN = 40 * D
HOMOGENIZATION = filled("homogenization", {"rule": "gauss", "cells": [60, 40],
                                           "separations": {"start": 1.0, "stop": 6.0, "count": 11}})
POPULATION = filled("population", {})


# --- synthetic samples -----------------------------------------------------------------------
def closed_form(R, w, branch, kind):
    """Force [N] and contact area [m^2] of the synthetic asperity of radius R at w
    (broadcast over arrays of R and w)."""
    w, R = np.asarray(w, float), np.asarray(R, float)
    pull = -derjaguin_force(LAW, R, D - np.minimum(w, 0.0))  # rigid paraboloid, s = d - w
    if kind == "dmt":  # Hertz plus the attraction at contact, continuous at w = 0
        wp = np.maximum(w, 0.0)
        inside = w > 0
        force = np.where(inside, 4 / 3 * E_STAR * np.sqrt(R) * wp**1.5 - 2 * np.pi * R
                         * LAW.work_of_adhesion, pull)
        return force, np.where(inside, np.pi * R * wp, 0.0)
    w_in, w_off = -3 * D, -6 * D
    P0 = 1.5 * np.pi * R * LAW.work_of_adhesion
    inside = w >= (w_in if branch == "approach" else w_off)
    wc = np.maximum(w - w_off, 0.0)
    force = np.where(inside, 4 / 3 * E_STAR * np.sqrt(R) * wc**1.5 - P0, pull)
    return force, np.where(inside, np.pi * R * (wc + D), 0.0)


def fake_sample(spec, key, kind="dmt"):
    """A dataset shaped like `solve_asperity_adhesive`'s output for the job `spec`."""
    R = 1.0 / spec["curvature"]
    top = spec["range"][1]
    w_min = -REACH - 2 * D
    near = np.linspace(-REACH, 0.0, 601)[:-1]
    up = np.concatenate([near, [0.0], np.geomspace(1e-4 * D, top, 400)])
    down = np.concatenate([up[::-1][1:], np.linspace(-REACH, w_min, 20)[1:]])
    w = np.concatenate([up, down])
    branch = np.array(["approach"] * up.size + ["retract"] * down.size)
    jump = np.zeros(w.size, bool)
    if kind == "jkr":  # the states either side of each jump, 0.002 d apart
        eps = 2e-3 * D
        w_in, w_off = -3 * D, -6 * D
        a = up[up < w_in - eps]
        up = np.concatenate([a, [w_in - eps, w_in], up[up > w_in]])
        r = down[down > w_off]
        down = np.concatenate([r, [w_off, w_off - eps], down[down < w_off - eps]])
        w = np.concatenate([up, down])
        branch = np.array(["approach"] * up.size + ["retract"] * down.size)
        jump = np.zeros(w.size, bool)
        jump[a.size + 1] = True
        jump[up.size + r.size + 1] = True
    force = np.empty(w.size)
    area = np.empty(w.size)
    for b in ("approach", "retract"):  # the state before a jump is on the old branch
        m = branch == b
        force[m], area[m] = closed_form(R, w[m], b, kind)
    n = w.size
    ds = xr.Dataset({
        "interference": ("step", w, {"units": "m", "long_name": "w"}),
        "force": ("step", force, {"units": "N", "long_name": "F"}),
        "contact_area": ("step", area, {"units": "m^2", "long_name": "A"}),
        "contact_radius": ("step", np.sqrt(area / np.pi), {"units": "m", "long_name": "a"}),
        "branch": ("step", branch, {"units": "1", "long_name": "branch"}),
        "elastic": ("step", w < np.where(branch == "approach", YIELD["approach"], YIELD["retract"]),
                    {"units": "1", "long_name": "nothing yielded"}),
        "max_equivalent_strain": ("step", 0.08 * np.maximum(w, 0) / LARGE_STRAIN,
                                  {"units": "1", "long_name": "largest equivalent strain"}),
        "jump": ("step", jump, {"units": "1", "long_name": "jump"}),
        "dofs": ("step", np.full(n, 100), {"units": "1", "long_name": "dofs"}),
        "newton_iterations": ("step", np.full(n, 3), {"units": "1", "long_name": "its"}),
        "step_cuts": ("step", np.zeros(n, int), {"units": "1", "long_name": "cuts"}),
    }, coords={"step": ("step", np.arange(n), {"units": "1", "long_name": "step"})})
    retract = branch == "retract"
    pull = -force[retract].min()
    ds.attrs.update(
        key=key, status="ok", symmetry="axisymmetric", tip_radius=R, cpu_time=1.0,
        work_of_adhesion=LAW.work_of_adhesion, adhesion=repr(LAW), accuracy="draft",
        pull_off_force=pull, pull_off_interference=float(w[retract][np.argmin(force[retract])]),
        tabor_parameter=LAW.tabor_parameter(R, E_STAR),
        jump_in_interference=-3 * D if kind == "jkr" else math.nan,
        jump_off_interference=-6 * D if kind == "jkr" else math.nan,
        band_facets=10, total_wall_time=1.0)
    return ds


@pytest.fixture(scope="module")
def surface():
    return surface_stage.surface_from_statistics(SMOOTH, UNITS)


def make_plan(surface, curvatures=41, adhesion=ADHESION):
    population = filled("population", {"samples": {"height": 41, "curvature": curvatures,
                                                   "interference": 241}})
    return population_stage.plan_dataset(surface, population, ASPERITY, filled("material", MATERIAL),
                                         ["adhesion"], UNITS, "draft", filled("adhesion", adhesion))


def gathered(plan, kind):
    samples = {}
    for key, spec in zip(plan["key"].values, plan["spec"].values):
        if str(key) not in samples:
            samples[str(key)] = fake_sample(json.loads(str(spec)), str(key), kind)
    return population_stage.asperities_dataset(plan, samples)


@pytest.fixture(scope="module")
def plan(surface):
    return make_plan(surface)


@pytest.fixture(scope="module")
def dmt(plan):
    return gathered(plan, "dmt")


@pytest.fixture(scope="module")
def jkr(plan):
    return gathered(plan, "jkr")


# --- grid ------------------------------------------------------------------------------------
@pytest.mark.parametrize("cutoff", [4.0, 16.0])
def test_grid_starts_where_the_attraction_starts_and_is_fine_near_contact(cutoff):
    si = Adhesion.from_section(filled("adhesion", {"spacing": 0.3, "cutoff": cutoff}))
    d = 0.3e-9
    assert si.spec() == {"dgamma": 1.0, "d": d, "cutoff": cutoff}
    grid = adhesive_interface.interference_grid(80e-9, 241, si)
    gaps = grid[grid < 0]
    assert gaps[0] == -(cutoff - 1) * d == -adhesive_interface.reach(si)
    assert np.all(np.diff(grid) > 0)
    np.testing.assert_array_equal(grid[grid >= 0], contact_grid(80e-9, 241))
    levels = -np.concatenate([gaps, [0.0]])[::-1]  # |w| from 0 out to the reach
    steps = np.diff(levels)
    inner = levels[:-1]
    # d / 8 within 12 d of contact (the jumps), then growing by at most 10 % of |w| per level
    near = inner < 12 * d - 1e-9 * d
    np.testing.assert_allclose(steps[near], d / 8, rtol=1e-9)
    assert np.all(steps[~near] <= 0.1 * inner[~near] * (1 + 1e-9))
    # the fewest levels that do so: 8 per d out to 12 d, ceil(log_1.1((cutoff - 1) / 12)) beyond
    expected = 8 * (cutoff - 1) if cutoff <= 13 else 96 + math.ceil(math.log((cutoff - 1) / 12)
                                                                     / math.log(1.1))
    assert gaps.size == expected


# --- plan and job ------------------------------------------------------------------------------
def test_plan_runs_one_adhesive_job_per_curvature_with_the_law_in_its_key(surface, plan):
    assert plan.attrs["reach"] == pytest.approx(REACH, rel=1e-15)
    assert plan["interference"].values[0] == -plan.attrs["reach"]
    specs = [json.loads(str(s)) for s in plan["spec"].values]
    assert all(s["adhesion"] == {"dgamma": 1.0, "d": 0.5e-9, "cutoff": 16.0} for s in specs)
    assert all("levels" not in s for s in specs)
    # shift invariant (one job per curvature) but not self-similar (d does not scale)
    assert np.unique(plan["key"].values).size == plan.sizes["curvature"] == 41
    np.testing.assert_array_equal(plan["scale"].values, 1.0)
    other = make_plan(surface, 3, {**ADHESION, "spacing": 0.3})
    again = make_plan(surface, 3)
    assert not set(other["key"].values) & set(again["key"].values)
    without = population_stage.plan_dataset(
        surface, filled("population", {"samples": {"height": 41, "curvature": 3}}), ASPERITY,
        filled("material", MATERIAL), [], UNITS, "draft", filled("adhesion", ADHESION))
    assert "adhesion" not in json.loads(str(without["spec"].values[0]))
    assert without["interference"].values[0] == 0.0 and "reach" not in without.attrs
    with pytest.raises(ValueError, match="elastic"):
        population_stage.plan_dataset(
            surface, filled("population", {"samples": {"curvature": 2}}), ASPERITY,
            filled("material", {**MATERIAL, "model": "j2", "yield_stress": 320.0}),
            ["adhesion", "plasticity"], UNITS, "draft", filled("adhesion", ADHESION))


# --- gather ------------------------------------------------------------------------------------
def test_gather_keeps_negative_forces_jumps_and_contact(plan, jkr):
    assert jkr["force"].dims == ("branch", "height", "curvature", "interference")
    assert list(jkr["branch"].values) == ["approach", "retract"]
    w = jkr["interference"].values
    eps = 2e-3 * D
    for j in (0, 20, 40):
        k = float(jkr["curvature"][j])
        R = 1 / k
        for branch, jump in (("approach", -3 * D), ("retract", -6 * D)):
            one = jkr.sel(branch=branch).isel(height=7, curvature=j)
            F, A = closed_form(R, w, branch, "jkr")
            ok = np.abs(w - jump) > eps  # the jump's chord: 0.002 d wide
            scale = np.abs(F).max()
            beyond = one["extrapolated"].values
            np.testing.assert_allclose(one["force"].values[ok & ~beyond], F[ok & ~beyond],
                                       rtol=0, atol=2e-5 * scale)
            np.testing.assert_allclose(one["contact_area"].values[ok & ~beyond], A[ok & ~beyond],
                                       rtol=0, atol=2e-5 * A.max())
            np.testing.assert_array_equal(one["in_contact"].values[ok], (A > 0)[ok])
            # attraction before touching, zero at the far end of the range
            assert one["force"].values[0] == pytest.approx(0.0, abs=1e-12 * scale)
            assert np.all(one["force"].values[(w < 0) & (w > -REACH) & ok] < 0)
        assert float(jkr["pull_off_force"][j]) == pytest.approx(1.5 * np.pi * R * LAW.work_of_adhesion,
                                                                rel=1e-12)
        assert float(jkr["pull_off_force_dmt"][j]) == pytest.approx(2 * np.pi * R * LAW.work_of_adhesion)
    assert not jkr["extrapolated"].values.any()  # the jobs reach the top of the grid
    # the computed paths are kept for Fig. 7.6
    assert jkr["path_force"].dims == ("curvature", "step")
    assert set(np.unique(jkr["path_branch"].values[jkr["path_valid"].values])) == {"approach", "retract"}


def test_gather_flags_elastic_and_small_strain_contacts_per_branch(jkr):
    """``elastic``: touching and the job's flag, per branch (first yield at 20 d on
    approach, 10 d on retraction here), the flag of the nearer record, so it may differ
    only within a record's spacing of first yield (3.7 % of it); ``small_strain``:
    touching and the interpolated strain below 8 % (linear here: exact but at 40 d)."""
    w = jkr["interference"].values
    for j in (0, 20, 40):
        for branch in ("approach", "retract"):
            one = jkr.sel(branch=branch).isel(height=7, curvature=j)
            touching = one["in_contact"].values == 1
            expected = touching & (w < YIELD[branch])
            differ = one["elastic"].values != expected
            assert np.all(np.abs(w[differ] - YIELD[branch]) < 0.05 * YIELD[branch]), w[differ] / D
            assert one["elastic"].values[touching].min() == 0 and not one["elastic"].values[~touching].any()
            np.testing.assert_array_equal(one["small_strain"].values,
                                          (touching & (w < LARGE_STRAIN)).astype(float))


def test_no_jump_no_hysteresis_and_count_by_contact_area(dmt):
    np.testing.assert_array_equal(dmt["force"].sel(branch="approach").values,
                                  dmt["force"].sel(branch="retract").values)
    w = dmt["interference"].values
    one = dmt.sel(branch="approach").isel(height=0, curvature=0)
    # attracting but not touching: force < 0, in_contact 0; touching: in_contact 1
    assert np.all(one["force"].values[(w < 0) & (w > -REACH)] < 0)
    np.testing.assert_array_equal(one["in_contact"].values, (w > 0).astype(float))


# --- interface: direct quadrature ---------------------------------------------------------------
def _gl(lo, hi, n):
    x, wt = np.polynomial.legendre.leggauss(n)
    return 0.5 * (hi - lo) * x + 0.5 * (hi + lo), 0.5 * (hi - lo) * wt


def support(surface, plan):
    density = population_density.population_density(
        surface, Population.from_section(POPULATION, Units.from_section(UNITS)))
    return density, density.support(float(plan.attrs["support_threshold"]))


def direct(surface, plan, h, kind, branch="approach", h_turn=None):
    """n / I int int F(z - h, kappa) f dz dkappa: closed form F, composite Gauss-Legendre
    split at every kink and jump (contact onset, jumps, the caught-or-not switch, first
    yield). Columns: pressure, contact count, the gross pressure n / I int int |F| f (the
    scale of the errors where compression and attraction cancel), and the count of
    contacts still elastic."""
    density, (z0, z1, k0, k1) = support(surface, plan)
    n = population_density.peak_density(surface)
    k, wk = _gl(k0, k1, 400)
    zf, wzf = _gl(z0, z1, 800)
    norm = (density.pdf(zf[:, None], k[None, :]) * wzf[:, None] * wk[None, :]).sum()
    out = np.empty((h.size, 4))
    R = 1 / k[None, :]
    for i, hi in enumerate(h):  # a handful of separations
        cuts = [hi - REACH, hi - 6 * D, hi - 3 * D, hi, hi + YIELD["approach"],
                hi + YIELD["retract"]]
        if h_turn is not None:
            cuts.append(h_turn - 3 * D)
        edges = np.unique(np.clip(np.array([z0, z1] + cuts), max(z0, hi - REACH), z1))
        p = c = gross = elastic = 0.0
        for lo, up in zip(edges[:-1], edges[1:]):  # the pieces between kinks and jumps
            z, wz = _gl(lo, up, 60)
            g = density.pdf(z[:, None], k[None, :]) * wz[:, None] * wk[None, :]
            w = (z - hi)[:, None]
            F, A = closed_form(R, w, branch, kind)
            E = w < YIELD[branch]
            if branch == "retract" and h_turn is not None:  # never jumped in: approach branch
                Fa, Aa = closed_form(R, w, "approach", kind)
                caught = (z - h_turn >= -3 * D)[:, None]
                F, A = np.where(caught, F, Fa), np.where(caught, A, Aa)
                E = np.where(caught, E, w < YIELD["approach"])
            p += (F * g).sum()
            gross += (np.abs(F) * g).sum()
            c += ((A > 0) * g).sum()
            elastic += ((A > 0) * E * g).sum()
        out[i] = n * p / norm, n * c / norm, n * gross / norm, n * elastic / norm
    return out


@pytest.fixture(scope="module")
def dmt_interface(surface, plan, dmt):
    return homogenize_stage.interface_dataset(dmt, surface, plan, POPULATION, HOMOGENIZATION, UNITS)


def test_homogenized_attraction_against_direct_quadrature(surface, plan, dmt_interface):
    """Same integrator (homogenize.interface_response with reach) against the closed form
    integrated directly: pressure within 0.2 % of the gross pressure n E^(|F|) (measured
    3e-4; the net pressure changes sign near 3 sigma), contact count within 1e-4 (measured
    1e-7).  Above the highest peak nothing touches and the pressure is a pure attraction,
    within 5 % of the gross there (measured 0.13 % and 3.5 %: the last grid interval before
    the cut-off); beyond the reach, exactly zero."""
    out = dmt_interface.sel(branch="approach")
    h = out["separation"].values
    ref = direct(surface, plan, h, "dmt")
    p = out["nominal_pressure"].values
    z1 = support(surface, plan)[1][1]  # the highest peak of the support
    below, far = h < z1, (h > z1) & (h < z1 + REACH)
    assert np.any(p[below] < 0) and np.any(p[below] > 0)
    np.testing.assert_array_less(np.abs(p - ref[:, 0])[below], 2e-3 * ref[below, 2])
    np.testing.assert_allclose(out["contact_count"].values, ref[:, 1], rtol=1e-4, atol=0)
    assert far.any() and np.all(p[far] < 0) and np.all(out["contact_count"].values[far] == 0)
    np.testing.assert_array_less(np.abs(p - ref[:, 0])[far], 0.05 * ref[far, 2])
    assert np.all(p[h >= z1 + REACH] == 0)


def test_retract_branch_hangs_on_against_direct_quadrature(surface, plan, jkr):
    """Jumps in the table: within 2 % of the gross pressure and 2 % in the contact count
    below the highest peak (measured 1.0 % and 1.3 % on approach, 1.5 % and 1.2 % on
    retraction: a jump between two grid levels d / 8 apart is integrated as a ramp)."""
    out = homogenize_stage.interface_dataset(jkr, surface, plan, POPULATION, HOMOGENIZATION, UNITS)
    h = out["separation"].values
    below = h < support(surface, plan)[1][1]
    for branch in ("approach", "retract"):
        ref = direct(surface, plan, h, "jkr", branch, h.min() if branch == "retract" else None)
        p = out["nominal_pressure"].sel(branch=branch).values
        np.testing.assert_array_less(np.abs(p - ref[:, 0])[below], 0.02 * ref[below, 2])
        np.testing.assert_allclose(out["contact_count"].sel(branch=branch).values[below],
                                   ref[below, 1], rtol=0.02, atol=0)
    # hysteresis: retracting, the contacts hang on and pull harder than on approach
    ret, app = (out["nominal_pressure"].sel(branch=b).values for b in ("retract", "approach"))
    assert np.all(ret <= app + 1e-9 * np.abs(app).max())
    assert out.attrs["pull_off_pressure"] == pytest.approx(-ret.min())
    assert out["normal_stiffness"].dims == ("branch", "separation")


def test_elastic_share_against_direct_quadrature_and_judges_first_yield(surface, plan, jkr):
    """The share of contacting asperities still elastic (report 7.3, Fig. 7.10) on both
    branches against the direct quadrature of the flags, within 0.02 below the highest peak
    (measured 0.5 % on retraction and 1.1 % on approach: the flag steps at the midpoint
    between two records and the integrator interpolates it between grid levels); the
    retracting contacts, yielding earlier, are less often elastic. With a yield stress
    and the scene's validity limits the interface's yielded share is the FE flag's, one
    minus the elastic share (`asperity.homogenize.validity`: first yield by the flag, not
    by F/A, which adhesion lowers)."""
    material = filled("material", {**MATERIAL, "yield_stress": 320.0})
    out = homogenize_stage.interface_dataset(jkr, surface, plan, POPULATION, HOMOGENIZATION, UNITS,
                                             material_cfg=material, effects=["adhesion"],
                                             validity_cfg=filled("validity", {}))
    h = out["separation"].values
    below = h < support(surface, plan)[1][1]
    for branch in ("approach", "retract"):
        ref = direct(surface, plan, h, "jkr", branch, h.min() if branch == "retract" else None)
        share = out["elastic_fraction"].sel(branch=branch).values
        assert np.all(ref[below, 1] > 0)
        np.testing.assert_allclose(share[below], ref[below, 3] / ref[below, 1], rtol=0, atol=0.02)
    ret, app = (out["elastic_fraction"].sel(branch=b).values[below] for b in ("retract", "approach"))
    assert np.all(ret < app)
    touching = out["contact_count"] > 0
    np.testing.assert_allclose(out["yielded_fraction"].where(touching).values,
                               (1 - out["elastic_fraction"]).where(touching).values, atol=1e-12)
    assert "FE job" in out["yielded_fraction"].attrs["long_name"]


def test_integrator_refuses_a_table_that_does_not_reach(dmt):
    table = dmt.sel(branch="approach", drop=True)[["force", "in_contact"]]
    density = JointDensity(sigma=0.013e-6, sigma_slope=0.013, sigma_curvature=0.018e6)
    with pytest.raises(ValueError, match="reach > 0"):
        homogenize.interface_response(table, density, [20e-9], peak_density=5.8e10)
    with pytest.raises(ValueError, match="start at"):
        homogenize.interface_response(table, density, [20e-9], peak_density=5.8e10,
                                      reach=2 * REACH)
    with pytest.raises(ValueError, match="contact variable"):
        homogenize.interface_response(table, density, [20e-9], peak_density=5.8e10,
                                      reach=REACH, contact="touching")


def test_adhesion_figure_draws_both_branches_and_the_samples(surface, plan, jkr, dmt_interface):
    from asperity.plots import adhesion as plots_adhesion

    out = homogenize_stage.interface_dataset(jkr, surface, plan, POPULATION, HOMOGENIZATION, UNITS)
    fig = plots_adhesion.adhesion_figure(out, jkr.isel(curvature=[0, 20, 40]),
                                         {"no adhesion": dmt_interface.sel(branch="approach")},
                                         length_unit="um", pressure_unit="MPa")
    axes = fig.axes
    assert len(axes) == 4
    assert len(axes[0].lines) == 2 + 1 + 1  # approach, retract, the compared scene, p = 0
    assert len(axes[3].lines) == 3 * 3 + 1  # per asperity approach, retract, pull-off; F = 0
    # the pull-off markers sit at the recorded pull-off forces
    marker = axes[3].lines[2]
    assert marker.get_ydata()[0] == pytest.approx(-float(jkr["pull_off_force"][0]))


def test_peaks_rule_counts_the_attracting_peaks_too(dmt):
    """Rule `peaks` (a map's own peaks, 2.4.3) with reach: the mean over the peaks of the
    closed form, every peak within reach counted, within 1.5 % of the gross pressure
    (the table's linear interpolation between 41 curvatures, point by point; measured
    0.36 % to 0.95 %)."""
    from asperity.peaks import SampledDensity

    rng = np.random.default_rng(5)
    z = rng.uniform(-10e-9, 60e-9, 400)
    k = rng.uniform(float(dmt["curvature"][0]), float(dmt["curvature"][-1]), 400)
    density = SampledDensity.from_peaks(z, k)
    table = dmt.sel(branch="approach", drop=True)[["force", "in_contact"]]
    h = np.array([0.0, 30e-9, 58e-9, 62e-9])
    out = homogenize.interface_response(table, density, h, rule="peaks", peak_density=1.0,
                                        reach=REACH, contact="in_contact")
    F, A = closed_form(1 / k[None, :], z[None, :] - h[:, None], "approach", "dmt")
    acting = z[None, :] > h[:, None] - REACH
    F = np.where(acting, F, 0.0)
    gross = np.abs(F).mean(axis=1)
    assert np.all(np.abs(out["nominal_pressure"].values - F.mean(axis=1)) <= 0.015 * gross)
    np.testing.assert_allclose(out["contact_count"].values, (A > 0).mean(axis=1), atol=1e-12)
    assert out["nominal_pressure"].values[-1] < 0  # above every peak: attraction only
