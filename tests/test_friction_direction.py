"""Friction along a sliding direction (report 2.3.2, 9.1): the rms slope along theta,
m(theta) = m20 cos^2 + 2 m11 cos sin + m02 sin^2, its extremes at the lay, and
``friction.direction`` in friction.nc and its figure."""

import math

import numpy as np
import pytest
import xarray as xr

from asperity import friction
from asperity.io.netcdf import missing_attributes, read_dataset, write_dataset
from asperity.plots.friction import friction_figure
from asperity.references import greenwood_williamson
from asperity.scene import Friction, Units
from asperity.scene.checks import SceneError
from asperity.stages import surface as surface_stage
from asperity.surface.maps import map_statistics
from tests.scene_defaults import filled

UNITS = {"length": "um", "pressure": "MPa"}
STEEL = filled("surface", {"statistics": {
    "sigma": 4.91, "sigma_slope": 0.16, "sigma_curvature": 0.0227, "peak_density": 0.000508}})
# slope covariances [[m20, m11], [m11, m02]]: anisotropic with each sign of m11, aligned, nearly 1D
COVARIANCES = [(0.04, 0.003, 0.01), (0.01, -0.012, 0.03), (0.02, 0.0, 0.005), (0.0256, 0.0199, 0.0156)]


def friction_of(section: dict) -> Friction:
    return Friction.from_section(filled("friction", section), Units.from_section(UNITS))


def moments(m20, m11, m02) -> xr.Dataset:
    one = {"units": "1", "long_name": "slope moment"}
    return xr.Dataset({"m20": ((), m20, one), "m11": ((), m11, one), "m02": ((), m02, one)})


def gw_interface():
    h = np.linspace(0.0, 3.0, 16) * 7.07106e-7
    return greenwood_williamson.gw_interface(h, 0.1414e-3, 7.07106e-7, 300e6, 321.7335 * 9.80665e6, 0.3)


def anisotropic_map(n=256, lx=48.0, ly=12.0, seed=3):
    """White noise filtered by exp(-(kx^2 lx^2 + ky^2 ly^2)/8) (lx/ly = 4, unit spacing):
    a Gaussian map whose slopes are smaller along x, the lay, by lx/ly."""
    noise = np.random.default_rng(seed).standard_normal((n, n))
    k = 2 * np.pi * np.fft.fftfreq(n)
    ky, kx = np.meshgrid(k, k, indexing="ij")
    z = np.fft.ifft2(np.fft.fft2(noise) * np.exp(-(kx**2 * lx**2 + ky**2 * ly**2) / 8)).real
    return z / z.std()


def rms_difference(z, di, dj, skip=4):
    """rms slope along the step (di rows, dj columns) of a unit-spacing map by the
    fourth-order central difference (-z(+2) + 8 z(+1) - 8 z(-1) + z(-2)) / (12 h), on the
    points `skip` steps or more from the ends along the step (those where the order-8
    stencils of `map_statistics` are whole: the same sample, whose long correlation
    along x makes the few end columns count)."""
    n0, n1 = z.shape
    s0, s1 = skip * abs(di), skip * abs(dj)
    at = lambda s: z[s0 + s * di: n0 - s0 + s * di, s1 + s * dj: n1 - s1 + s * dj]  # noqa: E731
    slope = (-at(2) + 8 * at(1) - 8 * at(-1) + at(-2)) / (12 * math.hypot(di, dj))
    return float(slope.std(ddof=1))


@pytest.mark.parametrize("cov", COVARIANCES)
def test_slope_along_is_symmetric_under_a_half_turn(cov):
    """m(theta + pi) = m(theta): equal to round-off on 361 directions (1e-14 of the largest
    slope: near the lay of a nearly one-dimensional lay m(theta) is a difference)."""
    theta = np.radians(np.linspace(-180.0, 180.0, 361))
    s = friction.slope_along(moments(*cov), theta)
    np.testing.assert_allclose(friction.slope_along(moments(*cov), theta + np.pi), s, rtol=0,
                               atol=1e-14 * s.max())
    # and the quadratic form of the brief's first line, term by term
    c, n = np.cos(theta), np.sin(theta)
    m20, m11, m02 = cov
    np.testing.assert_allclose(s**2, m20 * c * c + 2 * m11 * c * n + m02 * n * n, rtol=1e-13, atol=1e-17)


