"""Scene anisotropic_reference at draft, end to end through Snakemake: a Gaussian map with
a lay (correlation lengths 4 to 1), the boundary-element contact of it beside the
anisotropic route of report 2.4.2 / 2.5.2, the isotropic routes on the same map, and the
friction of the anisotropic route against the sliding direction (9.1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.io.netcdf import missing_attributes

from .conftest import result, run_scenes

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

SCENE = "anisotropic_reference"
ARGS = ("--config", f"scenes=[{SCENE}]", "accuracy=draft", "studies=False")
ROUTES = ("anisotropic", "anisotropic_spheres", "anisotropic_j2", "anisotropic_j2_sphere", "nayak_hertz",
          "interacting",
          "interacting_elliptic", "persson")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return run_scenes(tmp_path_factory, "anisotropic", *ARGS)


def test_every_route_writes_the_contract(run):
    ref = result(run, SCENE, "reference.nc")
    for route in ROUTES:
        ds = result(run, f"{SCENE}+{route}", "interface.nc")
        assert missing_attributes(ds) == [], route
        assert {"valid", "validity"} <= set(ds.data_vars), route
        np.testing.assert_allclose(ds["separation"].values, ref["separation"].values, rtol=1e-12)
    ds = result(run, f"{SCENE}+anisotropic", "interface.nc")
    assert ds.attrs["route"] == "anisotropic" and ds.attrs["law"] == "elliptic"
    assert result(run, f"{SCENE}+anisotropic_spheres", "interface.nc").attrs["law"] == "hertz"
    assert (run / "results" / SCENE / "figures" / "reference.png").stat().st_size > 10_000


def test_the_elliptic_interacting_route_reaches_every_separation(run):
    """The hard case of the interacting route: elliptic summits of a map with a lay, where
    Newton from the last separation cycles between contact sets; the flat approaches in
    half steps (`interacting._approach`).  Every separation is solved, its largest
    residual within what the route accepts (1e-2 of the largest interference), and the
    pressure and area fall monotonically as the flat withdraws."""
    from asperity.stages.routes import INTERACTING_ACCEPT

    ds = result(run, f"{SCENE}+interacting_elliptic", "interface.nc")
    surface = result(run, SCENE, "surface.nc")
    scale = float(surface["height"].max()) - ds["separation"].values
    touching = scale > 0
    assert np.all(np.isfinite(ds["nominal_pressure"].values))
    assert np.all(ds["residual"].values[touching] <= INTERACTING_ACCEPT * scale[touching])
    assert np.all(np.diff(ds["nominal_pressure"].values[touching]) < 0)
    assert np.all(np.diff(ds["contact_area_ratio"].values[touching]) < 0)


def test_the_map_has_its_lay(run):
    """The generated map's slope variances: m20 = 2 sigma^2 / (4 l)^2 along the lay and
    m02 = 2 sigma^2 / l^2 across it (sigma 1 um, l = 14.577 um), within 10 % (one
    realization of 512^2 points, about 300 correlation areas: a spread of about 8 %)."""
    s = result(run, SCENE, "surface.nc")
    l, sigma = 14.577e-6, 1e-6
    assert float(s["m20"]) == pytest.approx(2 * sigma**2 / (4 * l) ** 2, rel=0.1)
    assert float(s["m02"]) == pytest.approx(2 * sigma**2 / l**2, rel=0.1)


def test_the_anisotropic_route_is_closer_than_the_isotropic_one(run):
    """Where the boundary elements resolve their contacts and their area ratio lies between
    0.1 % and 10 %, the anisotropic route's pressure error (equal mean gap) and area error
    (equal pressure) are smaller than those of the isotropic Nayak-Hertz route on the same
    moments (the issue's goal), in their largest magnitude and in their rms over the band's
    separations where both are defined (at the lightest load, A/A0 = 0.13 %, the two
    pressure errors are of equal size and opposite sign, +45 and -43 %), and within the
    envelope measured at draft, 50 % in pressure and 40 % in area (45 % and 31 % measured
    against the perimeter-corrected area; the table of the docs, rule route_errors,
    holds the numbers)."""
    cmp_ = result(run, SCENE, "comparison.nc")
    a = cmp_["reference_area_ratio"].values
    band = (a >= 1e-3) & (a <= 0.1) & cmp_["reference_resolved"].values.astype(bool)
    assert band.sum() >= 5
    for name, envelope in (("pressure_error", 0.5), ("area_error", 0.4)):
        mine = cmp_[name].sel(route="anisotropic").values[band]
        theirs = cmp_[name].sel(route="nayak_hertz").values[band]
        ok = np.isfinite(mine) & np.isfinite(theirs)
        assert ok.sum() >= 5, name
        assert np.abs(mine[ok]).max() < np.abs(theirs[ok]).max(), (name, mine, theirs)
        assert np.sqrt(np.mean(mine[ok] ** 2)) < np.sqrt(np.mean(theirs[ok] ** 2)), (name, mine, theirs)
        assert np.all(np.abs(mine[ok]) < envelope), (name, mine)


@pytest.mark.parametrize("route, envelope, measured", [
    ("anisotropic_j2", (0.4, 0.1), (1.71, 1.80, 0.30, 0.024)),
    ("anisotropic_j2_sphere", (0.4, 0.2), (1.84, 1.97, 0.35, 0.163)),
])
def test_the_j2_anisotropic_routes_against_the_hardness_limited_contact(run, route, envelope, measured):
    """The elliptic summits with a J2 finite element departure from Hertz (route.law fe):
    ``anisotropic_j2`` from 3-D elliptic paraboloids at three curvature ratios,
    ``anisotropic_j2_sphere`` from the axisymmetric sphere of equal peak pressure. Both are
    plastic, held against the boundary elements limited by the hardness
    (``reference_limit``). Their summits are pressed far past first yield (E / Y = 250):
    the pressure below half of the elastic route's and the area 1.5 to 2.1 times its area,
    near the fully plastic truncation's 2 (2 pi R w against Hertz's pi R w; measured area
    ratios `measured[:2]`). Where the boundary elements' area ratio lies between 0.1 % and
    10 %, the errors are within the envelope measured at draft (`envelope`, pressure and
    area; measured `measured[2:]`): the 3-D ellipses' area error is a sixth of the
    sphere's."""
    j2 = result(run, f"{SCENE}+{route}", "interface.nc")
    elastic = result(run, f"{SCENE}+anisotropic", "interface.nc")
    assert j2.attrs["law"] == "fe" and j2.attrs["limit"] == "hardness"
    cmp_ = result(run, SCENE, "comparison.nc")
    assert str(cmp_["reference_limit"].sel(route=route).values) == "hardness"
    ratio_p = j2["nominal_pressure"].values / elastic["nominal_pressure"].values
    ratio_a = j2["contact_area_ratio"].values / elastic["contact_area_ratio"].values
    assert np.all(ratio_p < 0.5), ratio_p
    assert np.all((ratio_a > 1.5) & (ratio_a < 2.1)), ratio_a
    a = cmp_["reference_area_ratio"].values
    band = (a >= 1e-3) & (a <= 0.1) & cmp_["reference_resolved"].values.astype(bool)
    assert band.sum() >= 5
    for name, limit in zip(("pressure_error", "area_error"), envelope):
        err = cmp_[name].sel(route=route).values[band]
        assert np.all(np.isfinite(err)) and np.all(np.abs(err) < limit), (name, err)
    # the jobs reach every summit that carries load: under 0.1 % of it extrapolated
    assert np.all(j2["extrapolated_load_fraction"].values < 1e-3)


