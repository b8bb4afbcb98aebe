"""Scene deterministic_reference at draft, end to end through Snakemake: the
boundary-element reference beside the statistical routes on the same map."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.io.netcdf import missing_attributes, read_dataset

from .conftest import planned_jobs, result, run_scenes, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

SCENE = "deterministic_reference"
ARGS = ("--config", f"scenes=[{SCENE}]", "accuracy=draft", "studies=False")
ROUTES = ("nayak_hertz", "nayak_fe", "peaks", "interacting", "persson", "interacting_j2")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return run_scenes(tmp_path_factory, "reference", *ARGS)


def test_files_and_attributes(run):
    for name in ("reference.nc", "comparison.nc", "surface.nc"):
        ds = result(run, SCENE, name)
        assert missing_attributes(ds) == [], name
    assert (run / "results" / SCENE / "figures" / "reference.png").stat().st_size > 10_000
    for route in ROUTES:
        assert (run / "results" / f"{SCENE}+{route}" / "interface.nc").exists()


def test_every_route_writes_the_same_contract(run):
    """Statistical, interacting and Persson routes: the variables of interface.nc with their
    units, on the reference's separations, with valid and validity; the comparison names,
    per separation the boundary elements resolve, the route closest to them, whose error is
    the smallest of the routes' larger errors (pressure or area)."""
    ref = result(run, SCENE, "reference.nc")
    units = {"nominal_pressure": "Pa", "contact_area_ratio": "1", "normal_stiffness": "Pa/m",
             "contact_count": "1/m^2"}
    for route in ROUTES:
        ds = result(run, f"{SCENE}+{route}", "interface.nc")
        assert missing_attributes(ds) == [], route
        for name, unit in units.items():
            assert ds[name].attrs["units"] == unit, (route, name)
        assert {"valid", "validity"} <= set(ds.data_vars), route
        np.testing.assert_allclose(ds["separation"].values, ref["separation"].values, rtol=1e-12)
    cmp_ = result(run, SCENE, "comparison.nc")
    # the J2 asperities against the boundary elements limited by the hardness, the rest elastic
    assert dict(zip(cmp_["route"].values, cmp_["reference_limit"].values)) == {
        route: "hardness" if route == "interacting_j2" else "elastic" for route in ROUTES}
    # the recommended route: the elastic route whose larger error is smallest (the J2 route's
    # errors are against another reference)
    both = np.isfinite(cmp_["pressure_error"]) & np.isfinite(cmp_["area_error"])
    worst = np.fmax(np.abs(cmp_["pressure_error"]), np.abs(cmp_["area_error"])).where(both)
    worst = worst.where(cmp_["reference_limit"] == "elastic")
    for k, best in enumerate(cmp_["recommended_route"].values):
        column = worst.isel(separation=k)
        if not best:  # no route with both errors there, or the reference does not resolve it
            assert not (np.isfinite(column).any() and bool(cmp_["reference_resolved"][k]))
            continue
        assert float(column.sel(route=best)) == float(column.min(skipna=True))
        assert float(cmp_["recommended_error"][k]) == float(column.min(skipna=True))


def test_light_load_agreement_with_asperity_theory(run):
    """Where asperity theory is expected to hold (A/A0 from 0.5 to 4 %: separate contacts,
    about 20 to 100 of them), the map-peaks route (Hertz asperities on the map's own peaks)
    is within 30 % of the elastic boundary-element pressure and the Nayak-Hertz route within
    a factor 1.5 (the Nayak density is an ensemble average; the map is one realization)."""
    cmp_ = result(run, SCENE, "comparison.nc")
    light = (cmp_["reference_area_ratio"] >= 0.005) & (cmp_["reference_area_ratio"] <= 0.04)
    assert int(light.sum()) >= 3
    peaks = cmp_["pressure_error"].sel(route="peaks").values[light.values]
    assert np.all(np.abs(peaks) < 0.30), peaks
    ratio = 1 + cmp_["pressure_error"].sel(route="nayak_hertz").values[light.values]
    assert np.all((ratio > 1 / 1.5) & (ratio < 1.5)), ratio
    assert np.isfinite(float(cmp_["holds_from"].sel(route="peaks")))


