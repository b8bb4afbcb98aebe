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


def test_show_unknown_variable_names_the_file(folder, capsys):
    assert main(["show", str(folder / "interface.nc"), "--var", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"asperity: error: {folder / 'interface.nc'}: nope: no such variable"), err


# --------------------------------------------------------------------------
# asperity new-scene FILE [NAME]
# --------------------------------------------------------------------------

DATA = __import__("pathlib").Path(__file__).resolve().parents[1] / "data" / "topographies"


def validated(path):
    """The scene through the workflow's own schema, defaults filled in (as Snakemake does)."""
    import yaml
    from snakemake.utils import validate

    scene = yaml.safe_load(path.read_text())
    config = {"scenes": [path.stem], "accuracy": "draft", "results": "results", "scene_dir": str(path.parent),
              "scene_definitions": {path.stem: scene}}
    validate(config, str(DATA.parents[1] / "config" / "schema.yaml"))
    return scene


def test_new_scene_for_a_map(tmp_path, capsys):
    assert main(["new-scene", str(DATA / "di-3.di"), "--scene-dir", str(tmp_path), "--material", "steel"]) == 0
    out = capsys.readouterr().out
    assert f"wrote {tmp_path / 'di_3.yaml'}" in out
    assert ("snakemake --cores 2 results/di_3/interface.nc results/di_3/figures/interface.png "
            f"--config scene_dir={tmp_path.resolve()}") in out
    text = (tmp_path / "di_3.yaml").read_text()
    assert "steel: SAE 1020" in text.split("material:")[1].splitlines()[0]  # the material and its source
    scene = validated(tmp_path / "di_3.yaml")
    # inside the workflow folder: relative to it (unit, spacing from the file)
    assert scene["surface"]["map"] == {"file": "data/topographies/di-3.di"}
    assert scene["surface"]["form"] == "tilt"
    assert scene["population"]["density"] == "sampled"
    assert scene["homogenization"]["rule"] == "peaks"
    assert scene["asperity"]["model"] == "hertz"
    assert scene["material"] == {"youngs_modulus": 209000, "poisson": 0.3, "yield_stress": 350,
                                 "model": "elastic"}  # the schema's default model
    assert "nm" in text  # says which unit the file's numbers are in


def test_new_scene_for_a_profile_and_a_unitless_file(tmp_path, capsys):
    steel = ["--scene-dir", str(tmp_path), "--material", "steel"]
    assert main(["new-scene", str(DATA / "hfm-1.hfm"), "stylus", *steel]) == 0
    scene = validated(tmp_path / "stylus.yaml")
    assert scene["population"]["density"] == "nayak" and scene["homogenization"]["rule"] == "gauss"
    capsys.readouterr()
    assert main(["new-scene", str(DATA / "xy-4.txt"), *steel]) == 2
    assert capsys.readouterr().err == (f"asperity: error: {DATA / 'xy-4.txt'}: the file states no length "
                                       f"unit (give the unit of its numbers with --unit: m, cm, mm, um, nm)\n")
    assert not (tmp_path / "xy_4.yaml").exists()
    assert main(["new-scene", str(DATA / "xy-4.txt"), "--unit", "mm", *steel]) == 0
    assert validated(tmp_path / "xy_4.yaml")["surface"]["profile"]["unit"] == "mm"
    capsys.readouterr()
    assert main(["new-scene", str(DATA / "hfm-1.hfm"), "stylus", *steel]) == 2
    assert "exists (choose another NAME or pass --force)" in capsys.readouterr().err
    assert main(["new-scene", str(tmp_path / "missing.plu"), *steel]) == 2
    assert capsys.readouterr().err == f"asperity: error: {tmp_path / 'missing.plu'}: no such file\n"


def test_show_flags_files_written_by_another_version_of_their_stage(tmp_path, capsys):
    """A file records the code version of its stage (asperity.versions); `show` flags one
    written by another version, or by a version of asperity that recorded none, with
    '!', and leaves the current ones alone. Figures carry the version in their PNG text."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from asperity import versions
    from asperity.io.figures import figure_version, save_figure

    ds = xr.Dataset({"x": ("i", np.arange(2.0), {"units": "1", "long_name": "x"})},
                    coords={"i": ("i", np.arange(2), {"units": "1", "long_name": "i"})})
    current = versions.code_version("interface")
    older = f"friction {versions.VERSIONS['friction'] - 1}"
    write_dataset(ds, tmp_path / "interface.nc", scene="s", title="t", version=current)
    write_dataset(ds, tmp_path / "friction.nc", scene="s", title="t", version=older)
    write_dataset(ds, tmp_path / "laws.nc", scene="s", title="t")  # no version recorded
    save_figure(plt.figure(), tmp_path / "figures" / "laws.png", version="laws_figure 0")
    save_figure(plt.figure(), tmp_path / "figures" / "interface.png",
                version=versions.code_version("interface_figure"))
    assert figure_version(tmp_path / "figures" / "laws.png") == "laws_figure 0"
    assert main(["show", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    flagged = [line for line in out.splitlines() if line.lstrip().startswith("!")]
    assert len(flagged) == 3, out
    expected = versions.VERSIONS["friction"]
    assert any(f"written by friction version {expected - 1}; this code computes version {expected}"
               in line for line in flagged)
    assert any("before asperity recorded the version" in line for line in flagged)
    assert any("laws.png" in line and "laws_figure version 0" in line for line in flagged)
    assert not any("interface" in line for line in flagged)
