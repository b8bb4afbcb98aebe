"""Where each scene holds, in one table (asperity.studies.validity_summary)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from asperity.studies.validity_summary import validity_summary


def _interface(valid, why, indicator, branch=False, hardness=None):
    h = 1e-6 * np.arange(1.0, len(valid) + 1)
    ds = xr.Dataset({"valid": ("separation", np.asarray(valid)), "validity": ("separation", np.array(why, dtype=object)),
                     "yielded_fraction": ("separation", np.asarray(indicator, float)),
                     "nominal_pressure": ("separation", np.linspace(5.0, 1.0, len(valid))),
                     "extrapolated_load_fraction": ("separation", np.linspace(0.1, 0.4, len(valid)))},
                    coords={"separation": h})
    if hardness is not None:
        ds["hardness"] = hardness
    if branch:  # an adhesive scene: approach first, then retraction (read: the approach)
        ds = xr.concat([ds, ds.assign(valid=~ds["valid"])], dim=xr.DataArray(["approach", "retraction"], dims="branch"))
    return ds


def test_counts_ranges_and_the_limit_that_fails_most():
    surface = xr.Dataset({"sigma_peak_height": 0.5e-6})  # separations 2, 4, 6, 8, 10 sigma
    why = ["yielded_fraction 0.9 > 0.5", "yielded_fraction 0.7 > 0.5", "contact_area_ratio 0.2 > 0.1", "", ""]
    a = _interface([False, False, False, True, True], why, [0.9, 0.7, 0.3, 0.1, 0.0], hardness=1e9)
    b = _interface([True] * 5, [""] * 5, [0.0] * 5, branch=True)
    ds = validity_summary({"a": (a, surface), "b": (b, surface)})
    r = ds.sel(scene="a")
    assert int(r["valid_separations"]) == 2 and int(r["separations"]) == 5
    assert float(r["valid_from"]) == pytest.approx(8.0) and float(r["valid_to"]) == pytest.approx(10.0)
    assert str(r["failing_limit"].values) == "yielded_fraction" and int(r["failing_separations"]) == 2
    assert float(r["failing_low"]) == 0.7 and float(r["failing_high"]) == 0.9
    assert float(r["hardness"]) == 1e9 and np.isnan(float(r["plasticity_index"]))
    assert float(r["extrapolated_load_low"]) == pytest.approx(0.1)
    assert float(r["extrapolated_load_high"]) == pytest.approx(0.4)
    r = ds.sel(scene="b")  # the approach, valid everywhere; the retraction, not, is not read
    assert int(r["valid_separations"]) == 5 and str(r["failing_limit"].values) == ""
    assert np.isnan(float(r["failing_low"])) and np.isnan(float(r["hardness"]))
    for name in ds.variables:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