def test_area_load_slope_and_hardness(run):
    """Elastic, A/A0 from 1 to 10 %: the linear regime A/A0 = kappa p / (E* h'_rms), i.e. a
    log-log slope of area against pressure between 0.85 and 1 (the boundary-element area
    grows slightly slower than the load as contacts merge), and kappa above Persson's
    sqrt(8/pi) and below 3: at the scene's 16 points per correlation length the small
    contacts have tens of cells, where even the perimeter-corrected area is a little too
    large (the literature's bracket is asserted on a finer-sampled window in
    tests/references); hardness: no pressure above
    H, and at equal pressure the plastic area is larger than the elastic one."""
    ref = result(run, SCENE, "reference.nc")
    el = ref.sel(limit="elastic")
    kappa = el["contact_area_ratio"] * ref.attrs["contact_modulus"] * ref.attrs["gradient_rms"] \
        / el["nominal_pressure"]
    window = (el["contact_area_ratio"] >= 0.01) & (el["contact_area_ratio"] <= 0.10)
    k = kappa.values[window.values]
    assert k.size >= 3 and np.all((k > np.sqrt(8 / np.pi)) & (k < 3.0)), k
    a, p = el["contact_area_ratio"].values[window.values], el["nominal_pressure"].values[window.values]
    slope = np.polyfit(np.log(p), np.log(a), 1)[0]
    assert 0.85 < slope <= 1.0, slope
    pl = ref.sel(limit="hardness")
    assert float(pl["max_pressure"].max()) <= ref.attrs["hardness"] * (1 + 1e-6)
    p = el["nominal_pressure"].values
    a_plastic = np.interp(np.log(p[window.values]), np.log(pl["nominal_pressure"].values[::-1]),
                          pl["contact_area_ratio"].values[::-1])
    assert np.all(a_plastic > el["contact_area_ratio"].values[window.values])


def test_the_route_errors_study_tabulates_the_comparison(run):
    """Rule route_errors on a table of this scene: the comparison's own errors per route and
    separation (nothing computed again), the band's ranges over the separations whose
    boundary-element area lies in 0.1-10 % and are resolved, the goal by the route's
    reference, and a figure."""
    from asperity.studies.route_errors import GOALS

    study = "route_errors={'accuracy': 'draft', 'tables': {'one': ['%s']}}" % SCENE
    snakemake(run, "results/studies/route_errors_one.nc", "--config", "accuracy=draft", study)
    ds = read_dataset(run / "results" / "studies" / "route_errors_one.nc").sel(scene=SCENE)
    assert missing_attributes(ds) == []
    cmp_ = result(run, SCENE, "comparison.nc")
    for route in cmp_["route"].values:
        for name in ("pressure_error", "area_error"):
            np.testing.assert_array_equal(ds[name].sel(route=route).values, cmp_[name].sel(route=route).values)
        band = ((cmp_["reference_area_ratio"] >= 1e-3) & (cmp_["reference_area_ratio"] <= 0.1)
                & cmp_["reference_resolved"]).values
        worst = np.nanmax(np.abs(np.r_[cmp_["pressure_error"].sel(route=route).values[band],
                                        cmp_["area_error"].sel(route=route).values[band]]))
        assert float(ds["largest_error"].sel(route=route)) == worst
        assert int(ds["band_steps"]) == band.sum() >= 3
        limit = str(cmp_["reference_limit"].sel(route=route).values)
        assert float(ds["goal"].sel(route=route)) == GOALS[limit]
    np.testing.assert_allclose(ds["separation_over_sigma"].values,
                               cmp_["separation"].values / result(run, SCENE, "reference.nc").attrs["sigma"])
    # what explains the misses: the map's own numbers and the interacting route's merged load
    assert float(ds["skewness"]) == float(result(run, SCENE, "surface.nc")["skewness"])
    merged = result(run, f"{SCENE}+interacting", "interface.nc")["merged_load_fraction"]
    np.testing.assert_allclose(ds["merged_load_fraction"].sel(route="interacting").values,
                               merged.interp(separation=cmp_["separation"].values).values, rtol=1e-12)
    assert (run / "results" / "studies" / "route_errors_one.png").read_bytes()[:4] == b"\x89PNG"


def test_reference_is_cached_apart_from_the_routes(run):
    """A route's homogenization changed: its interface and the comparison rerun, the
    boundary-element solve does not (it depends on the map, material and solver only)."""
    scene_file = run / "config" / "scenes" / f"{SCENE}.yaml"
    text = scene_file.read_text()
    scene_file.write_text(text.replace("cells: [60, 40]}\n  nayak_fe", "cells: [50, 40]}\n  nayak_fe"))
    try:
        jobs = planned_jobs(snakemake(run, "-n", *ARGS))
    finally:
        scene_file.write_text(text)
    assert "reference" not in jobs and jobs.get("reference_comparison") == 1, jobs
    assert jobs.get("interface") == 1, jobs
