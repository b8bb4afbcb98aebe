"""Validity of a homogenized interface (asperity.homogenize.validity) on cases with known
answers: Greenwood-Williamson populations of Hertz asperities whose mean contact pressure
crosses the hardness, and an FE-like table capped on purpose."""

import math

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq

from asperity import homogenize
from asperity.homogenize import validity
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.peaks import FixedCurvatureDensity
from asperity.plots.validity import invalid_spans
from asperity.population.gather import gather
from asperity.population.plan import interference_grid, make_plan
from asperity.references.greenwood_williamson import gw_integral
from asperity.references.hertz import hertz_asperities, plane_strain_modulus
from asperity.scene import Material

SIGMA_P = 1e-6  # m
CURVATURE = 1e4  # 1/m: R = 100 um
N_PEAKS = 1e9  # 1/m^2
E, NU = 2e11, 0.3
BOUNDS = (-8 * SIGMA_P, 8 * SIGMA_P, CURVATURE, CURVATURE)  # truncation below 1e-14
DENSITY = FixedCurvatureDensity(SIGMA_P, CURVATURE)
#: the mean Hertz pressure (4 E'/(3 pi)) sqrt(w/R) reaches H at w_H = R (3 pi H / (4 E'))^2;
#: H is chosen so that w_H = sigma_p / 2
W_H = 0.5 * SIGMA_P
HARDNESS = 4 * plane_strain_modulus(E, NU) / (3 * math.pi) * math.sqrt(W_H * CURVATURE)
LIMITS = dict(extrapolated_load_fraction=0.02, yielded_fraction=0.5, large_strain_fraction=0.1,
              contact_area_ratio=0.1, interaction=0.3, plasticity_index=None)


def _homogenized(table, separations, cells=800):
    out = homogenize.interface_response(table, DENSITY, separations, bounds=BOUNDS, cells=(cells, 1),
                                        rule="gauss", peak_density=N_PEAKS)
    return out


def _hertz_interface(plasticity, separations, limits=LIMITS):
    grid = interference_grid(16 * SIGMA_P, 4001)
    table = validity.with_indicators(hertz_asperities([0.0], [CURVATURE], grid, E, NU), plasticity)
    peaks = validity.peak_statistics(DENSITY, BOUNDS)
    return validity.assess(_homogenized(table, separations), plasticity, peaks,
                           validity.Limits(**limits))


def _yielded_share(h):
    """Closed form: the share of contacting asperities pressed beyond w_H, F_0(t + w_H/sigma) / F_0(t)."""
    t = np.asarray(h) / SIGMA_P
    return gw_integral(0.0, t + W_H / SIGMA_P) / gw_integral(0.0, t)


def elastic(**given) -> Material:
    return Material("elastic", youngs_modulus=E, poisson=NU, **given)


@pytest.mark.parametrize("material, hardness, rule", [
    (elastic(hardness=HARDNESS), HARDNESS, "above the hardness"),
    # a yield stress whose Hertz first yield p0 = 1.5 F/A = 1.6 Y is at the same mean pressure
    (elastic(yield_stress=1.5 / 1.6 * HARDNESS), None, "p0 = 1.5 F/A"),
])
def test_hertz_interface_yields_where_the_mean_pressure_crosses_the_limit(material, hardness, rule):
    plasticity = validity.plasticity_of(material, [])
    assert rule in plasticity.yield_rule
    h = np.linspace(-2.0, 3.0, 51) * SIGMA_P
    out = _hertz_interface(plasticity, h)
    # against the closed form: the flag is linear between grid levels 0.23 % apart
    np.testing.assert_allclose(out["yielded_fraction"].values, _yielded_share(h), atol=2e-3, rtol=0)
    # the share falls to the limit 0.5 at the separation where F_0(t + 1/2) = F_0(t) / 2
    crossing = brentq(lambda x: _yielded_share(x) - 0.5, -2 * SIGMA_P, 3 * SIGMA_P)
    clear = np.abs(h - crossing) > 0.02 * SIGMA_P
    np.testing.assert_array_equal(out["valid"].values[clear], (h > crossing)[clear])
    assert all(str(w).startswith("yielded_fraction") for w in out["validity"].values[h < crossing])
    assert set(out["validity"].values[h > crossing + 0.02 * SIGMA_P]) == {""}
    # psi = (E'/H) sqrt(sigma_p / R) with H = the hardness given, or 2.8 Y
    h_used = hardness if hardness is not None else validity.HARDNESS_OVER_YIELD * material.yield_stress
    psi = plane_strain_modulus(E, NU) / h_used * math.sqrt(SIGMA_P * CURVATURE)
    assert float(out["plasticity_index"]) == pytest.approx(psi, rel=1e-6)
    assert float(out["hardness"]) == pytest.approx(h_used, rel=1e-12)


