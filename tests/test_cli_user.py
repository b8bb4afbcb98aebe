"""`asperity new-scene` a new user can trust, `asperity show`'s caveats and CSV, `--version`.

new-scene: the material from options or by name (no placeholder), the whole file read, the
population and the notes from the heights' skewness and kurtosis (checked against scipy)
and their form, paths relative to the workflow folder or absolute."""

from __future__ import annotations

import csv
import io
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from scipy import stats

import asperity
from asperity.cli import main
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.new_scene import workflow_root
from asperity.scene import Material, Units, check_scene
from tests.scene_defaults import filled_scene

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "topographies"


def scene_of(path: Path) -> dict:
    return yaml.safe_load(path.read_text())


def write_profile(path: Path, z: np.ndarray, dx: float = 0.5) -> Path:
    """A two-column text profile (x, z), numbers in um."""
    x = dx * np.arange(z.size)
    np.savetxt(path, np.column_stack([x, z]), fmt="%.9f")
    return path


def smooth_noise(n: int, seed: int, width: float = 4.0) -> np.ndarray:
    """Gaussian white noise smoothed by a Gaussian kernel: Gaussian heights."""
    rng = np.random.default_rng(seed)
    t = np.arange(-25, 26)
    kernel = np.exp(-0.5 * (t / width) ** 2)
    return np.convolve(rng.standard_normal(n + t.size - 1), kernel / kernel.sum(), mode="valid")


def tilt_residual_moments(z: np.ndarray) -> tuple[float, float]:
    """scipy's skewness and kurtosis of a profile less its least-squares line."""
    x = np.arange(z.size, dtype=float)
    r = z - np.polyval(np.polyfit(x, z, 1), x)
    return float(stats.skew(r)), float(stats.kurtosis(r, fisher=False))


def test_material_options_write_a_scene_asperity_scene_accepts(tmp_path, capsys):
    path = write_profile(tmp_path / "gauss.txt", smooth_noise(20000, 1))
    assert main(["new-scene", str(path), "--unit", "um", "--scene-dir", str(tmp_path), "--youngs-modulus",
                 "123000", "--poisson", "0.25", "--yield-stress", "456", "--hardness", "1300"]) == 0
    target = tmp_path / "gauss.yaml"
    raw = scene_of(target)
    check_scene(raw, target)  # raises on a problem
    scene = filled_scene(raw)  # the workflow's schema, its defaults filled in
    material = Material.from_scene(scene["material"], Units.from_section(scene["units"]))
    assert (material.youngs_modulus, material.poisson, material.yield_stress, material.hardness) == \
        (123000.0 * 1e6, 0.25, 456.0 * 1e6, 1300.0 * 1e6)
    assert "given to asperity new-scene" in target.read_text()
    assert main(["check", str(target)]) == 0


def test_a_named_material_in_another_pressure_unit(tmp_path):
    path = write_profile(tmp_path / "ti.txt", smooth_noise(5000, 2))
    assert main(["new-scene", str(path), "--unit", "um", "--scene-dir", str(tmp_path), "--material",
                 "titanium", "--pressure-unit", "GPa"]) == 0
    scene = filled_scene(scene_of(tmp_path / "ti.yaml"))
    assert scene["units"]["pressure"] == "GPa"
    material = Material.from_scene(scene["material"], Units.from_section(scene["units"]))
    # Ti-6Al-4V of the table, written in GPa and read back in Pa (6 significant digits in the file)
    assert material.youngs_modulus == pytest.approx(114e9, rel=1e-12)
    assert material.yield_stress == pytest.approx(880e6, rel=1e-12)
    assert "Ti-6Al-4V" in (tmp_path / "ti.yaml").read_text()


