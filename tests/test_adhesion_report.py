"""The adhesion report's share of summits outside the curvature samples
(asperity.studies.adhesion_report.outside_samples), against sums of Nayak's density."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from scipy import integrate

from asperity import peaks
from asperity.studies.adhesion_report import outside_samples

STATS = {"sigma": 1.3e-8, "sigma_slope": 2.0e-3, "sigma_curvature": 1.5e4}


def _surface() -> xr.Dataset:
    return xr.Dataset({k: ((), v) for k, v in STATS.items()})


def test_shares_outside_a_single_curvature_add_to_one():
    """Samples of one curvature leave every summit flatter or steeper (1e-3 for the sum's grid)."""
    k = np.array([1.2 * STATS["sigma_curvature"]])
    out = outside_samples(_surface(), k)
    for n in (1, 2):
        assert out[f"flatter_above_{n}_sigma"] + out[f"steeper_above_{n}_sigma"] == pytest.approx(1.0, abs=1e-3)


def test_shares_against_the_density_integrated_by_quadrature():
    """Above 1 sigma, the share flatter than 0.5 sigma_curvature and steeper than 3
    sigma_curvature against scipy's dblquad of the same density (1e-3)."""
    density = peaks.JointDensity(**STATS)
    s, sk = STATS["sigma"], STATS["sigma_curvature"]
    lo, hi = 0.5 * sk, 3.0 * sk
    out = outside_samples(_surface(), np.array([lo, hi]), levels=(1,))

    def mass(k0, k1):
        return integrate.dblquad(lambda k, z: density.pdf(z, k), s, 8 * s, k0, k1, epsabs=0, epsrel=1e-8)[0]

    total = mass(0.0, 15 * sk)
    assert out["flatter_above_1_sigma"] == pytest.approx(mass(0.0, lo) / total, abs=1e-3)
    assert out["steeper_above_1_sigma"] == pytest.approx(mass(hi, 15 * sk) / total, abs=1e-3)
    assert 0 < out["flatter_above_1_sigma"] < 1 and 0 < out["steeper_above_1_sigma"] < 1
