"""The deterministic reference stage (asperity.stages.reference): route scenes, the
hardness rule, and the comparison of statistical routes with the reference."""

from __future__ import annotations

import re

import numpy as np
import pytest
import xarray as xr

from asperity.stages import reference as stage
from tests.scene_defaults import filled, filled_scene

SCENE = {
    "title": "t", "report": "r", "units": {"length": "um", "pressure": "MPa"},
    "surface": {"map": {"generate": {"points": 64, "spacing": 1.25, "sigma": 1.0,
                                     "correlation_length": 20.0, "seed": 1}}},
    "material": {"youngs_modulus": 70000.0, "poisson": 0.33, "yield_stress": 280.0},
    "reference": {"separations": {"start": 0.5, "stop": 3.0, "count": 6, "unit": "sigma"}},
    "routes": {"fe": {"population": {"density": "nayak"}, "asperity": {"model": "fe"},
                      "homogenization": {"rule": "gauss"}}},
    "compare_with": ["other"],
}


def test_route_scene_reads_the_reference_map_at_its_separations():
    derived = stage.route_scene("ref", SCENE, "fe", "results")
    assert derived["surface"] == {"map": {"file": "results/ref/input/map.npy", "spacing": 1.25, "unit": "um"}}
    assert derived["homogenization"] == {"rule": "gauss", "separations": SCENE["reference"]["separations"]}
    assert derived["asperity"] == {"model": "fe"} and derived["population"] == {"density": "nayak"}
    assert derived["material"] == SCENE["material"] and derived["units"] == SCENE["units"]
    assert not {"routes", "reference", "compare_with"} & set(derived)
    assert SCENE["routes"]["fe"]["homogenization"] == {"rule": "gauss"}  # not modified
    user = {**SCENE, "surface": {"map": {"file": "data/m.nc"}}}
    assert stage.route_scene("ref", user, "fe", "results")["surface"] == {"map": {"file": "data/m.nc"}}
    with pytest.raises(KeyError, match="no route 'hertz'"):
        stage.route_scene("ref", SCENE, "hertz", "results")


def test_hardness_given_or_tabor():
    units = SCENE["units"]
    scene = filled_scene({k: v for k, v in SCENE.items() if k != "compare_with"})
    material, reference = scene["material"], scene["reference"]
    given = {**reference, "hardness": 900.0}
    assert stage.reference_hardness(material, given, units) == pytest.approx(9.0e8)
    assert stage.reference_hardness(material, reference, units) == pytest.approx(2.8 * 280e6)
    bare = filled("material", {"youngs_modulus": 1.0, "poisson": 0.3})
    assert stage.reference_hardness(bare, reference, units) is None


def test_periodic_separations_must_be_positive():
    surface = xr.Dataset({"sigma": ((), 1e-6)}, attrs={"population_estimator": "map"})
    scene = filled_scene({**{k: v for k, v in SCENE.items() if k != "compare_with"},
                          "reference": {"separations": {"start": 0.0, "stop": 3.0, "count": 4, "unit": "sigma"}}})
    ref = scene["reference"]
    with pytest.raises(ValueError, match="reference.separations"):
        stage.reference_separations(ref, surface, SCENE["units"])
    free = {**ref, "boundary": "free"}
    assert np.allclose(stage.reference_separations(free, surface, SCENE["units"]), [0, 1e-6, 2e-6, 3e-6])


