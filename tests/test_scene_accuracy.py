"""The scene accuracy study (asperity.studies.scenes) on synthetic interfaces whose
deviations from the reference are known exactly."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from asperity.io.netcdf import missing_attributes
from asperity.studies.scenes import branch_deviation, scene_accuracy

UM = 1e-6
#: the reference (fine) loading pressure [Pa] on separations 0..6 um: largest 100, so with
#: the threshold 1e-3 only values above 0.1 Pa (the first five) are compared
P_REF = np.array([100.0, 50.0, 20.0, 10.0, 1.0, 0.05, 0.0])
H_REF = np.arange(7.0) * UM
#: relative errors of a coarser run at the same separations: 4 % is the largest above the
#: threshold; the 500 % below it must not count
ERR = np.array([0.01, -0.02, 0.03, 0.0, -0.04, 5.0, 7.0])


def interface(h, pressure, area, *, unloading=None, accuracy="fine", **cost):
    """A synthetic interface.nc: loading only, or (loading, unloading) on dim branch."""
    attrs = {"accuracy": accuracy, **cost}
    sep = ("separation", np.asarray(h, float), {"units": "m", "long_name": "separation"})
    if unloading is None:
        return xr.Dataset({"nominal_pressure": ("separation", pressure, {"units": "Pa", "long_name": "p"}),
                           "contact_area_ratio": ("separation", area, {"units": "1", "long_name": "a"})},
                          coords={"separation": sep}, attrs=attrs)
    up, ua = unloading
    return xr.Dataset(
        {"nominal_pressure": (("branch", "separation"), np.stack([pressure, up]), {"units": "Pa", "long_name": "p"}),
         "contact_area_ratio": (("branch", "separation"), np.stack([area, ua]), {"units": "1", "long_name": "a"})},
        coords={"separation": sep, "branch": ("branch", ["loading", "unloading"],
                                              {"units": "1", "long_name": "branch"})},
        attrs=attrs)


def test_branch_deviation_threshold_and_location():
    dev, at, n = branch_deviation(H_REF, P_REF * (1 + ERR), H_REF, P_REF)
    assert dev == pytest.approx(0.04, rel=1e-12)
    assert at == pytest.approx(4 * UM, rel=1e-12)
    assert n == 5
    # a lower threshold (0.05 Pa > 1e-4 x 100 Pa) takes in the 500 % point
    dev, at, n = branch_deviation(H_REF, P_REF * (1 + ERR), H_REF, P_REF, threshold=1e-4)
    assert dev == pytest.approx(5.0, rel=1e-12)
    assert at == pytest.approx(5 * UM, rel=1e-12) and n == 6
    # a run equal to the reference deviates by exactly 0
    dev, at, n = branch_deviation(H_REF, P_REF, H_REF, P_REF)
    assert dev == 0.0 and np.isnan(at) and n == 5


def test_branch_deviation_only_common_separations():
    """Separations only one run holds (a run's own rebound points) are not compared, and
    separations equal to 1e-12 relative (round-off of two runs' grids) are."""
    h = np.concatenate([H_REF[:2] * (1 + 1e-12), [1.5 * UM], H_REF[3:]])  # no 2 um; 1.5 um extra
    p = np.concatenate([P_REF[:2] * (1 + ERR[:2]), [1e9], P_REF[3:] * (1 + ERR[3:])])
    dev, at, n = branch_deviation(h, p, H_REF, P_REF)
    assert n == 4  # 0, 1, 3, 4 um (2 um is missing from the run, 1.5 um from the reference)
    assert dev == pytest.approx(0.04, rel=1e-12) and at == pytest.approx(4 * UM, rel=1e-12)
    # nothing in common: no deviation
    dev, at, n = branch_deviation(H_REF + 0.5 * UM, P_REF, H_REF, P_REF)
    assert np.isnan(dev) and np.isnan(at) and n == 0


def test_branch_deviation_nan_where_branch_undefined():
    """NaN (the unloading branch below unloading_from) is left out on either side."""
    ref = P_REF.copy()
    ref[0] = np.nan
    run = P_REF * (1 + ERR)
    run[4] = np.nan  # the 4 % point
    dev, at, n = branch_deviation(H_REF, run, H_REF, ref)
    assert dev == pytest.approx(0.03, rel=1e-12) and at == pytest.approx(2 * UM, rel=1e-12)
    # compared: 1, 2, 3 um (4 um is above 1e-3 of the largest finite 50 Pa but NaN in the run;
    # 0.05 Pa at 5 um is not above 0.05 Pa)
    assert n == 3


def _study(**overrides):
    """Two scenes at draft, standard, fine: an unloading one and a loading-only one."""
    area_ref = P_REF / 1000.0
    e_std = ERR / 4  # standard: a quarter of draft's errors
    up_ref = np.array([100.0, 30.0, 3.0, 0.0, 0.0, 0.0, 0.0])  # the unloading branch, steep
    up_ref_nan = np.where(np.arange(7) < 1, np.nan, up_ref)
    runs = {
        ("unloads", "fine"): interface(H_REF, P_REF, area_ref, unloading=(up_ref_nan, up_ref_nan / 1000),
                                       fe_jobs=5, fe_cpu_time=1000.0, max_newton_iterations=30,
                                       max_step_cuts=2, max_dofs=9000, max_time_steps=900),
        ("unloads", "standard"): interface(
            H_REF, P_REF * (1 + e_std), area_ref * (1 - 2 * e_std),
            unloading=(up_ref_nan * 1.1, up_ref_nan / 1000 * 0.95), accuracy="standard",
            fe_jobs=5, fe_cpu_time=200.0, max_newton_iterations=20, max_step_cuts=1, max_dofs=4000,
            max_time_steps=500),
        ("unloads", "draft"): interface(
            H_REF, P_REF * (1 + ERR), area_ref * (1 - 2 * ERR),
            unloading=(up_ref_nan * 1.2, up_ref_nan / 1000 * 0.8), accuracy="draft",
            fe_jobs=5, fe_cpu_time=50.0, max_newton_iterations=10, max_step_cuts=0, max_dofs=2000,
            max_time_steps=300),
        ("loads", "fine"): interface(H_REF, P_REF, area_ref, fe_jobs=1, fe_cpu_time=20.0),
        ("loads", "standard"): interface(H_REF, P_REF * (1 + e_std), area_ref, accuracy="standard",
                                         fe_jobs=1, fe_cpu_time=5.0),
        ("loads", "draft"): interface(H_REF, P_REF * (1 + ERR), area_ref, accuracy="draft",
                                      fe_jobs=1, fe_cpu_time=2.0),
    }
    # the share of contacting asperities extrapolated: 0.55 at most on loading (the 0.9 of the
    # unloading branch and NaN without contact do not count)
    frac = np.array([[0.55, 0.5, 0.3, 0.1, 0.0, np.nan, np.nan], [0.9, 0.9, 0.9, np.nan, np.nan, np.nan, np.nan]])
    runs[("unloads", "draft")]["extrapolated_fraction"] = (("branch", "separation"), frac,
                                                          {"units": "1", "long_name": "x"})
    runs.update(overrides)
    return runs


def test_scene_accuracy_deviations_and_costs():
    ds = scene_accuracy(_study(), ["unloads", "loads"], ["draft", "standard", "fine"])
    assert ds.attrs["reference"] == "fine"
    dev = ds["deviation"]
    sel = dict(scene="unloads", branch="loading")
    assert float(dev.sel(**sel, preset="draft", quantity="nominal_pressure")) == pytest.approx(0.04, rel=1e-12)
    assert float(dev.sel(**sel, preset="standard", quantity="nominal_pressure")) == pytest.approx(0.01, rel=1e-12)
    assert float(dev.sel(**sel, preset="draft", quantity="contact_area_ratio")) == pytest.approx(0.08, rel=1e-12)
    # unloading: 20 % and 10 % in pressure, 20 % and 5 % in area at every compared point, NaN left out
    sel = dict(scene="unloads", branch="unloading")
    assert float(dev.sel(**sel, preset="draft", quantity="nominal_pressure")) == pytest.approx(0.2, rel=1e-12)
    assert float(dev.sel(**sel, preset="standard", quantity="nominal_pressure")) == pytest.approx(0.1, rel=1e-12)
    assert float(dev.sel(**sel, preset="standard", quantity="contact_area_ratio")) == pytest.approx(0.05, rel=1e-12)
    assert int(ds["compared_separations"].sel(**sel, preset="draft", quantity="nominal_pressure")) == 2
    # the reference deviates by exactly 0 on every branch it has
    assert (dev.sel(preset="fine", scene="unloads").values == 0).all()
    # a loading-only scene has no unloading deviation
    assert np.isnan(dev.sel(scene="loads", branch="unloading")).all()
    assert (ds["compared_separations"].sel(scene="loads", branch="unloading") == 0).all()
    assert float(dev.sel(scene="loads", preset="draft", branch="loading",
                         quantity="contact_area_ratio")) == 0.0
    # costs come from the attributes; absent ones are NaN
    assert ds["fe_cpu_time"].sel(scene="unloads").values.tolist() == [50.0, 200.0, 1000.0]
    assert ds["fe_jobs"].sel(scene="loads").values.tolist() == [1.0, 1.0, 1.0]
    assert ds["max_time_steps"].sel(scene="unloads").values.tolist() == [300.0, 500.0, 900.0]
    assert np.isnan(ds["max_dofs"].sel(scene="loads")).all()
    assert float(ds["max_extrapolated_fraction"].sel(scene="unloads", preset="draft")) == 0.55
    assert np.isnan(ds["max_extrapolated_fraction"].sel(scene="loads")).all()
    assert missing_attributes(ds) == []


def test_a_variant_is_compared_with_its_scenes_reference():
    """A variant of `loads` (runs at draft and standard only) against `loads` at fine: its
    draft deviates by the largest of its own errors above the threshold, 2 %; nothing at
    fine; a variant's missing coarser run is still refused."""
    variant = {("band", "draft"): interface(H_REF, P_REF * (1 + 0.5 * ERR), P_REF / 100, accuracy="draft",
                                            fe_jobs=1, fe_cpu_time=3.0),
               ("band", "standard"): interface(H_REF, P_REF, P_REF / 100, accuracy="standard",
                                               fe_jobs=1, fe_cpu_time=8.0)}
    ds = scene_accuracy({**_study(), **variant}, ["loads", "band"], ["draft", "standard", "fine"],
                        against={"band": "loads"})
    sel = dict(scene="band", branch="loading", quantity="nominal_pressure")
    assert float(ds["deviation"].sel(preset="draft", **sel)) == pytest.approx(0.02, rel=1e-12)
    assert float(ds["deviation"].sel(preset="standard", **sel)) == 0.0
    assert np.isnan(ds["deviation"].sel(preset="fine", **sel)) and np.isnan(ds["fe_cpu_time"].sel(
        scene="band", preset="fine"))
    assert ds["fe_cpu_time"].sel(scene="band").values[:2].tolist() == [3.0, 8.0]
    assert ds.attrs["variants"] == "band: against loads"
    with pytest.raises(ValueError, match="band@draft"):
        scene_accuracy({**_study(), ("band", "standard"): variant[("band", "standard")]}, ["loads", "band"],
                       ["draft", "standard", "fine"], against={"band": "loads"})


def test_scene_accuracy_other_reference_and_threshold():
    """Against standard instead of fine, threshold 1e-2: draft's loading pressure deviates by
    (1 + e) / (1 + e/4) - 1 where standard's is above 1e-2 of its largest (100.25 Pa): at 0..3 um
    (1 Pa x 0.99 at 4 um falls below 1.0025 Pa)."""
    ds = scene_accuracy(_study(), ["loads"], ["draft", "standard", "fine"], reference="standard",
                        threshold=1e-2)
    expected = np.abs((1 + ERR[:4]) / (1 + ERR[:4] / 4) - 1).max()  # 1.03 / 1.0075 - 1 at 2 um
    assert expected == pytest.approx(0.0223325, rel=1e-6)
    sel = dict(scene="loads", branch="loading", quantity="nominal_pressure")
    assert float(ds["deviation"].sel(preset="draft", **sel)) == pytest.approx(expected, rel=1e-12)
    assert int(ds["compared_separations"].sel(preset="draft", **sel)) == 4
    assert float(ds["deviation"].sel(preset="standard", **sel)) == 0.0
    assert ds.attrs["reference"] == "standard" and ds.attrs["threshold"] == 1e-2


def test_scene_accuracy_refuses_mixed_up_inputs():
    runs = _study()
    runs[("loads", "draft")].attrs["accuracy"] = "standard"
    with pytest.raises(ValueError, match="loads@draft was computed at accuracy 'standard'"):
        scene_accuracy(runs, ["loads"], ["draft", "standard", "fine"])
    with pytest.raises(ValueError, match="no interface for loads@coarse"):
        scene_accuracy(_study(), ["loads"], ["coarse", "fine"])
    with pytest.raises(ValueError, match="not among the presets"):
        scene_accuracy(_study(), ["loads"], ["draft", "standard"], reference="fine")
    # one run unloads, the other does not
    runs = _study()
    runs[("unloads", "draft")] = interface(H_REF, P_REF, P_REF, accuracy="draft")
    with pytest.raises(ValueError, match="unloading branch is in only one"):
        scene_accuracy(runs, ["unloads"], ["draft", "fine"])


def test_scene_accuracy_figure_lines():
    from asperity.plots.accuracy_scenes import scene_accuracy_figure

    ds = scene_accuracy(_study(), ["unloads", "loads"], ["draft", "standard", "fine"])
    fig = scene_accuracy_figure(ds)
    loading, unloading = fig.axes
    # loading: 2 scenes x 2 quantities, but the loads scene's area deviates by 0 (nothing on
    # a log axis): 3 lines of 2 presets each (the reference is a vertical line per scene)
    data = [line for line in loading.get_lines() if len(line.get_xdata()) == 2
            and line.get_linestyle() != ":"]
    assert len(data) == 3
    assert len(unloading.get_lines()) == 2 + 1  # unloads' pressure, area; its reference line


def test_deviation_over_the_valid_range_only():
    """With the reference's `valid`, the deviation is also taken where it holds: valid at
    0..2 um leaves the 3 % at 2 um the largest (the 4 % at 4 um is in the invalid part)."""
    mask = np.array([True, True, True, False, False, False, False])
    dev, at, n = branch_deviation(H_REF, P_REF * (1 + ERR), H_REF, P_REF, mask=mask)
    assert dev == pytest.approx(0.03, rel=1e-12) and at == pytest.approx(2 * UM, rel=1e-12) and n == 3
    runs = _study()
    for preset in ("draft", "standard", "fine"):
        runs[("loads", preset)]["valid"] = ("separation", mask, {"units": "1", "long_name": "valid"})
    ds = scene_accuracy(runs, ["unloads", "loads"], ["draft", "standard", "fine"])
    sel = dict(scene="loads", branch="loading", quantity="nominal_pressure")
    assert float(ds["valid_deviation"].sel(**sel, preset="draft")) == pytest.approx(0.03, rel=1e-12)
    assert float(ds["valid_deviation"].sel(**sel, preset="standard")) == pytest.approx(0.0075, rel=1e-12)
    assert int(ds["valid_separations"].sel(**sel, preset="draft")) == 3
    # a scene without `valid` has no valid deviation
    assert np.isnan(ds["valid_deviation"].sel(scene="unloads")).all()
