"""mu_shear against the report's (asperity.studies.friction_report), and the flow stresses
the study puts beside it (asperity.stages.studies.flow_stresses)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from asperity.stages.studies import flow_stresses
from asperity.studies.friction_report import friction_against_report
from tests.scene_defaults import filled


def test_ranges_over_the_valid_separations():
    h = np.array([1.0, 2.0, 3.0])
    p, a = np.array([3e8, 2e8, 0.0]), np.array([0.3, 0.25, 0.0])   # p_r 1000, 800 MPa; nothing at 3
    tau = 160e6
    friction = xr.Dataset({"mu_shear": ("separation", tau * np.where(p > 0, a / np.where(p > 0, p, 1), np.nan)),
                           "valid": ("separation", [True, True, False]),
                           "junction_shear_strength": tau, "report_mu_shear": 0.3},
                          coords={"separation": h})
    interface = xr.Dataset({"nominal_pressure": ("separation", p), "contact_area_ratio": ("separation", a)},
                           coords={"separation": h})
    ds = friction_against_report({"s": (friction, interface, (200e6, 300e6))}).sel(scene="s")
    assert int(ds["valid_separations"]) == 2
    assert float(ds["mu_shear_low"]) == pytest.approx(0.16) and float(ds["mu_shear_high"]) == pytest.approx(0.2)
    assert float(ds["real_pressure_low"]) == pytest.approx(8e8) and float(ds["real_pressure_high"]) == pytest.approx(1e9)
    assert float(ds["report_real_pressure"]) == pytest.approx(tau / 0.3)
    assert float(ds["mu_at_saturated_flow_high"]) == pytest.approx(300e6 / math.sqrt(3) / 8e8)
    assert float(ds["mu_at_initial_flow_low"]) == pytest.approx(200e6 / math.sqrt(3) / 1e9)
    for name in ds.variables:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name


def test_flow_stresses_of_each_body():
    """J2: its yield stress; Bodner-Partom (SAE 1020, 8.2.1): the saturated hardness flows
    higher than the initial one; elastic: none."""
    units = filled("units", {"length": "um", "pressure": "MPa"})
    j2 = filled("material", {"youngs_modulus": 70000.0, "poisson": 0.33, "model": "j2", "yield_stress": 280.0})
    assert flow_stresses(j2, units) == (280e6, 280e6)
    bp = filled("material", {"youngs_modulus": 209000.0, "poisson": 0.3, "model": "bodner_partom",
                             "bodner_partom": {"preset": "sae_1020"}})
    y0, ys = flow_stresses(bp, units)
    assert 0 < y0 < ys
    elastic = filled("material", {"youngs_modulus": 70000.0, "poisson": 0.33})
    assert all(math.isnan(v) for v in flow_stresses(elastic, units))