def test_a_gaussian_profile_gets_nayak_and_a_skewed_one_a_note(tmp_path, capsys):
    gauss = smooth_noise(20000, 3)
    sk, ku = tilt_residual_moments(gauss)
    assert abs(sk) < 0.3 and 2.5 < ku < 4.0  # the limits of asperity.surface.distribution
    assert main(["new-scene", str(write_profile(tmp_path / "g.txt", gauss)), "--unit", "um",
                 "--scene-dir", str(tmp_path), "--material", "steel"]) == 0
    text = (tmp_path / "g.yaml").read_text()
    assert scene_of(tmp_path / "g.yaml")["population"]["density"] == "nayak"
    assert "not Gaussian" not in text
    assert f"skewness {sk:.3g}, kurtosis {ku:.3g}" in text

    skewed = np.random.default_rng(4).exponential(1.0, 20000)  # skewness 2, kurtosis 9
    sk, ku = tilt_residual_moments(skewed)
    capsys.readouterr()
    assert main(["new-scene", str(write_profile(tmp_path / "e.txt", skewed)), "--unit", "um",
                 "--scene-dir", str(tmp_path), "--material", "steel"]) == 0
    out = capsys.readouterr().out
    note = f"the heights are not Gaussian (skewness {sk:.3g} beyond +-0.3; kurtosis {ku:.3g} outside 2.5 ... 4)"
    assert f"note: {note}" in out
    assert f"# NOTE: {note}; the Nayak density assumes Gaussian heights" in (tmp_path / "e.yaml").read_text()


def test_a_non_gaussian_map_gets_its_own_peaks_and_says_why(tmp_path, capsys):
    assert main(["new-scene", str(DATA / "mi-1.mi"), "--scene-dir", str(tmp_path), "--material", "copper"]) == 0
    from asperity.io.topography import read_measurement

    m = read_measurement(DATA / "mi-1.mi", "map")
    z = m.heights
    i, j = np.indices(z.shape)
    plane = np.column_stack([np.ones(z.size), j.ravel(), i.ravel()])
    r = z.ravel() - plane @ np.linalg.lstsq(plane, z.ravel(), rcond=None)[0]
    sk, ku = float(stats.skew(r)), float(stats.kurtosis(r, fisher=False))
    scene = scene_of(tmp_path / "mi_1.yaml")
    assert scene["population"]["density"] == "sampled" and scene["homogenization"]["rule"] == "peaks"
    assert (f"the heights are not Gaussian (skewness {sk:.3g} beyond +-0.3; kurtosis {ku:.3g} outside "
            f"2.5 ... 4): the population is the map's own peaks") in capsys.readouterr().out


def test_a_dominating_form_is_noted_with_a_cut_off(tmp_path, capsys):
    n, dx = 8001, 0.5
    x = dx * np.arange(n)
    z = 50.0 * ((x - x.mean()) / x.max()) ** 2 + 0.1 * smooth_noise(n, 5)  # a curved part, fine roughness
    assert main(["new-scene", str(write_profile(tmp_path / "bow.txt", z, dx)), "--unit", "um",
                 "--scene-dir", str(tmp_path), "--material", "glass"]) == 0
    out = capsys.readouterr().out
    cutoff = (n - 1) * dx / 5  # ISO 4288: five cut-offs in the record
    assert "note: the form dominates: a 2nd-degree polynomial removes 100 % of the variance" in out
    assert f"surface.filter: {{lambda_c: {cutoff:.3g}}}" in out
    assert "# NOTE: the form dominates" in (tmp_path / "bow.yaml").read_text()


def test_paths_are_relative_to_the_workflow_folder_or_absolute(tmp_path, monkeypatch):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    assert workflow_root() == ROOT  # no Snakefile above tmp: the checkout asperity runs from
    outside = write_profile(elsewhere / "mine.txt", smooth_noise(3000, 6))
    assert main(["new-scene", "mine.txt", "--unit", "um", "--scene-dir", "scenes", "--material", "steel"]) == 0
    assert scene_of(elsewhere / "scenes" / "mine.yaml")["surface"]["profile"]["file"] == str(outside.resolve())
    inside = os.path.relpath(DATA / "di-3.di", elsewhere)  # ../../../work/main/data/...: relative to the shell
    assert main(["new-scene", inside, "--scene-dir", "scenes", "--material", "steel"]) == 0
    named = scene_of(elsewhere / "scenes" / "di_3.yaml")["surface"]["map"]["file"]
    assert named == "data/topographies/di-3.di" and (ROOT / named).is_file()


def test_a_latin1_text_export_through_new_scene(tmp_path, capsys):
    """A Windows-1252 export, micro sign as the byte 0xB5: its unit is read from its header."""
    z = smooth_noise(2000, 7)
    body = "\r\n".join(f"{0.0005 * k:.4f};{v:.6f}" for k, v in enumerate(z))
    (tmp_path / "export.txt").write_bytes(
        ("Profil\r\nX unit: mm\r\nZ unit: \u00b5m\r\n" + body + "\r\n").encode("cp1252"))
    assert main(["new-scene", str(tmp_path / "export.txt"), "--scene-dir", str(tmp_path),
                 "--material", "steel"]) == 0
    text = (tmp_path / "export.yaml").read_text()
    assert "its numbers in um" in text and "unit:" not in scene_of(tmp_path / "export.yaml")["surface"]["profile"]


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert capsys.readouterr().out == f"asperity {asperity.__version__}\n"