@pytest.mark.parametrize("cov", COVARIANCES)
def test_extremes_along_and_across_the_lay_are_the_eigen_pairs(cov):
    """sqrt of the eigenvalues of [[m20, m11], [m11, m02]] (numpy.linalg.eigh) to 1e-12,
    at its eigenvectors (|sin| of the angle between them < 1e-12); no direction of a
    fine sweep goes beyond them; friction.nc carries them."""
    m20, m11, m02 = cov
    values, vectors = np.linalg.eigh(np.array([[m20, m11], [m11, m02]]))
    principal = friction.lay(m20, m11, m02)
    assert principal["sigma_slope_along_lay"] == pytest.approx(math.sqrt(max(values[0], 0)), rel=1e-12, abs=1e-15)
    assert principal["sigma_slope_across_lay"] == pytest.approx(math.sqrt(values[1]), rel=1e-12)
    for key, vector in (("lay", vectors[:, 0]), ("steepest", vectors[:, 1])):
        along = np.array([math.cos(principal[key]), math.sin(principal[key])])
        assert abs(along[0] * vector[1] - along[1] * vector[0]) < 1e-12
        assert 0.0 <= principal[key] < math.pi
    surface = moments(*cov)
    at = friction.slope_along(surface, [principal["lay"], principal["steepest"]])
    np.testing.assert_allclose(at, [principal["sigma_slope_along_lay"], principal["sigma_slope_across_lay"]],
                               rtol=1e-12, atol=1e-9)
    fine = friction.slope_along(surface, np.linspace(0.0, np.pi, 20001))
    assert fine.min() >= principal["sigma_slope_along_lay"] * (1 - 1e-12) - 1e-9
    assert fine.max() <= principal["sigma_slope_across_lay"] * (1 + 1e-12)
    ds = friction.friction_dataset(gw_interface(), surface, friction_of(
        {"junction_shear_strength": 150.0, "interlocking": "rms_slope",
         "direction": {"start": 0.0, "stop": 180.0, "count": 13}}), None)
    for key in ("lay_direction", "steepest_direction", "sigma_slope_along_lay", "sigma_slope_across_lay"):
        assert ds.attrs[key] == principal[key.removesuffix("_direction")]


def test_slope_along_x_y_and_the_diagonal_of_an_anisotropic_map():
    """A filtered-noise map with lx/ly = 4: sqrt(m(theta)) from the map's moments against
    fourth-order finite differences of the map along x, y and both diagonals (1 %); the
    lay is the x axis and the slope across it 4 times that along, within the sampling
    scatter of a map five correlation lengths long in x (5 deg, 15 %: over seeds 0-11 the
    angle scatters up to 2.6 deg, the ratio 3.5-4.4)."""
    z = anisotropic_map()
    surface = map_statistics(z, 1.0, 1.0)
    theta = np.radians([0.0, 90.0, 45.0, 135.0])
    got = friction.slope_along(surface, theta)
    want = [rms_difference(z, 0, 1), rms_difference(z, 1, 0), rms_difference(z, 1, 1), rms_difference(z, 1, -1)]
    np.testing.assert_allclose(got, want, rtol=0.01)
    principal = friction.lay(*(float(surface[m]) for m in ("m20", "m11", "m02")))
    off = min(principal["lay"], math.pi - principal["lay"])
    assert off < math.radians(5.0)
    assert principal["sigma_slope_across_lay"] / principal["sigma_slope_along_lay"] == pytest.approx(4.0, rel=0.15)