def test_separations_in_material_ratios_of_the_map():
    """Unit bearing: the separations are the heights above which the given shares of the
    prepared map lie, spaced geometrically from start to stop (the curve's own ratios:
    exact); the routes' scenes get the same ones from their own surface.nc
    (`asperity.population.density.scene_separations`); a ratio outside (0, 1] or a
    surface without the curve is an error naming the key."""
    from asperity.population.density import scene_separations
    from asperity.scene import Homogenization, Units
    from asperity.surface.distribution import height_distribution

    z = np.random.default_rng(3).gamma(2.0, size=20000) * 1e-6  # skewed heights
    d = height_distribution(z)
    surface = xr.Dataset({"sigma": ((), 1e-6), "bearing_height": ("material_ratio", d["bearing_height"])},
                         coords={"material_ratio": d["material_ratio"]},
                         attrs={"population_estimator": "map"})
    section = {"start": 0.1, "stop": 0.001, "count": 3, "unit": "bearing"}
    scene = filled_scene({**{k: v for k, v in SCENE.items() if k != "compare_with"},
                          "reference": {"separations": section}})
    h = stage.reference_separations(scene["reference"], surface, SCENE["units"])
    values = z - z.mean()
    np.testing.assert_allclose(h, np.quantile(values, 1.0 - np.array([0.1, 0.01, 0.001])), rtol=1e-12)
    units = Units.from_section(SCENE["units"])
    homogenization = Homogenization.from_section(filled("homogenization", {"separations": section}), units)
    np.testing.assert_array_equal(scene_separations(homogenization, surface), h)
    with pytest.raises(ValueError, match="homogenization.unloading_from: has no scale"):
        homogenization.separation_scale(1e-6)  # an unloading separation in sigma or length only
    with pytest.raises(ValueError, match="reference.separations: in unit bearing"):
        stage.reference_separations({**scene["reference"], "separations": {**section, "start": 2.0}},
                                    surface, SCENE["units"])
    with pytest.raises(ValueError, match="reference.separations: unit bearing needs the bearing-area"):
        stage.reference_separations(scene["reference"], surface.drop_vars("bearing_height"), SCENE["units"])
    # past the mean plane (the skewed heights' mean lies at material ratio 0.406): a periodic
    # interface cannot, and the error says where to start
    below = {**section, "start": 0.6}
    mean_plane = np.mean(values > 0)
    with pytest.raises(ValueError, match="start below") as error:
        stage.reference_separations({**scene["reference"], "separations": below}, surface, SCENE["units"])
    said = float(re.search(r"start below ([0-9.]+)", str(error.value)).group(1))
    assert said == pytest.approx(mean_plane, abs=2e-3)  # the curve's resolution, 0.01 here


def _reference(h, p, a, count, hardness_p=None):
    limits = ["elastic"] + (["hardness"] if hardness_p is not None else [])
    data = {"nominal_pressure": np.array([p] + ([hardness_p] if hardness_p is not None else [])),
            "contact_area_ratio": np.array([a] * len(limits)),
            "contact_count": np.array([count] * len(limits)),
            "cells_per_patch": np.full((len(limits), len(h)), 100.0)}  # resolved
    return xr.Dataset({k: (("limit", "separation"), v) for k, v in data.items()},
                      coords={"limit": limits, "separation": h},
                      attrs={"boundary": "periodic", "hardness": 1.0})


def _interface(h, p, a, count):
    return xr.Dataset({"nominal_pressure": ("separation", p), "contact_area_ratio": ("separation", a),
                       "contact_count": ("separation", count)}, coords={"separation": h})


def test_comparison_errors_and_range():
    """A route equal to the reference holds everywhere; one with the same A(p) but
    shifted in separation has a pressure error and no area error (areas are compared
    at equal pressure); twice the pressure at equal area fails both; the range where
    a route holds is the longest run of separations; a plastic route is held against the
    hardness-limited solution and is not a candidate for the recommended route."""
    h = np.linspace(1e-6, 3e-6, 9)
    p = 1e8 * np.exp(-3 * h / 1e-6)
    a = 2.0 * p / 1e10
    n = np.full(h.size, 1e9)
    ref = _reference(h, p, a, n, hardness_p=0.5 * p)
    shifted = _interface(h - 0.1e-6, p, a, n)  # the same curve, 0.1 um lower
    double = _interface(h, 2 * p, a, n)
    partial = _interface(h, np.where(h < 2e-6, p, 1.5 * p), np.where(h < 2e-6, a, 1.5 * a), 2 * n)
    plastic = _interface(h, 0.5 * p, a, n).assign_attrs(limit="hardness")  # the hardness-limited BEM
    out = stage.comparison_dataset(ref, {"plastic": plastic, "same": _interface(h, p, a, n),
                                         "shifted": shifted, "double": double, "partial": partial},
                                   agreement=0.25)
    assert str(out["reference_limit"].sel(route="plastic").values) == "hardness"
    assert np.allclose(out.sel(route="plastic")["pressure_error"], 0)
    # recommended among the routes held against the elastic boundary elements only: "same"
    # (error 0), not "plastic" (error 0 against the other reference, first in the order)
    assert list(out["recommended_route"].values) == ["same"] * h.size
    same = out.sel(route="same")
    assert np.allclose(same["pressure_error"], 0) and np.allclose(same["area_error"], 0)
    assert same["holds"].all() and float(same["holds_from"]) == h[0] and float(same["holds_to"]) == h[-1]
    sh = out.sel(route="shifted")
    inside = np.isfinite(sh["area_error"].values)
    assert np.allclose(sh["area_error"].values[inside], 0, atol=1e-12) and inside.sum() >= 7
    assert np.allclose(sh["pressure_error"].values[:-1], np.exp(-0.3) - 1)
    assert np.isnan(float(sh["pressure_error"][-1]))  # beyond the route's separations
    d = out.sel(route="double")
    assert np.allclose(d["pressure_error"], 1.0) and not d["holds"].any()
    assert np.isnan(float(d["holds_from"]))
    part = out.sel(route="partial")
    assert float(part["holds_from"]) == h[0] and float(part["holds_to"]) == h[h < 2e-6][-1]
    assert float(part["holds_pressure_high"]) == pytest.approx(p[0])
    assert np.allclose(part["contact_count_ratio"], 2.0)
    assert np.allclose(out["plastic_departure"], -0.5)


