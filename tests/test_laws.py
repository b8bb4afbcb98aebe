"""Analytic interface laws (report section 10): exact recovery, calibrated
uncertainties, the Greenwood-Williamson interface, the dataset."""

import math

import numpy as np
import pytest

from asperity import laws
from asperity.references import greenwood_williamson
from asperity.io.netcdf import missing_attributes, read_dataset, write_dataset
from asperity.scene import Laws, Units
from tests.scene_defaults import filled


def laws_of(section: dict, units: dict) -> Laws:
    """A scene's laws section (with the schema's defaults) as the stage reads it."""
    return Laws.from_section(filled("laws", section), Units.from_section(filled("units", units)))

UM = 1e-6
A = np.linspace(0.5, 6.0, 40) * UM  # approaches of the fits below
STEEL_OM = dict(c=15.2e4, g=0.2 * UM, m=2.25)  # 15.2 N/cm^2 (report, Fig. 10.1), g shifted
R, SIGMA_P, N = 0.1414e-3, 7.07106e-7, 300e6  # the GW surface of report 7.1
E, NU = 321.7335 * 9.80665e6, 0.3


def _rel(fit, truth, span):
    """Relative errors of the fitted parameters (g against the span of the approaches)."""
    return {k: abs(fit.values[k] - v) / (span if k == "g" else abs(v)) for k, v in truth.items()}


@pytest.mark.parametrize("residual", ["absolute", "log"])
def test_exact_data_recovered_to_1e_8(residual):
    span = float(A.max() - A.min())
    p = laws.oden_martins(A, **STEEL_OM)
    free = laws.fit_oden_martins(A, p, residual=residual)
    assert max(_rel(free, STEEL_OM, span).values()) < 1e-8, free.values
    fixed = laws.fit_oden_martins(A, p, gap=STEEL_OM["g"], residual=residual)
    assert max(_rel(fixed, STEEL_OM, span).values()) < 1e-8, fixed.values
    assert fixed.stderr["g"] == 0.0 and fixed.fixed == ("g",)
    truth = dict(c=1.0e5, decay_length=1.3 * UM)
    expo = laws.fit_exponential(A, laws.exponential(A, **truth), residual=residual)
    assert max(_rel(expo, truth, span).values()) < 1e-8, expo.values
    # a smooth-surface fit (report 10.2: g = 0.0025 um, c = 3.17e9 N/cm^2, m = 5.17)
    smooth = dict(c=3.17e13, g=0.0025 * UM, m=5.17)
    a = np.linspace(0.004, 0.03, 30) * UM
    fit = laws.fit_oden_martins(a, laws.oden_martins(a, **smooth), residual=residual)
    assert max(_rel(fit, smooth, float(a.max() - a.min())).values()) < 1e-8, fit.values


@pytest.mark.parametrize("residual", ["absolute", "log"])
def test_noisy_fits_scatter_as_their_standard_errors_say(residual):
    """200 noisy replicates: the scatter of each estimate matches the mean reported
    standard error within 20 % (the sampling error of a standard deviation from 200
    replicates is 5 %), and about 95 % of the estimates lie within 2 standard errors."""
    rng = np.random.default_rng(3)
    p0 = laws.oden_martins(A, **STEEL_OM)
    est = {k: [] for k in STEEL_OM}
    se = {k: [] for k in STEEL_OM}
    for _ in range(200):  # replicates: one small fit each
        noise = rng.standard_normal(A.size)
        p = p0 + 0.01 * p0.max() * noise if residual == "absolute" else p0 * np.exp(0.02 * noise)
        fit = laws.fit_oden_martins(A, p, residual=residual)
        for k in STEEL_OM:
            est[k].append(fit.values[k])
            se[k].append(fit.stderr[k])
    for k, true in STEEL_OM.items():
        e, s = np.array(est[k]), np.array(se[k])
        assert 0.8 < e.std(ddof=1) / s.mean() < 1.2, (k, e.std(ddof=1), s.mean())
        covered = np.mean(np.abs(e - true) < 2 * s)
        assert 0.88 < covered <= 1.0, (k, covered)


