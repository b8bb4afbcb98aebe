"""The routes beyond independent asperities as a stage (asperity.stages.routes): the
boundary elements as a route, its stiffness, and the validity each route reports."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.references.boundary_element import solve_map
from asperity.stages import routes
from asperity.surface.synthetic import gaussian_map
from tests.scene_defaults import filled, filled_scene

UNITS = {"length": "um", "pressure": "MPa"}
ALUMINUM = filled("material", {"youngs_modulus": 70000.0, "poisson": 0.33, "yield_stress": 280.0})
BARE = filled("material", {"youngs_modulus": 70000.0, "poisson": 0.33})
VALIDITY = filled("validity", {})


def route(**section):
    """A scene's route section with the schema's defaults (in a scene with the map and
    material a route needs)."""
    return filled_scene({"route": section, "material": {"youngs_modulus": 1.0, "poisson": 0.3},
                         "surface": {"map": {"file": "map.npy"}}})["route"]


@pytest.fixture(scope="module")
def surface():
    """A small Gaussian map (128 x 128 points every 1.25 um, sigma 1 um, l = 20 um)."""
    z = gaussian_map(128, 1.25e-6, 1e-6, 20e-6, 3)
    return z - z.mean()


def _surface_ds(z):
    import xarray as xr

    return xr.Dataset({"sigma": ((), float(z.std()), {"units": "m", "long_name": "sigma"})})


def _homogenization(start=1.0, stop=2.5, count=7):
    return filled("homogenization", {"separations": {"start": start, "stop": stop, "count": count,
                                                     "unit": "sigma"}})


def test_the_boundary_element_route_stiffness_is_the_derivative_of_its_own_pressure(surface):
    """-dp/dh of the route (the incremental problem on the contact set) against the central
    difference of two solves 1e-4 sigma apart, at each separation: within 2e-3 (a cell that
    enters or leaves the contact within the step moves the difference, not the stiffness)."""
    z = surface
    ds = routes.route_interface(z, 1.25e-6, 1.25e-6, _surface_ds(z),
                                route(kind="boundary_elements", tolerance=1e-9), ALUMINUM,
                                _homogenization(), UNITS, VALIDITY)
    h = ds["separation"].values
    modulus = ds.attrs["contact_modulus"]
    step = 1e-4 * float(z.std())
    for k in range(h.size):
        pair = solve_map(z, 1.25e-6, 1.25e-6, [h[k] - step, h[k] + step], modulus, tolerance=1e-10)
        p = pair["nominal_pressure"].values
        exact = -(p[1] - p[0]) / (2 * step)
        assert ds["normal_stiffness"].values[k] == pytest.approx(exact, rel=2e-3), h[k]


def test_every_route_writes_the_interface_contract(surface):
    z = surface
    for kind in ("boundary_elements", "persson"):
        ds = routes.route_interface(z, 1.25e-6, 1.25e-6, _surface_ds(z), route(kind=kind), ALUMINUM,
                                    _homogenization(), UNITS, VALIDITY)
        for name, (unit, _) in routes.CONTRACT.items():
            assert ds[name].attrs["units"] == unit, (kind, name)
            assert ds[name].attrs["long_name"], (kind, name)
        assert ds.attrs["route"] == kind
        p = ds["nominal_pressure"].values
        assert np.all(np.diff(p) < 0), kind  # less pressure at larger separations
        # equal to the solver's tolerance (1e-6 sigma; Persson's exactly)
        np.testing.assert_allclose(ds["mean_gap"].values, ds["separation"].values, rtol=1e-6)


def test_an_elastic_route_without_hardness_is_not_called_valid(surface):
    z = surface
    bare = BARE
    ds = routes.route_interface(z, 1.25e-6, 1.25e-6, _surface_ds(z), route(kind="persson"), bare,
                                _homogenization(), UNITS, VALIDITY)
    assert not ds["valid"].values.any()
    assert set(ds["validity"].values) == {"unchecked_yield: no hardness or yield stress in the "
                                          "scene's material"}


def test_the_boundary_elements_judge_their_own_resolution(surface):
    """A map sampled at 4 points per correlation length: toward its highest point the few
    contacts have fewer than 10 cells each, not valid there; above it the flat touches
    nothing (zero force, valid)."""
    z = gaussian_map(128, 1.25e-6, 1e-6, 5e-6, 3)
    z = z - z.mean()
    ds = routes.route_interface(z, 1.25e-6, 1.25e-6, _surface_ds(z), route(kind="boundary_elements"),
                                ALUMINUM, _homogenization(1.0, 4.5, 15), UNITS, VALIDITY)
    cells = ds["cells_per_patch"].values
    low = np.isfinite(cells) & (cells < routes.MIN_CELLS_PER_PATCH)
    assert low.any()
    assert not ds["valid"].values[low].any()
    assert all(str(w).startswith("unresolved_contacts") for w in ds["validity"].values[low])
    free = ds["nominal_pressure"].values == 0
    assert free.any() and ds["valid"].values[free].all()
    assert np.all(ds["normal_stiffness"].values[free] == 0)


def test_a_hardness_limited_route_needs_a_hardness(surface):
    bare = BARE
    with pytest.raises(ValueError, match="route.limit: hardness"):
        routes.route_interface(surface, 1.25e-6, 1.25e-6, _surface_ds(surface),
                               route(kind="boundary_elements", limit="hardness"), bare,
                               _homogenization(), UNITS, VALIDITY)


def _with_peaks(z):
    from asperity.surface.maps import map_peaks

    return map_peaks(z, 1.25e-6, 1.25e-6).assign(
        sigma=((), float(z.std()), {"units": "m", "long_name": "sigma"}))


def test_the_interacting_route_by_each_law(surface):
    """Every law writes the contract; on this Gaussian map the summits' own shape is closer
    to the boundary elements' pressure than the sphere of their mean curvature, at every
    separation from 1 to 2.5 sigma."""
    z = surface
    ds_map = _with_peaks(z)
    bem = routes.route_interface(z, 1.25e-6, 1.25e-6, ds_map, route(kind="boundary_elements"), ALUMINUM,
                                 _homogenization(), UNITS, VALIDITY)
    errors = {}
    for law in ("shape", "elliptic", "hertz"):  # fe: tests/workflow/test_deterministic_reference
        ds = routes.route_interface(z, 1.25e-6, 1.25e-6, ds_map, route(kind="interacting", law=law),
                                    ALUMINUM, _homogenization(), UNITS, VALIDITY)
        for name, (unit, _) in routes.CONTRACT.items():
            assert ds[name].attrs["units"] == unit, (law, name)
        assert ds.attrs["law"] == law
        p = ds["nominal_pressure"].values
        assert np.all(np.isfinite(p)) and np.all(np.diff(p) < 0), law
        errors[law] = np.abs(p / bem["nominal_pressure"].values - 1)
    assert np.all(errors["shape"] < errors["hertz"]), errors
    with pytest.raises(ValueError, match="route.law fe needs the scene's finite element asperities"):
        routes.route_interface(z, 1.25e-6, 1.25e-6, ds_map, route(kind="interacting", law="fe"),
                               ALUMINUM, _homogenization(), UNITS, VALIDITY)


def test_the_fe_law_is_the_shape_law_with_the_spheres_departure(surface):
    """``law: fe`` takes each summit's own shape and the finite element sphere's departure
    from Hertz: a table of exact Hertz spheres gives the shape law's interface (the table's
    linear interpolation within 1e-3); with a table at half of Hertz's force each summit
    carries half of its shape's force on the same area (1e-3), also past the interference
    the sphere was computed to (``extrapolated``: the ratio there is held); a table of
    other shapes than spheres is refused, naming the key. A departure that depends on w/R
    reaches tips outside the table's curvatures at their own w/R (1e-3)."""
    import xarray as xr
    import yaml

    from asperity.homogenize.asperity_laws import hertz_law

    z = surface
    ds_map = _with_peaks(z)
    modulus, _ = routes.contact_modulus_and_hardness(ALUMINUM, UNITS)
    curvature = np.geomspace(0.3, 3.0, 61) * float(np.median(ds_map["curvature"].values))
    grid = np.concatenate([[0.0], np.geomspace(1e-5, 6.0, 400) * float(z.std())])
    hertz = hertz_law(modulus, curvature)
    index = np.repeat(np.arange(curvature.size), grid.size)
    force, area = (v.reshape(curvature.size, grid.size) for v in hertz(np.tile(grid, curvature.size), index)[:2])

    def table(scale, extrapolated=None, geometry="sphere"):
        data = {"force": (("curvature", "interference"), scale * force),
                "contact_area": (("curvature", "interference"), area)}
        if extrapolated is not None:
            data["extrapolated"] = (("curvature", "interference"),
                                    np.broadcast_to(extrapolated, force.shape).astype(np.int8))
        config = yaml.safe_dump({"asperity": {"model": "fe", "geometry": geometry}})
        return xr.Dataset(data, coords={"curvature": curvature, "interference": grid},
                          attrs={"config": config}).expand_dims(height=[0.0])

    def pressure(asperities=None, law="fe"):
        return routes.route_interface(z, 1.25e-6, 1.25e-6, ds_map, route(kind="interacting", law=law),
                                      ALUMINUM, _homogenization(), UNITS, VALIDITY,
                                      asperities=asperities)["nominal_pressure"].values

    np.testing.assert_allclose(pressure(table(1.0)), pressure(law="shape"), rtol=1e-3)
    shape = routes.asperity_law("shape", z, 1.25e-6, 1.25e-6, ds_map, modulus)
    index = np.arange(ds_map.sizes["peak"])
    sigma = float(z.std())
    beyond = grid > 0.1 * sigma  # computed to 0.1 sigma: the ratio 0.5 held past it
    for asperities in (table(0.5), table(np.where(beyond, 0.25, 0.5), beyond)):
        law = routes.asperity_law("fe", z, 1.25e-6, 1.25e-6, ds_map, modulus, asperities)
        for w in (0.05 * sigma, 0.5 * sigma, 2.0 * sigma):
            at = np.full(index.size, w)
            np.testing.assert_allclose(law(at, index)[0], 0.5 * shape(at, index)[0], rtol=1e-3)
            np.testing.assert_allclose(law(at, index)[1], shape(at, index)[1], rtol=1e-3)
    # a departure of w/R alone (a sphere without a length of its own): tips outside the
    # table's curvatures (some below it here) take it at their own w/R
    tip = np.sqrt(np.prod(routes.principal_curvatures(ds_map), axis=0))
    assert tip.min() < curvature[0]
    law = routes.asperity_law("fe", z, 1.25e-6, 1.25e-6, ds_map, modulus,
                              table(1.0 / (1.0 + 300.0 * grid[None, :] * curvature[:, None])))
    for w in (0.05 * sigma, 0.5 * sigma):
        at = np.full(index.size, w)
        np.testing.assert_allclose(law(at, index)[0], shape(at, index)[0] / (1.0 + 300.0 * w * tip),
                                   rtol=1e-3)
    with pytest.raises(ValueError, match="asperity.geometry: sphere"):
        pressure(table(1.0, geometry="cosine"))


