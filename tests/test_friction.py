"""Static friction of the interface (report 9.1): closed forms and the dataset."""

import math

import numpy as np
import pytest
import xarray as xr
from scipy import integrate

from asperity import friction
from asperity.stages import surface as surface_stage
from asperity.references import greenwood_williamson
from asperity.references.hertz import plane_strain_modulus
from asperity.io.netcdf import missing_attributes, read_dataset, write_dataset
from asperity.scene import Friction, Material, Units
from tests.scene_defaults import filled

UNITS = {"length": "um", "pressure": "MPa"}


def friction_of(section: dict) -> Friction:
    """A scene's friction section (in UNITS, with the schema's defaults) as the stage reads it."""
    return Friction.from_section(filled("friction", section), Units.from_section(UNITS))

# the Greenwood-Williamson surface of report 7.1, SI
R, SIGMA_P, N = 0.1414e-3, 7.07106e-7, 300e6
E, NU = 321.7335 * 9.80665e6, 0.3
STEEL = filled("surface", {"statistics": {
    "sigma": 4.91, "sigma_slope": 0.16, "sigma_curvature": 0.0227,
    "peak_density": 0.000508}})


def _gw_integral_by_quadrature(m, t):
    """F_m(t) = int_t^inf (s - t)^m phi(s) ds by adaptive quadrature (independent of pbdv)."""
    f = lambda s: (s - t) ** m * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi)  # noqa: E731
    val, _ = integrate.quad(f, t, np.inf, epsabs=0.0, epsrel=1e-13, limit=200)
    return val


def _gw_interface(h):
    return greenwood_williamson.gw_interface(h, R, SIGMA_P, N, E, NU)


def _gw_surface():
    return surface_stage.surface_from_statistics(
        {"gaussian_heights": {"sigma_peak_height": SIGMA_P, "radius": R, "peak_density": N}}, {"length": "m"})


def test_mu_shear_against_greenwood_williamson_closed_form():
    """tau_s A/F for GW-Hertz: (3 pi / 4) sqrt(R / sigma_p) F_1(t) / (E* F_3/2(t)), to 1e-6.

    The closed form's F_m by adaptive quadrature, independently of the
    parabolic-cylinder evaluation of asperity.references.greenwood_williamson.
    """
    h = np.linspace(-1.0, 4.0, 11) * SIGMA_P
    tau = 150.0  # MPa
    ds = friction.friction_dataset(_gw_interface(h), _gw_surface(),
                                   friction_of({"junction_shear_strength": tau, "interlocking": "none"}), None)
    estar = float(plane_strain_modulus(E, NU))
    t = h / SIGMA_P
    closed = np.array([0.75 * math.pi * math.sqrt(R / SIGMA_P) * _gw_integral_by_quadrature(1.0, x)
                       / (estar * _gw_integral_by_quadrature(1.5, x)) for x in t]) * tau * 1e6
    np.testing.assert_allclose(ds["mu_shear"].values, closed, rtol=1e-6)
    np.testing.assert_array_equal(ds["mu"].values, ds["mu_shear"].values)  # interlocking none
    assert float(ds["mu_interlocking"]) == 0.0
    # mu_shear grows with the separation (lighter loads: fewer, younger contacts carry
    # relatively more area, A/F ~ sqrt(t) for GW)
    assert np.all(np.diff(ds["mu_shear"].values) > 0)


def test_interlocking_of_a_gaussian_surface():
    """E|z'| = sqrt(2/pi) sigma_slope: exact for the scene statistics, and against
    2e6 Gaussian slopes within 4 standard errors of their sample mean."""
    surface = surface_stage.surface_from_statistics(STEEL, UNITS)
    choice = lambda c: friction.interlocking(surface, c)[0]  # noqa: E731
    assert choice("mean_absolute_slope") == pytest.approx(0.16 * math.sqrt(2 / math.pi), rel=1e-15)
    assert choice("rms_slope") == pytest.approx(0.16, rel=1e-15)  # the report's 0.16 (9.1)
    assert choice("none") == 0.0 and choice(0.2) == 0.2
    with pytest.raises(ValueError, match="interlocking"):
        choice("steepest")
    slopes = np.random.default_rng(7).normal(0.0, 0.16, 2_000_000)
    se = 0.16 * math.sqrt(1 - 2 / math.pi) / math.sqrt(slopes.size)
    assert abs(np.abs(slopes).mean() - float(friction.mean_absolute_slope(0.16))) < 4 * se


