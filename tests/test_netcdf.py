"""The netCDF contract: attributes enforced, atomic writes, round trips."""

import numpy as np
import pytest
import xarray as xr

from asperity.io.netcdf import ContractError, read_dataset, scene_config, write_dataset


def _ds():
    return xr.Dataset(
        {"force": ("step", np.arange(3.0), {"units": "N", "long_name": "force"}),
         "elastic": ("step", np.array([True, False, True]), {"units": "1", "long_name": "flag"})},
        coords={"step": ("step", np.arange(3), {"units": "1", "long_name": "step"})},
    )


def test_round_trip_with_config_and_bools(tmp_path):
    path = write_dataset(_ds(), tmp_path / "a.nc", scene="s", title="t", config={"x": np.float64(1.5)})
    ds = read_dataset(path)
    assert ds["elastic"].dtype == bool and ds["elastic"].values.tolist() == [True, False, True]
    assert scene_config(ds) == {"x": 1.5}
    assert ds.attrs["scene"] == "s" and ds.attrs["source"].startswith("asperity")
    assert list(tmp_path.iterdir()) == [path]  # no temporary left behind


def test_missing_attributes_refused_before_writing(tmp_path):
    ds = _ds()
    ds["bare"] = ("step", np.zeros(3))
    with pytest.raises(ContractError, match="bare"):
        write_dataset(ds, tmp_path / "b.nc", scene="s", title="t")
    assert not list(tmp_path.iterdir())


def test_failed_write_leaves_nothing(tmp_path, monkeypatch):
    def boom(self, *args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", boom)
    with pytest.raises(OSError):
        write_dataset(_ds(), tmp_path / "c.nc", scene="s", title="t")
    assert not list(tmp_path.iterdir())
