"""The anisotropic route's finite element summits over the curvature ratio (report 2.4.2,
2.5.2; issue #52 item 2): the plan of one 3-D job per ratio, the departure table read
between the ratios and past the jobs' reach, and the load counted there."""

import math

import numpy as np
import pytest
import xarray as xr

from asperity.homogenize.anisotropic import (anisotropic_interface, elliptic_law, peak_pressure_curvature,
                                             with_departure)
from asperity.peaks.anisotropic import AnisotropicDensity
from asperity.scene import Asperity, Material
from asperity.scene.checks import SceneError, check_scene
from asperity.stages import routes

E, NU, Y = 70e9, 0.33, 280e6
J2 = Material(model="j2", youngs_modulus=E, poisson=NU, yield_stress=Y)


@pytest.fixture(scope="module")
def surface_ds():
    from asperity.surface import map_statistics
    from asperity.surface.synthetic import gaussian_map

    z = gaussian_map(256, 1.25e-6, 1e-6, 10e-6, 4, aspect=4.0)
    return map_statistics(z, 1.25e-6, 1.25e-6)


def _asperity(**changes):
    base = dict(model="fe", value=1.0, geometry="elliptic", mapping="representative", width_to_height=None,
                levels=40, contact="penalty", max_height_fraction=0.3, max_radius_fraction=0.25, velocity=None,
                unloading_levels=4, unloading_smallest=0.05, unloading_check=False, scaling="auto",
                reference_curvature=None)
    return Asperity(**{**base, **changes})


def _plan(surface_ds, **changes):
    from asperity.population.samples import scene_plan
    from asperity.scene import Population

    population = Population.__new__(Population)  # the elliptic plan reads no population key
    return scene_plan(surface_ds, population, _asperity(**changes), J2, frozenset({"plasticity"}), "draft")


def test_the_plan_is_one_job_per_curvature_ratio(surface_ds):
    """Three ratios geometrically spaced from the summits' 5 % quantile of kappa_2 / kappa_1
    (at least 1/8) to 1, at the summits' median kappa_1; each job from first yield of the
    sphere of equal Hertz peak pressure, w_c = (pi K H / (2 E*))^2 / kappa_p (Kogut and
    Etsion's K H = (0.454 + 0.41 nu) 2.8 Y), to 1000 w_c (1e-12); distinct keys, all jobs;
    a change of how far the jobs press changes every key."""
    plan = _plan(surface_ds)
    assert plan.attrs["kind"] == "elliptic" and plan.sizes["sample"] == 3
    ratios = plan["sample_ratio"].values
    density = AnisotropicDensity.from_surface(surface_ds)
    _, k1, t, weight = density.nodes()
    share = np.cumsum(weight.sum(axis=(0, 1))) / weight.sum()
    smallest = max(t[np.searchsorted(share, 0.05)], 1 / 8)
    np.testing.assert_allclose(ratios, np.geomspace(smallest, 1.0, 3), rtol=1e-12)
    assert ratios[0] < 1.0
    kref = float(plan.attrs["reference_curvature"])
    half = np.cumsum(weight.sum(axis=(0, 2))) / weight.sum()
    assert kref == k1[np.searchsorted(half, 0.5)]
    specs = [__import__("json").loads(s) for s in plan["spec"].values]
    modulus = E / (1 - NU**2)
    for ratio, spec in zip(ratios, specs):
        kp = float(peak_pressure_curvature(np.array(kref), np.array(ratio)))
        w_c = (math.pi * (0.454 + 0.41 * NU) * 2.8 * Y / (2 * modulus)) ** 2 / kp
        np.testing.assert_allclose(spec["range"], [w_c, 1000 * w_c], rtol=1e-12)
        assert spec["geometry"] == "elliptic" and spec["ratio"] == ratio and spec["curvature"] == kref
    assert len(set(plan["key"].values)) == 3 and plan["job"].values.all()
    farther = _plan(surface_ds, yield_multiple=500.0)
    assert not set(farther["key"].values) & set(plan["key"].values)


def test_the_elliptic_kind_refuses_what_it_does_not_model(surface_ds):
    """An elastic body (Hertz's elliptic contact is exact there), other effects, and an
    elliptic asperity outside the anisotropic route's law fe are refused, naming the key."""
    from asperity.population.samples import scene_plan
    from asperity.scene import Population

    population = Population.__new__(Population)
    with pytest.raises(ValueError, match="route.law: elliptic"):
        scene_plan(surface_ds, population, _asperity(), J2, frozenset(), "draft")
    with pytest.raises(ValueError, match=r"effects \['adhesion'\]"):
        scene_plan(surface_ds, population, _asperity(), J2, frozenset({"plasticity", "adhesion"}), "draft")
    asperity = {"model": "fe", "geometry": "elliptic"}
    with pytest.raises(SceneError, match="asperity.geometry"):
        check_scene({"asperity": asperity, "route": {"kind": "interacting", "law": "fe"}})
    with pytest.raises(SceneError, match="routes.j2.asperity.geometry"):
        check_scene({"routes": {"j2": {"asperity": asperity, "route": {"kind": "anisotropic"}}}})
    check_scene({"routes": {"j2": {"asperity": asperity, "route": {"kind": "anisotropic", "law": "fe"}}}})