def test_plasticity_index_limit_fails_every_separation_of_an_elastic_scene():
    plasticity = validity.plasticity_of(elastic(hardness=HARDNESS), [])
    psi = plane_strain_modulus(E, NU) / HARDNESS * math.sqrt(SIGMA_P * CURVATURE)
    h = np.linspace(2.0, 3.0, 5) * SIGMA_P
    out = _hertz_interface(plasticity, h, {**LIMITS, "plasticity_index": 0.5 * psi})
    assert not out["valid"].values.any()
    assert all(str(w).startswith("plasticity_index") for w in out["validity"].values)
    # an inelastic body is limited by neither (its yield is modelled), only records them
    inelastic = validity.plasticity_of(elastic(hardness=HARDNESS), ["plasticity"])
    strict = {**LIMITS, "plasticity_index": 0.5 * psi, "yielded_fraction": 0.1}
    out = _hertz_interface(inelastic, h, strict)
    assert out["valid"].values.all()
    assert float(out["yielded_fraction"].min()) > 0.1


def _linear_sample(key, curvature, levels, stiffness=1e3):
    """A 'FE' job whose force is k w (so the gather's straight continuation is exact)."""
    ds = xr.Dataset({"force": ("step", stiffness * levels),
                     "contact_area": ("step", math.pi * levels / curvature),
                     "contact_radius": ("step", np.sqrt(levels / curvature)),
                     "interference": ("step", levels),
                     "elastic": ("step", np.ones(levels.size, bool)),
                     "max_equivalent_strain": ("step", np.zeros(levels.size))})
    ds.attrs["key"] = key
    return ds


def test_fe_job_capped_on_purpose_extrapolates_a_known_share_of_the_load():
    cap = 1.5 * SIGMA_P  # the job computes up to w_c
    grid = interference_grid(16 * SIGMA_P, 4001)
    plan = make_plan([0.0], [CURVATURE], grid, model="fe", job_spec=lambda h, k, lv: {"curvature": k},
                     shift_invariant=True, analytic=False)
    key = str(plan["key"].values[0])
    gathered = gather(plan, {key: _linear_sample(key, CURVATURE, np.geomspace(grid[1], cap, 40))})
    assert gathered["extrapolated"].values[..., grid > cap * (1 + 1e-12)].all()
    h = np.linspace(-2.0, 3.0, 51) * SIGMA_P
    out = validity.assess(_homogenized(validity.with_indicators(gathered, None), h), None,
                          validity.peak_statistics(DENSITY, BOUNDS), validity.Limits(**LIMITS))
    # F = k w: the load beyond w_c over the whole load, [F_1(t + c) + c F_0(t + c)] / F_1(t)
    t, c = h / SIGMA_P, cap / SIGMA_P
    share = (gw_integral(1.0, t + c) + c * gw_integral(0.0, t + c)) / gw_integral(1.0, t)
    np.testing.assert_allclose(out["extrapolated_load_fraction"].values, share, atol=2e-3, rtol=0)
    assert share.min() < 0.02 < share.max()
    crossing = h[np.argmin(np.abs(share - 0.02))]
    clear = np.abs(h - crossing) > 0.15 * SIGMA_P
    np.testing.assert_array_equal(out["valid"].values[clear], (share <= 0.02)[clear])
    assert all(str(w).startswith("extrapolated_load_fraction") for w in out["validity"].values[~out["valid"].values])
    assert "yielded_fraction" not in out  # no material given