def test_the_elliptic_jobs_over_the_curvature_ratio(run):
    """``anisotropic_j2``'s plan: one 3-D job per curvature ratio (1/8, 0.35, 1), pressed
    to 1, 10, 100 and 1000 times first yield of the sphere of equal peak pressure. The
    elastic twin of each level, on a block of 20 long semi-axes, is elliptic Hertz within
    3 % in force (the finite block's stiffening, measured 0.6 to 2.4 %); the J2 summit's
    force departs from it by less than 1 % at first yield, then falls with the
    interference. The job of ratio 1 is a sphere's tip: its departure is the axisymmetric
    J2 sphere's of ``anisotropic_j2_sphere`` within 5 % at ten times first yield
    (measured 3.9 %; at a hundred times 10.5 %, at a thousand 49 %: draft's 3-D mesh
    puts one element across the contact)."""
    from asperity.stages.routes import sphere_departure

    plan = result(run, f"{SCENE}+anisotropic_j2", "plan.nc")
    table = result(run, f"{SCENE}+anisotropic_j2", "asperities.nc")
    assert plan.attrs["kind"] == "elliptic" and plan.sizes["sample"] == 3
    np.testing.assert_allclose(table["ratio"].values, [0.125, 0.125 ** 0.5, 1.0], rtol=1e-12)
    s = table["scaled_interference"].values
    np.testing.assert_allclose(s / s[:, :1], np.broadcast_to([1.0, 10.0, 100.0, 1000.0], s.shape), rtol=1e-9)
    twin = table["elastic_force"].values / table["hertz_force"].values
    assert np.all(np.abs(twin - 1.0) < 0.03), twin
    d = table["force_departure"].values
    assert np.all(np.abs(d[:, 0] - 1.0) < 0.01) and np.all(np.diff(d, axis=1) < 0), d
    sphere = result(run, f"{SCENE}+anisotropic_j2_sphere", "asperities.nc")
    modulus = 70e9 / (1.0 - 0.33**2)
    ball = sphere_departure(sphere, modulus)(s[-1], 1.0)[0]
    assert d[-1, 1] == pytest.approx(ball[1], rel=0.05), (d[-1], ball)


def test_friction_against_the_sliding_direction(run):
    """mu_interlocking along 13 directions from 0 to 180 degrees: equal under a half turn
    (1e-12), smallest along the lay (x) and largest across it, in the ratio
    sqrt(m(90 deg) / m(0)) = sqrt(m02 / m20) of the map's slope covariance (1e-12), the
    lay found within 2 degrees of x (the map's m11 turns it by a fraction of a degree),
    and mu = mu_shear + mu_interlocking on (separation, direction)."""
    f = result(run, f"{SCENE}+anisotropic", "friction.nc")
    s = result(run, SCENE, "surface.nc")
    assert missing_attributes(f) == []
    theta = f["direction"].values
    np.testing.assert_allclose(np.degrees(theta), np.linspace(0, 180, 13), atol=1e-12)
    mu_i = f["mu_interlocking"].values
    assert mu_i[0] == pytest.approx(mu_i[-1], rel=1e-12)
    assert np.argmin(mu_i) in (0, 12) and np.argmax(mu_i) == 6
    assert mu_i[6] / mu_i[0] == pytest.approx(math.sqrt(float(s["m02"]) / float(s["m20"])), rel=1e-12)
    lay = math.degrees(float(f.attrs["lay_direction"]))
    assert min(lay, 180.0 - lay) < 2.0
    np.testing.assert_allclose(f["mu"].values, f["mu_shear"].values[:, None] + mu_i[None, :], rtol=1e-14)