@pytest.mark.parametrize("residual", ["absolute", "log"])
@pytest.mark.parametrize("window, deep", [((-10.0, -4.0), True), ((0.0, 3.0), False), ((-1.0, 1.0), False)])
def test_greenwood_williamson_interface_exponents(window, deep, residual):
    """Oden-Martins on GW-Hertz: the fitted m lies within the range of the local
    exponent (a - g) (dp/da) / p of the closed form over the window (dp/da the GW
    stiffness), and the exponential law's decay length within that of p / (dp/da);
    with every asperity in contact (h < -4 sigma_p) m -> 3/2, the Hertz exponent
    (F_3/2(t) = |t|^1.5 (1 + 3/(8 t^2) + ...)): within 0.03."""
    h = np.linspace(*window, 41) * SIGMA_P
    gw = greenwood_williamson.gw_interface(h, R, SIGMA_P, N, E, NU)
    a, p, k = -h, gw["nominal_pressure"].values, gw["normal_stiffness"].values
    om = laws.fit_oden_martins(a, p, residual=residual)
    m_local = (a - om.values["g"]) * k / p
    assert m_local.min() <= om.values["m"] <= m_local.max(), (om.values, m_local.min(), m_local.max())
    if deep:
        assert abs(om.values["m"] - 1.5) < 0.03
    else:
        assert om.values["m"] > 2.5  # the Gaussian tail: steeper than any single asperity
    ex = laws.fit_exponential(a, p, residual=residual)
    lam_local = p / k
    assert lam_local.min() <= ex.values["decay_length"] <= lam_local.max()


def _gw_dataset():
    h = np.linspace(0.0, 3.0, 31) * SIGMA_P
    return greenwood_williamson.gw_interface(h, R, SIGMA_P, N, E, NU)


def test_laws_dataset_window_report_values_and_contract(tmp_path):
    gw = _gw_dataset()
    p = gw["nominal_pressure"].values
    units = {"length": "um", "pressure": "MPa"}
    lo, hi = float(np.sort(p)[5]) / 1e6, float(np.sort(p)[25]) / 1e6
    cfg = {"residual": "log", "pressure_range": [lo, hi],
           "report": {"units": {"length": "um", "pressure": "N/cm^2"}, "source": "10, Fig. 10.1",
                      "oden_martins": {"c": 15.2, "g": 0.0, "m": 2.25}}}
    ds = laws.laws_dataset(gw, laws_of(cfg, units))
    window = ds["in_window"].values
    assert window.sum() == 21
    # report values in SI: 15.2 N/cm^2 = 1.52e5 Pa
    rep = ds["report_value"].sel(law="oden_martins")
    assert float(rep.sel(parameter="c")) == pytest.approx(1.52e5, rel=1e-15)
    assert float(rep.sel(parameter="m")) == 2.25 and float(rep.sel(parameter="g")) == 0.0
    assert "15.2 N/cm^2" in ds.attrs["report_as_printed"]
    # the approach origin defaults to the largest separation
    np.testing.assert_allclose(ds["approach"].values, gw["separation"].values.max() - gw["separation"].values)
    # the same fit as the function's, on the window
    direct = laws.fit_oden_martins(ds["approach"].values[window], p[window], residual="log")
    est = ds["estimate"].sel(law="oden_martins")
    for name in ("c", "g", "m"):
        assert float(est.sel(parameter=name)) == pytest.approx(direct.values[name], rel=1e-12)
    assert np.isnan(float(est.sel(parameter="decay_length")))
    np.testing.assert_allclose(ds["residual"].sel(law="oden_martins").values[window], direct.residuals, rtol=1e-12)
    assert np.all(np.isnan(ds["residual"].values[:, ~window]))
    assert np.all(ds["r_squared"].values > 0.99)
    assert missing_attributes(ds) == []
    back = read_dataset(write_dataset(ds, tmp_path / "laws.nc", scene="t", title="laws", config=cfg))
    assert list(back["parameter_units"].values) == ["Pa", "m", "1", "m"]
    assert back["in_window"].dtype == bool


def test_fixed_gap_origin_by_pressure_and_clear_errors():
    gw = _gw_dataset()
    p = gw["nominal_pressure"].values
    units = {"length": "um", "pressure": "MPa"}
    q = float(p[20]) / 1e6
    ds = laws.laws_dataset(gw, laws_of({"approach_origin": {"pressure": q}, "laws": ["oden_martins"],
                                        "oden_martins": {"gap": -5.0}}, units))
    assert float(ds["approach"][20]) == pytest.approx(0.0, abs=1e-12 * SIGMA_P)
    assert float(ds["estimate"].sel(law="oden_martins", parameter="g")) == pytest.approx(-5e-6)
    assert bool(ds["fixed"].sel(law="oden_martins", parameter="g"))
    with pytest.raises(ValueError, match="not below every approach"):
        laws.laws_dataset(gw, laws_of({"oden_martins": {"gap": 1.0}}, units))
    with pytest.raises(ValueError, match="widen the fit window"):
        laws.laws_dataset(gw, laws_of({"pressure_range": [q, q * 1.0001]}, units))
    with pytest.raises(ValueError, match="outside the computed pressures"):
        laws.laws_dataset(gw, laws_of({"approach_origin": {"pressure": 1e9}}, units))
    with pytest.raises(ValueError, match="unknown law"):
        laws.fit_law("logarithmic", np.arange(5.0), np.arange(1.0, 6.0))