def test_interaction_is_twice_the_mean_contact_radius_over_the_spacing():
    """GW: a_mean = sqrt(R sigma_p) E(sqrt(s - t)) = sqrt(R sigma_p) F_1/2(t) / F_0(t)."""
    h = np.linspace(-1.0, 2.0, 7) * SIGMA_P
    out = _hertz_interface(validity.plasticity_of(elastic(), []), h)
    t = h / SIGMA_P
    count = N_PEAKS * gw_integral(0.0, t)
    radius = math.sqrt(SIGMA_P / CURVATURE) * gw_integral(0.5, t) / gw_integral(0.0, t)
    np.testing.assert_allclose(out["interaction"].values, 2 * radius * np.sqrt(count), rtol=1e-4)
    # nothing known about yield: recorded, not checked
    assert "yielded_fraction" not in out
    assert "yield: not checked" in out["valid"].attrs["not_checked"]
    assert math.isnan(float(out["plasticity_index"]))


def _branches(names, valid_load, turn=None):
    """A two-branch interface whose first branch fails the contact area limit where asked."""
    h = np.arange(5.0) * 1e-6
    area = np.where(valid_load, 0.01, 0.5)
    ds = xr.Dataset({
        "nominal_pressure": (("branch", "separation"), np.array([np.ones(5), [np.nan, 1.0, 1.0, 1.0, 1.0]]),
                             {"units": "Pa", "long_name": "p"}),
        "contact_area_ratio": (("branch", "separation"), np.array([area, np.full(5, 0.01)]),
                               {"units": "1", "long_name": "A"}),
        "contact_count": (("branch", "separation"), np.ones((2, 5)), {"units": "1/m^2", "long_name": "n"}),
    }, coords={"separation": ("separation", h, {"units": "m", "long_name": "h"}),
               "branch": ("branch", names, {"units": "1", "long_name": "branch"})})
    if turn is not None:
        ds.attrs["unloading_from"] = h[turn]
    return ds


def test_unloading_branch_fails_where_it_unloads_from_a_failing_state():
    ds = _branches(["loading", "unloading"], np.array([False, True, True, True, True]), turn=0)
    out = validity.assess(ds, None, (SIGMA_P, 1 / CURVATURE), validity.Limits(**LIMITS))
    unl = out.sel(branch="unloading")
    np.testing.assert_array_equal(unl["valid"].values, [True, False, False, False, False])  # NaN: not on it
    assert str(unl["validity"].values[1]).startswith("unloads from a state that fails: contact_area_ratio")
    ok = _branches(["loading", "unloading"], np.array([True, False, True, True, True]), turn=0)
    out = validity.assess(ok, None, (SIGMA_P, 1 / CURVATURE), validity.Limits(**LIMITS))
    assert out.sel(branch="unloading")["valid"].values.all()


def test_adhesive_branches_are_judged_each_on_its_own_and_survive_netcdf(tmp_path):
    ds = _branches(["approach", "retract"], np.array([False, False, True, True, True]))
    out = validity.assess(ds, None, (SIGMA_P, 1 / CURVATURE), validity.Limits(**LIMITS))
    np.testing.assert_array_equal(out["valid"].values, [[False, False, True, True, True], [True] * 5])
    assert "validity_warning" in out.attrs and "(approach)" in out.attrs["validity_warning"]
    write_dataset(out, tmp_path / "interface.nc", scene="s", title="t")
    back = read_dataset(tmp_path / "interface.nc")
    assert back["valid"].dtype == bool
    np.testing.assert_array_equal(back["valid"].values, out["valid"].values)
    np.testing.assert_array_equal(back["validity"].values.astype(str), out["validity"].values.astype(str))
    assert validity.valid_ranges(back)[0] == ("valid (approach): 3 of 5 separations, 2e-06 .. 4e-06 m; "
                                              "contact_area_ratio fails at 2 separations (0 .. 1e-06 m), "
                                              "e.g. contact_area_ratio 0.5 > 0.1")


def test_hardness_rules():
    assert validity.hardness_of(elastic(yield_stress=3e8))[0] == pytest.approx(8.4e8, rel=1e-12)
    assert validity.hardness_of(elastic(yield_stress=3e8, hardness=1e9)) == (
        1e9, "given in the scene (material.hardness)")
    assert math.isnan(validity.hardness_of(elastic())[0])
    # Bodner-Partom SAE 1020 (8.2.1): Z1 = 1050 MPa, n = 2.28, D0 = 1e4 1/s, at 1e-3 1/s
    sigma = 1050e6 * (2 * math.log(2 / math.sqrt(3) * 1e4 / 1e-3)) ** (-0.5 / 2.28)
    h, rule = validity.hardness_of(Material("bodner_partom", youngs_modulus=2.09e11, poisson=0.3,
                                            preset="sae_1020"))
    assert h == pytest.approx(2.8 * sigma, rel=1e-12)
    assert "saturated Bodner-Partom flow stress" in rule