@pytest.mark.slow
def test_a_stalled_newton_is_kept_only_close_to_the_solution():
    """A hard case: the synthetic reference map at 8 grid steps, its summits with their own
    shape, pressed to 0.5 sigma, where spots overlap and Newton's line search stalls a little
    above the tolerance. Without `accept` the solve fails naming the separation; with it the
    state is kept, its largest residual within 1e-2 of the largest interference and on the
    record, its pressure finite and within 10 % of the boundary elements."""
    from asperity.homogenize.interacting import interacting_interface
    from asperity.surface.summits import lowpass_map, map_summits

    z0 = gaussian_map(512, 1.25e-6, 1e-6, 20e-6, 11)
    scale = 8 * 1.25e-6
    z = lowpass_map(z0, 1.25e-6, 1.25e-6, scale)
    z = z - z.mean()
    peaks = map_summits(z0, 1.25e-6, 1.25e-6, scale).rename(summit="peak")
    modulus = 70e9 / (1 - 0.33**2)
    h = np.array([0.5, 0.75]) * float(z.std())
    law = routes.asperity_law("shape", z, 1.25e-6, 1.25e-6, peaks, modulus)
    args = (peaks["x"].values, peaks["y"].values, peaks["height"].values, peaks["curvature"].values, h,
            modulus, (512 * 1.25e-6, 512 * 1.25e-6))
    with pytest.raises(RuntimeError, match=r"did not converge at separation 4\.9"):
        interacting_interface(*args, law=law, tolerance=routes.INTERACTING_TOLERANCE)
    ds = interacting_interface(*args, law=law, tolerance=routes.INTERACTING_TOLERANCE,
                               accept=routes.INTERACTING_ACCEPT)
    residual = ds["residual"].values
    reach = float(peaks["height"].max()) - h
    assert residual[0] > routes.INTERACTING_TOLERANCE * reach[0]  # it did stall there
    assert np.all(residual <= routes.INTERACTING_ACCEPT * reach)
    bem = solve_map(z, 1.25e-6, 1.25e-6, h[:1], modulus)
    assert np.isfinite(ds["nominal_pressure"].values).all()
    assert float(ds["nominal_pressure"][0]) == pytest.approx(float(bem["nominal_pressure"][0]), rel=0.10)