def test_isotropic_surfaces_give_a_flat_sweep_equal_to_todays_value():
    """An isotropic profile: mu_interlocking along every direction is today's value, bit for
    bit, and an attribute says so; isotropic moments (m20 = m02, m11 = 0): today's
    direction average to 1e-15."""
    section = {"junction_shear_strength": 150.0, "direction": {"start": -90.0, "stop": 270.0, "count": 25}}
    profile = surface_stage.surface_from_statistics(STEEL, UNITS)
    today = friction.friction_dataset(gw_interface(), profile, friction_of({"junction_shear_strength": 150.0}),
                                      None)
    ds = friction.friction_dataset(gw_interface(), profile, friction_of(section), None)
    assert np.all(ds["mu_interlocking"].values == float(today["mu_interlocking"]))
    assert float(today["mu_interlocking"]) == pytest.approx(0.16 * math.sqrt(2 / math.pi), rel=1e-15)
    np.testing.assert_array_equal(ds["mu"].values, np.repeat(today["mu"].values[:, None], 25, axis=1))
    np.testing.assert_array_equal(ds["sigma_slope_along"].values, np.full(25, 0.16))
    assert ds.attrs["direction_dependence"].startswith("none: the surface is isotropic")
    assert "lay_direction" not in ds.attrs
    round_moments = moments(0.0225, 0.0, 0.0225)
    sweep = friction.interlocking(round_moments, "rms_slope", np.radians(np.arange(0.0, 360.0, 7.5)))[0]
    np.testing.assert_allclose(sweep, friction.interlocking(round_moments, "rms_slope")[0], rtol=1e-15)


def test_no_direction_is_todays_dataset():
    """Absent and null are the same dataset (xarray identical), with no direction dim and
    the direction average sqrt((m20 + m02)/2) as the slope."""
    surface = moments(0.04, 0.003, 0.01)
    base = {"junction_shear_strength": 150.0, "interlocking": "rms_slope",
            "measured": [{"label": "a test", "value": 0.3, "nominal_pressure": 1.0}]}
    absent = friction.friction_dataset(gw_interface(), surface, friction_of(base), None)
    null = friction.friction_dataset(gw_interface(), surface, friction_of({**base, "direction": None}), None)
    xr.testing.assert_identical(absent, null)
    assert "direction" not in absent.dims and "sigma_slope_along" not in absent
    assert "lay" not in absent.attrs and "direction_dependence" not in absent.attrs
    assert float(absent["mu_interlocking"]) == math.sqrt(0.025)
    assert friction_of(base).direction is None


def test_direction_keys_parse_in_radians_and_bad_sweeps_name_the_key():
    """A number: one direction; a sweep: count directions start..stop, both included
    (degrees in the scene, rad in the library); a bad sweep is a one-line error naming
    friction.direction (the schema rejects a count below 1 already)."""
    one = friction_of({"direction": 30.0})
    assert one.direction == (math.radians(30.0),)
    sweep = friction_of({"direction": {"start": 0.0, "stop": 90.0, "count": 4}})
    np.testing.assert_allclose(sweep.direction, np.radians([0.0, 30.0, 60.0, 90.0]), rtol=1e-15)
    assert len(friction_of({"direction": {"start": 10, "stop": 10, "count": 1}}).direction) == 1
    with pytest.raises(Exception, match="count"):
        filled("friction", {"direction": {"start": 0.0, "stop": 90.0, "count": 0}})
    units = Units.from_section(UNITS)
    for bad, what in (({"start": 0.0, "stop": 90.0, "count": 0}, "count"),
                      ({"start": float("nan"), "stop": 90.0, "count": 3}, "finite"),
                      ({"start": 0.0, "stop": float("inf"), "count": 3}, "finite"),
                      ({"start": 5.0, "stop": 5.0, "count": 3}, "stop != start"),
                      (float("nan"), "finite")):
        with pytest.raises(SceneError, match=what) as err:
            Friction.from_section({"interlocking": "rms_slope", "direction": bad}, units)
        assert str(err.value).startswith("friction.direction: ") and "\n" not in str(err.value)