def test_no_route_holds_where_the_boundary_elements_do_not_resolve_the_contact(caplog):
    """Where the elastic solve's patches hold fewer than MIN_CELLS_PER_PATCH cells, the
    comparison marks the separation unresolved, a route equal to the reference does not
    hold there (it holds everywhere else), and the warning names those separations."""
    h = np.linspace(1e-6, 3e-6, 9)
    p = 1e8 * np.exp(-3 * h / 1e-6)
    a = 2.0 * p / 1e10
    n = np.full(h.size, 1e9)
    ref = _reference(h, p, a, n)
    cells = np.full(h.size, 40.0)
    cells[-3:] = [9.0, 4.0, 1.5]  # the lightest loads: a few cells per patch
    ref["cells_per_patch"].values[0] = cells
    with caplog.at_level("WARNING", logger="asperity"):
        out = stage.comparison_dataset(ref, {"same": _interface(h, p, a, n)}, agreement=0.25)
    np.testing.assert_array_equal(out["reference_resolved"].values, cells >= stage.MIN_CELLS_PER_PATCH)
    np.testing.assert_array_equal(out["holds"].sel(route="same").values, cells >= stage.MIN_CELLS_PER_PATCH)
    assert float(out.sel(route="same")["holds_to"]) == h[-4]
    assert np.allclose(out.sel(route="same")["pressure_error"], 0)  # the errors are still computed
    expected = (f"the boundary elements do not resolve the contact at 3 of 9 separations "
                f"({h[-3]:.4g} .. {h[-1]:.4g} m): 1.5 to 9 cells per contact patch")
    assert expected in out.attrs["warning"] and expected in caplog.text


def test_the_recommended_route_has_the_smallest_larger_error():
    """Per separation the route whose larger of |pressure error| and |area error| is least;
    none where no route has both errors, or where the reference does not resolve its
    contacts, or where there is no route (the comparison offers only the routes held
    against the elastic boundary elements); asperity show prints it, and where even that
    route is off by more than the scene's agreement, that no route holds and the boundary
    elements are the law."""
    import xarray as xr

    from asperity.cli import recommendations
    from asperity.stages.reference import recommended

    names = ["a", "b", "c"]
    p = np.array([[0.05, -0.30, 0.05, 0.2], [0.10, 0.02, np.nan, 0.1], [-0.5, 0.01, 0.3, 0.1]])
    a = np.array([[0.04, 0.01, 0.1, 0.2], [-0.20, 0.03, np.nan, 0.1], [0.01, -0.5, np.nan, 0.1]])
    resolved = np.array([True, True, True, False])
    best, error = recommended(names, p, a, resolved)
    assert list(best) == ["a", "b", "a", ""]
    np.testing.assert_allclose(error[:3], [0.05, 0.03, 0.1], rtol=1e-15)
    assert np.isnan(error[3])
    none, nan = recommended([], p[:0], a[:0], resolved)  # no elastic route to recommend
    assert list(none) == ["", "", "", ""] and np.all(np.isnan(nan))
    ds = xr.Dataset({"recommended_route": ("separation", best), "recommended_error": ("separation", error),
                     "reference_resolved": ("separation", resolved)},
                    coords={"separation": [1e-6, 2e-6, 3e-6, 4e-6]}, attrs={"sigma": 1e-6, "agreement": 0.08})
    lines = recommendations(ds)
    assert lines[1] == "  separation 1e-06 m (1 sigma): a, within 5 %"
    assert lines[2] == "  separation 2e-06 m (2 sigma): b, within 3 %"
    assert lines[3] == ("  separation 3e-06 m (3 sigma): a, off by 10 %: no route holds within the "
                        "agreement of 8 %; the law here is the boundary elements' "
                        "(route: {kind: boundary_elements})")
    assert lines[4].endswith("none (the boundary elements do not resolve the contact)")