def test_slope_of_a_map_is_the_direction_average():
    ds = xr.Dataset({"m20": ((), 0.04), "m02": ((), 0.01), "m11": ((), 0.003)})
    assert friction.slope_deviation(ds) == pytest.approx(math.sqrt(0.025), rel=1e-15)
    with pytest.raises(ValueError, match="no slope statistic"):
        friction.interlocking(_gw_surface(), "mean_absolute_slope")


def test_junction_shear_strength_from_the_material_or_the_scene():
    y = 289.58e6  # 42 ksi, report 8.1.1
    yielding = Material(model="elastic", youngs_modulus=2e11, poisson=0.3, yield_stress=y)
    tau, how = friction.junction_shear_strength(friction_of({}), yielding)
    assert tau == pytest.approx(y / math.sqrt(3), rel=1e-15) and "sqrt(3)" in how
    tau, how = friction.junction_shear_strength(friction_of({"junction_shear_strength": 100.0}), yielding)
    assert tau == pytest.approx(100e6, rel=1e-15) and how == "given in the scene"
    with pytest.raises(ValueError, match="junction_shear_strength"):
        friction.junction_shear_strength(friction_of({}), Material(model="elastic", youngs_modulus=2e11,
                                                                   poisson=0.3))


def test_measured_values_pressure_lookup_and_report_side_by_side(tmp_path):
    """mu at the test's pressure by interpolation in log p: exact at a computed point,
    NaN outside the computed pressures; the report's estimates are carried as given."""
    h = np.linspace(0.0, 3.0, 31) * SIGMA_P
    gw = _gw_interface(h)
    p5 = float(gw["nominal_pressure"][5]) / 1e6  # MPa
    cfg = {"junction_shear_strength": 150.0, "interlocking": "rms_slope",
           "measured": [{"label": "at a grid point", "value": 0.2, "nominal_pressure": p5, "uncertainty": 0.01},
                        {"label": "beyond", "value": 0.3, "nominal_pressure": 1e9},
                        {"label": "no pressure", "value": 0.25}],
           "report": {"shear": 0.093, "interlocking": 0.16, "total": 0.253, "nominal_pressure": 2.1947,
                      "source": "9.1, Fig. 9.3"}}
    surface = surface_stage.surface_from_statistics(STEEL, UNITS)
    ds = friction.friction_dataset(gw, surface, friction_of(cfg), None)
    at = ds["mu_at_measurement"].values
    assert at[0] == pytest.approx(float(ds["mu"][5]), rel=1e-12)
    assert np.isnan(at[1]) and np.isnan(at[2])
    assert float(ds["mu_interlocking"]) == pytest.approx(0.16, rel=1e-15)
    assert float(ds["report_mu"]) == 0.253 and float(ds["report_nominal_pressure"]) == pytest.approx(2.1947e6)
    np.testing.assert_allclose(ds["measured_mu"].values, [0.2, 0.3, 0.25])
    assert missing_attributes(ds) == []
    path = write_dataset(ds, tmp_path / "friction.nc", scene="t", title="friction", config=cfg)
    back = read_dataset(path)
    np.testing.assert_allclose(back["mu"].values, ds["mu"].values, rtol=0, atol=0)
    assert back["nominal_pressure"].attrs["units"] == "Pa"


def test_no_load_and_adhesive_tension_give_nan_and_loading_branch_is_used():
    p = np.array([-2.0e5, 0.0, 1.0e6, 4.0e6])
    area = np.array([1e-4, 0.0, 2e-3, 5e-3])
    mu = friction.mu_shear(area, p, 1.0e8)
    assert np.isnan(mu[0]) and np.isnan(mu[1])
    np.testing.assert_allclose(mu[2:], 1e8 * area[2:] / p[2:], rtol=1e-15)
    sep = xr.DataArray(np.arange(4.0) * 1e-6, dims="separation", attrs={"units": "m", "long_name": "s"})
    two = xr.Dataset(
        {"nominal_pressure": (("branch", "separation"), np.stack([p, 0.5 * p])),
         "contact_area_ratio": (("branch", "separation"), np.stack([area, area]))},
        coords={"separation": sep, "branch": ["loading", "unloading"]})
    ds = friction.friction_dataset(two, surface_stage.surface_from_statistics(STEEL, UNITS),
                                   friction_of({"junction_shear_strength": 100.0}), None)
    np.testing.assert_allclose(ds["mu_shear"].values[2:], mu[2:], rtol=1e-15)
