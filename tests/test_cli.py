"""The `asperity show` command lists result files and prints variables."""

import numpy as np
import pytest
import xarray as xr

from asperity.cli import main
from asperity.io.netcdf import write_dataset


@pytest.fixture
def folder(tmp_path):
    ds = xr.Dataset(
        {"nominal_pressure": ("separation", np.array([3.0, 2.0, 1.0]),
                              {"units": "Pa", "long_name": "nominal contact pressure"})},
        coords={"separation": ("separation", np.array([0.0, 1e-6, 2e-6]),
                               {"units": "m", "long_name": "separation"})},
    )
    ds.attrs.update(fe_jobs=5, fe_cpu_time=12.5, accuracy="draft")
    write_dataset(ds, tmp_path / "interface.nc", scene="s", title="homogenized interface")
    return tmp_path


def test_show_folder_lists_variables_with_headline_numbers(folder, capsys):
    assert main(["show", str(folder)]) == 0
    out = capsys.readouterr().out
    assert "interface.nc  [separation=3]  homogenized interface" in out
    assert "nominal_pressure" in out and "1 .. 3 Pa" in out
    assert "fe_jobs = 5, fe_cpu_time = 12.5" in out  # the numeric attributes: FE cost, errors


def test_show_var_prints_a_table(folder, capsys):
    assert main(["show", str(folder / "interface.nc"), "--var", "nominal_pressure"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == "# nominal_pressure [Pa]: nominal contact pressure"
    assert "0.000002" in out.replace("2e-06", "0.000002") and "1.0" in out


def test_show_unknown_variable_names_the_file(folder):
    with pytest.raises(SystemExit, match="no variable 'nope'"):
        main(["show", str(folder / "interface.nc"), "--var", "nope"])