def test_large_strains_fail_small_strain_jobs_only():
    """A share of 0.4 of the contacts beyond 8 % strain fails the limit 0.1 where the FE
    jobs are in small-strain kinematics, and is recorded but not limited with the
    effect finite_strain."""
    ds = _branches(["loading", "unloading"], np.ones(5, bool)).sel(branch="loading", drop=True)
    ds["small_strain_fraction"] = ("separation", np.full(5, 0.6), {"units": "1", "long_name": "s"})
    steel = Material("bodner_partom", youngs_modulus=2.09e11, poisson=0.3, preset="sae_1020")
    peaks = (SIGMA_P, 1 / CURVATURE)
    small = validity.assess(ds, validity.plasticity_of(steel, {"plasticity"}, True), peaks,
                            validity.Limits(**LIMITS))
    assert not small["valid"].values.any()
    assert str(small["validity"].values[0]) == "large_strain_fraction 0.4 > 0.1"
    finite = validity.assess(ds, validity.plasticity_of(steel, {"plasticity", "finite_strain"}, True),
                             peaks, validity.Limits(**LIMITS))
    assert finite["valid"].values.all()
    np.testing.assert_allclose(finite["large_strain_fraction"].values, 0.4, rtol=1e-12)
    assert "large_strain_fraction: finite-strain FE asperities" in finite["valid"].attrs["not_checked"]
    # the effect means nothing without plasticity (the kinds refuse it there)
    assert not validity.plasticity_of(steel, {"finite_strain"}).finite_strain


def test_the_warning_says_what_each_failing_limit_means_and_what_to_change():
    """Each limit that fails is explained once, in the order it first fails, with the scene
    key that addresses it; the contact area and interaction share one explanation."""
    ds = _branches(["loading", "unloading"], np.array([False, False, True, True, True]))
    ds = ds.sel(branch="loading", drop=True)
    ds["small_strain_fraction"] = ("separation", [1.0, 1.0, 1.0, 0.6, 0.6], {"units": "1", "long_name": "s"})
    steel = Material("bodner_partom", youngs_modulus=2.09e11, poisson=0.3, preset="sae_1020")
    out = validity.assess(ds, validity.plasticity_of(steel, {"plasticity"}, True), (SIGMA_P, 1 / CURVATURE),
                          validity.Limits(**LIMITS))
    text = out.attrs["validity_warning"]
    means = text.split(". What it means: ")[1]
    assert means.startswith("contact_area_ratio: the contacts are no longer independent asperities")
    assert means.count("no longer independent") == 1
    assert "; large_strain_fraction: strains of 8 % or more in small-strain FE jobs: add the effect " \
           "finite_strain" in means
    assert validity.REMEDIES.keys() == set(validity.INDICATORS) | {"plasticity_index", *validity.ASSUMPTIONS}


def test_limits_are_shares():
    with pytest.raises(ValueError, match="validity.contact_area_ratio"):
        validity.Limits(**{**LIMITS, "contact_area_ratio": 1.5})


def test_invalid_spans_reach_midway_to_the_valid_neighbours():
    x = np.array([4.0, 3.0, 2.0, 1.0, 0.0])
    assert invalid_spans(x, np.array([True, False, False, True, False])) == [(1.5, 3.5), (0.0, 0.5)]
    assert invalid_spans(np.array([1.0, 10.0, 100.0]), np.array([False, True, True]), log=True) == \
        [(1.0, pytest.approx(math.sqrt(10.0)))]
    assert invalid_spans(x, np.ones(5, bool)) == []