# --------------------------------------------------------------------------
# asperity show: the caveats of the validity, and CSV
# --------------------------------------------------------------------------

NOT_CHECKED = ("yield: the material has no hardness; plasticity_index: no limit set "
               "(validity.plasticity_index)")


@pytest.fixture
def interface(tmp_path):
    rng = np.random.default_rng(8)
    h = np.sort(rng.uniform(0.0, 3e-6, 7))
    pressure = rng.uniform(1.0, 1e6, (2, 7)) / 3.0  # numbers no short decimal writes exactly
    valid = np.array([[True] * 5 + [False] * 2, [True, False] * 3 + [True]])
    ds = xr.Dataset(
        {"nominal_pressure": (("branch", "separation"), pressure,
                              {"units": "Pa", "long_name": "nominal contact pressure"}),
         "valid": (("branch", "separation"), valid,
                   {"units": "1", "long_name": "every validity limit holds", "not_checked": NOT_CHECKED,
                    "limit_contact_area_ratio": 0.1, "limit_interaction": 0.3}),
         "validity": (("branch", "separation"), np.where(valid, "", "interaction 0.5 > 0.3").astype(object),
                      {"units": "1", "long_name": "the first limit that fails"})},
        coords={"separation": ("separation", h, {"units": "m", "long_name": "separation"}),
                "branch": ("branch", ["loading", "unloading"], {"units": "1", "long_name": "branch"})})
    path = tmp_path / "interface.nc"
    write_dataset(ds, path, scene="s", title="homogenized interface")
    return path


def test_show_prints_what_the_validity_did_not_check(interface, capsys):
    assert main(["show", str(interface)]) == 0
    out = capsys.readouterr().out
    assert "valid (loading): 5 of 7 separations" in out
    assert "limits: contact_area_ratio <= 0.1, interaction <= 0.3" in out
    lines = out.splitlines()
    at = lines.index("  not checked:")
    assert lines[at + 1:at + 3] == ["    - yield: the material has no hardness",
                                    "    - plasticity_index: no limit set (validity.plasticity_index)"]


def test_show_csv_round_trips_the_variable_and_valid_to_full_precision(interface, capsys):
    assert main(["show", str(interface), "--var", "nominal_pressure", "--csv"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    ds = read_dataset(interface)
    assert list(rows[0]) == ["branch [1]", "separation [m]", "nominal_pressure [Pa]", "valid [1]"]
    assert len(rows) == ds["nominal_pressure"].size
    for row in rows:
        one = ds.sel(branch=row["branch [1]"], separation=float(row["separation [m]"]))  # exact: sel fails else
        assert float(row["nominal_pressure [Pa]"]) == float(one["nominal_pressure"])  # bit for bit
        assert int(row["valid [1]"]) == int(one["valid"])
    back = np.array([float(r["nominal_pressure [Pa]"]) for r in rows]).reshape(2, 7)
    np.testing.assert_array_equal(back, ds["nominal_pressure"].transpose("branch", "separation").values)


def test_show_csv_needs_a_variable(interface, capsys):
    assert main(["show", str(interface), "--csv"]) == 2
    assert capsys.readouterr().err == f"asperity: error: {interface}: --csv: give the variable with --var\n"


def test_the_scene_dir_default_is_the_workflow_folders(tmp_path, monkeypatch):
    """Without --scene-dir the scene goes to config/scenes of the workflow folder found from
    the shell's folder, not of the shell's folder."""
    work = tmp_path / "work"
    (work / "sub").mkdir(parents=True)
    (work / "Snakefile").write_text("")
    shutil.copy(DATA / "di-3.di", work / "sub" / "scan.di")
    monkeypatch.chdir(work / "sub")
    assert main(["new-scene", "scan.di", "--material", "aluminum"]) == 0
    assert scene_of(work / "config" / "scenes" / "scan.yaml")["surface"]["map"]["file"] == "sub/scan.di"