def test_a_sweep_in_the_dataset_the_file_and_the_figure(tmp_path):
    """On a map: mu (separation x direction) = mu_shear + mu_interlocking(theta) exactly,
    mean absolute slope sqrt(2/pi) sqrt(m(theta)), units and long_name everywhere, the
    direction in rad through netCDF, and a third figure panel with nothing outside."""
    from tests.test_figures_content import outside_texts

    surface = map_statistics(1e-6 * anisotropic_map(n=64, lx=16.0, ly=4.0), 1e-6, 1e-6)  # sigma 1 um
    cfg = {"junction_shear_strength": 150.0,
           "measured": [{"label": "a test", "value": 0.3, "nominal_pressure": 1.0}],
           "direction": {"start": 0.0, "stop": 180.0, "count": 19}}
    ds = friction.friction_dataset(gw_interface(), surface, friction_of(cfg), None)
    theta = np.radians(np.linspace(0.0, 180.0, 19))
    assert ds["mu"].dims == ("separation", "direction") and ds["mu_at_measurement"].dims == ("measurement",
                                                                                               "direction")
    np.testing.assert_allclose(ds["direction"].values, theta, rtol=1e-15)
    assert ds["direction"].attrs["units"] == "rad"
    np.testing.assert_allclose(ds["mu_interlocking"].values,
                               math.sqrt(2 / math.pi) * friction.slope_along(surface, theta), rtol=1e-15)
    np.testing.assert_array_equal(ds["mu"].values, ds["mu_shear"].values[:, None] + ds["mu_interlocking"].values)
    assert ds["mu_interlocking"].values[0] == pytest.approx(math.sqrt(2 / math.pi * float(surface["m20"])),
                                                            rel=1e-14)
    assert ds["mu_interlocking"].values[9] == pytest.approx(math.sqrt(2 / math.pi * float(surface["m02"])),
                                                            rel=1e-14)
    assert np.ptp(ds["mu_interlocking"].values) > 0.1 * ds["mu_interlocking"].values.max()
    assert missing_attributes(ds) == []
    back = read_dataset(write_dataset(ds, tmp_path / "friction.nc", scene="t", title="friction", config=cfg))
    np.testing.assert_array_equal(back["mu"].values, ds["mu"].values)
    assert back.attrs["lay_direction"] == ds.attrs["lay_direction"]
    fig = friction_figure(back, pressure_unit="MPa", length_unit="um")
    assert len(fig.axes) == 3 and fig.axes[2].get_xlabel().startswith("sliding direction")
    assert outside_texts(fig) == []
    single = friction.friction_dataset(gw_interface(), surface, friction_of({**cfg, "direction": 90.0}), None)
    assert single.sizes["direction"] == 1 and len(friction_figure(single).axes) == 2


def test_a_given_interlocking_is_flat_and_an_impossible_covariance_is_an_error():
    """A number or none: mu_interlocking the same in every direction (the slope still
    reported where known); moments with a negative eigenvalue (least squares of noisy
    profiles) are an error naming friction.direction when the slope is needed."""
    surface = moments(0.04, 0.003, 0.01)
    cfg = {"junction_shear_strength": 150.0, "interlocking": 0.1,
           "direction": {"start": 0, "stop": 90, "count": 4}}
    ds = friction.friction_dataset(gw_interface(), surface, friction_of(cfg), None)
    np.testing.assert_array_equal(ds["mu_interlocking"].values, np.full(4, 0.1))
    assert ds.attrs["direction_dependence"] == "none: interlocking given in the scene"
    np.testing.assert_allclose(ds["sigma_slope_along"].values[[0, 3]], np.sqrt([0.04, 0.01]), rtol=1e-15)
    bad = moments(0.01, 0.02, 0.01)
    with pytest.raises(ValueError, match="not positive semi-definite.*friction.direction"):
        friction.friction_dataset(gw_interface(), bad, friction_of({**cfg, "interlocking": "rms_slope"}), None)
    given = friction.friction_dataset(gw_interface(), bad, friction_of(cfg), None)
    assert np.isnan(given["sigma_slope_along"].values).all() and given.attrs["lay"].startswith("unknown")