def test_show_prints_the_valid_separation_range(tmp_path, capsys):
    from asperity.cli import main

    ds = _branches(["loading", "unloading"], np.array([False, True, True, True, True]), turn=2)
    out = validity.assess(ds, None, (SIGMA_P, 1 / CURVATURE), validity.Limits(**LIMITS))
    write_dataset(out, tmp_path / "interface.nc", scene="s", title="homogenized interface")
    assert main(["show", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert ("valid (loading): 4 of 5 separations, 1e-06 .. 4e-06 m; contact_area_ratio fails at 1 "
            "separation (0 .. 0 m), e.g. contact_area_ratio 0.5 > 0.1") in text
    assert "valid (unloading): every separation, 1e-06 .. 4e-06 m" in text


def test_interface_figure_shades_the_invalid_separations():
    from asperity.plots import interface_figure

    h = np.linspace(-1.0, 2.0, 7) * SIGMA_P
    out = _hertz_interface(validity.plasticity_of(elastic(hardness=HARDNESS), []), h)
    fig = interface_figure(out)
    spans = [p for p in fig.axes[0].patches]
    bad = h[~out["valid"].values]
    assert len(spans) == 1  # one run of invalid separations, out to midway to the first valid one
    lo, hi = spans[0].get_x(), spans[0].get_x() + spans[0].get_width()
    assert lo == pytest.approx(bad.min()) and hi == pytest.approx(bad.max() + 0.25 * SIGMA_P)
    assert "outside validity, e.g. yielded_fraction" in fig.axes[0].get_legend().get_texts()[-1].get_text()


def _elastic_scene_interface():
    """Five separations, contact at the four smallest, every indicator within its limit."""
    ds = _branches(["loading", "unloading"], np.array([True, True, True, True, True]))
    ds = ds.sel(branch="loading", drop=True)
    p = ds["nominal_pressure"].values.copy()
    p[-1] = 0.0
    ds["nominal_pressure"] = ("separation", p, ds["nominal_pressure"].attrs)
    return ds


def test_non_gaussian_heights_make_a_gaussian_density_not_valid_with_the_reason():
    """Skewness 10.8 and kurtosis 219 (a measured profile of the issue) under a Nayak or GW
    density: no separation with contact is valid, and the reason names both moments."""
    ds = _elastic_scene_interface()
    steel = Material("elastic", youngs_modulus=2.09e11, poisson=0.3, yield_stress=3.5e8)
    plastic = validity.plasticity_of(steel, ())
    limits = validity.Limits(**{**LIMITS, "contact_area_ratio": 1.0, "interaction": 10.0})
    gaussian = validity.assess(ds, plastic, (SIGMA_P, 1 / CURVATURE), limits, (0.1, 3.2))
    skewed = validity.assess(ds, plastic, (SIGMA_P, 1 / CURVATURE), limits, (10.8, 219.0))
    contact = ds["nominal_pressure"].values > 0
    assert gaussian["valid"].values[contact].all()
    assert not skewed["valid"].values[contact].any() and skewed["valid"].values[~contact].all()
    why = skewed["validity"].values[contact][0]
    assert why.startswith("gaussian_heights:") and "skewness 10.8" in why and "kurtosis 219" in why
    assert "gaussian_heights fails at 4 separations" in validity.valid_ranges(skewed)[0]


def test_an_elastic_scene_without_hardness_does_not_call_yield_checked():
    """No hardness and no yield stress: separations with contact are not valid, counted as
    not checked (not as a failed limit); with a yield stress the same interface is valid."""
    ds = _elastic_scene_interface()
    limits = validity.Limits(**{**LIMITS, "contact_area_ratio": 1.0, "interaction": 10.0})
    bare = Material("elastic", youngs_modulus=2.09e11, poisson=0.3)
    known = Material("elastic", youngs_modulus=2.09e11, poisson=0.3, yield_stress=3.5e8)
    unchecked = validity.assess(ds, validity.plasticity_of(bare, ()), (SIGMA_P, 1 / CURVATURE), limits)
    checked = validity.assess(ds, validity.plasticity_of(known, ()), (SIGMA_P, 1 / CURVATURE), limits)
    contact = ds["nominal_pressure"].values > 0
    assert checked["valid"].values.all()
    assert not unchecked["valid"].values[contact].any()
    assert set(unchecked["validity"].values[contact]) == {
        "unchecked_yield: no hardness or yield stress in the scene's material"}
    line = validity.valid_ranges(unchecked)[0]
    assert "unchecked_yield not checked at 4 separations" in line and "fails" not in line