RATIOS = np.array([0.125, 0.5, 1.0])
S0 = 1e-4


def _slope(t):
    """The departure's slope in ln s of the synthetic table: linear in ln t."""
    return 0.1 + 0.05 * np.log(t)


def _table(ratios=RATIOS, levels=4):
    """Jobs whose force ratio is 1 - slope(t) ln(s / s0) and area ratio 1 + ln(s / s0) / 10 at
    s = s0 10^k, k = 0 .. levels - 1 (bilinear in ln s and ln t)."""
    s = S0 * 10.0 ** np.arange(levels)
    scaled = np.broadcast_to(s, (ratios.size, levels))
    log = np.log(scaled / S0)
    return xr.Dataset({
        "scaled_interference": (("ratio", "level"), scaled.copy()),
        "force_departure": (("ratio", "level"), 1.0 - _slope(ratios)[:, None] * log),
        "area_departure": (("ratio", "level"), 1.0 + log / 10.0)},
        coords={"ratio": ratios, "level": np.arange(levels)})


def test_the_departure_is_read_between_the_jobs():
    """`elliptic_departure` of a table bilinear in ln s and ln t gives it exactly (1e-12)
    between the jobs, its slope in s as -slope(t) / s (1e-12); a ratio outside the jobs'
    takes the nearest job's, below the first level the first level's ratios are held,
    past the last the last's, marked beyond the reach; one job alone is read in s only."""
    departure = routes.elliptic_departure(_table())
    s = np.array([2e-4, 3e-3, 5e-2, 0.09])
    for t in (0.125, 0.2, 0.5, 0.7, 1.0):
        rf, ra, drf, beyond = departure(s, np.full(s.size, t))
        np.testing.assert_allclose(rf, 1.0 - _slope(t) * np.log(s / S0), rtol=1e-12)
        np.testing.assert_allclose(ra, 1.0 + np.log(s / S0) / 10.0, rtol=1e-12)
        np.testing.assert_allclose(drf, -_slope(t) / s, rtol=1e-12)
        assert not beyond.any()
    inside = departure(s, np.full(s.size, 0.125))
    for name, value in zip(("force", "area", "slope"), departure(s, np.full(s.size, 0.01))[:3]):
        np.testing.assert_array_equal(value, inside[("force", "area", "slope").index(name)])
    rf, ra, drf, beyond = departure(np.array([1e-6, 1.0, 10.0]), np.array([0.3, 0.3, 0.3]))
    np.testing.assert_allclose(rf, [1.0, 1.0 - _slope(0.3) * np.log(10.0 ** 3),
                                    1.0 - _slope(0.3) * np.log(10.0 ** 3)], rtol=1e-12)
    np.testing.assert_array_equal(drf, 0.0)
    np.testing.assert_array_equal(beyond, [False, True, True])
    alone = routes.elliptic_departure(_table(np.array([0.5])))
    np.testing.assert_allclose(alone(s, np.full(s.size, 0.1))[0], 1.0 - _slope(0.5) * np.log(s / S0),
                               rtol=1e-12)


def test_the_route_counts_the_load_past_the_jobs(surface_ds):
    """With every departure 1 the law is elliptic Hertz (1e-12); the load carried by the
    summits with w kappa_p past the jobs' last level is `anisotropic_interface`'s sum of
    their forces (1e-12), and the route's extrapolated_load_fraction is its share of the
    pressure."""
    from tests.references.test_routes import ALUMINUM, UNITS, VALIDITY, _homogenization, route

    modulus, _ = routes.contact_modulus_and_hardness(ALUMINUM, UNITS)
    flat = _table()
    flat["force_departure"][:] = 1.0
    flat["area_departure"][:] = 1.0
    z = np.zeros((8, 8))  # the route reads the moments
    ds = routes.route_interface(z, 1.25e-6, 1.25e-6, surface_ds, route(kind="anisotropic", law="fe"),
                                ALUMINUM, _homogenization(0.5, 3.0, 6), UNITS, VALIDITY, asperities=flat)
    density = AnisotropicDensity.from_surface(surface_ds)
    h = ds["separation"].values
    law = with_departure(elliptic_law(modulus), routes.elliptic_departure(flat))
    got = anisotropic_interface(density, law, h)
    plain = anisotropic_interface(density, elliptic_law(modulus), h)
    np.testing.assert_allclose(got["nominal_pressure"].values, plain["nominal_pressure"].values, rtol=1e-12)
    reach = float(flat["scaled_interference"].max())

    def past(w, k1, t):
        force = elliptic_law(modulus)(w, k1, t)[0]
        far = np.maximum(w, 0.0) * peak_pressure_curvature(k1, t) > reach
        return force * far, 0 * w, 0 * w, 0 * w

    expected = anisotropic_interface(density, past, h)["nominal_pressure"].values
    np.testing.assert_allclose(got["extrapolated_force_per_unit_area"].values, expected, rtol=1e-12)
    assert 0 < expected[0] < plain["nominal_pressure"].values[0]
    share = ds["extrapolated_load_fraction"].values
    np.testing.assert_allclose(share, expected / plain["nominal_pressure"].values, rtol=1e-9)
