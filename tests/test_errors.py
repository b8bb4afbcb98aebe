"""Every error a user can cause at the command line is one line, ``asperity: error: <file>:
<key or byte>: <what> (<fix>)``, with exit status 2 and no traceback: truncated instrument
files, a binary file given as text, scene files (an FE asperity without its geometry, sizes
that say the pressure unit is wrong, numbers YAML reads as text), new-scene without a
material, show on a file that is not a result."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from asperity.cli import main
from asperity.io.inputs import InputError
from asperity.io.topography import read_measurement
from asperity.scene import Asperity, Material, SceneError, Units, check_scene
from tests.scene_defaults import filled

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"
STEEL = ["--material", "steel"]


def one_error_line(capsys, argv) -> str:
    """Run `asperity argv`: exit status 2, nothing on stdout, one line on stderr without a
    traceback; returns that line without its 'asperity: error: ' prefix."""
    assert main(argv) == 2
    captured = capsys.readouterr()
    lines = captured.err.splitlines()
    assert len(lines) == 1, captured.err
    assert "Traceback" not in captured.err
    assert lines[0].startswith("asperity: error: "), lines[0]
    return lines[0][len("asperity: error: "):]


def half(tmp_path, name) -> Path:
    """The first half of the bytes of a real instrument file, under its own name."""
    data = (DATA / name).read_bytes()
    out = tmp_path / name
    out.write_bytes(data[: len(data) // 2])
    return out


# the reader's own words for each truncated format (SurfaceTopography's CorruptFile)
TRUNCATED = {
    "di-3.di": ("map", "Bruker/Veeco/DI Nanoscope", "not large enough to contain all data buffers"),
    "frt-1.frt": ("map", "FRT MicroProf", "probably truncated"),
    "hfm-1.hfm": ("profile", "x,y,z coordinates", "probably truncated"),
}


@pytest.mark.parametrize("name", sorted(TRUNCATED))
def test_a_truncated_instrument_file_is_one_line_naming_it(tmp_path, capsys, name):
    kind, reader, words = TRUNCATED[name]
    path = half(tmp_path, name)
    with pytest.raises(InputError) as info:
        read_measurement(path, kind)
    assert info.value.path == str(path)
    assert reader in info.value.reason and words in info.value.reason
    line = one_error_line(capsys, ["new-scene", str(path), "--scene-dir", str(tmp_path), *STEEL])
    assert line.startswith(f"{path}: a ") and words in line and "truncated or damaged" in line
    assert not (tmp_path / f"{Path(name).stem.replace('-', '_')}.yaml").exists()


def test_the_command_exits_2_without_a_traceback(tmp_path):
    """The installed entry point (not only `main`): status 2 and one line on stderr."""
    path = half(tmp_path, "di-3.di")
    run = subprocess.run([sys.executable, "-m", "asperity.cli", "new-scene", str(path), "--scene-dir",
                          str(tmp_path), *STEEL], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2
    assert run.stdout == ""
    assert run.stderr.startswith(f"asperity: error: {path}: ") and run.stderr.count("\n") == 1, run.stderr


def test_a_binary_file_given_as_text_names_the_byte_offset(tmp_path, capsys):
    data = (DATA / "di-3.di").read_bytes()
    path = tmp_path / "scan.txt"
    path.write_bytes(data)
    # the first byte no text holds (C0 controls other than tab, LF, VT, FF, CR), found byte by byte
    offset = next(i for i, b in enumerate(data) if b <= 0x08 or 0x0E <= b <= 0x1F)
    line = one_error_line(capsys, ["new-scene", str(path), "--scene-dir", str(tmp_path), *STEEL])
    assert line.startswith(f"{path}: byte 0x{data[offset]:02x} at offset {offset}: not a text file"), line


SCENE = """title: t
report: r
units: {length: um, pressure: MPa}
surface:
  gaussian_heights: {sigma_peak_height: 1.0, radius: 100.0, peak_density: 0.001}
"""


def test_an_fe_asperity_without_geometry_names_the_file_and_key(tmp_path, capsys):
    path = tmp_path / "fe.yaml"
    path.write_text(SCENE + "asperity: {model: fe}\nmaterial: {youngs_modulus: 210000.0, poisson: 0.3}\n")
    line = one_error_line(capsys, ["check", str(path)])
    assert line == (f"{path}: asperity.geometry: an FE asperity (model: fe) needs its geometry "
                    f"(add geometry: sphere | paraboloid | cosine)")
    # the typed object the plan job builds refuses it too (the schema's defaults filled in)
    with pytest.raises(SceneError, match=r"^asperity.geometry: .* sphere \| paraboloid \| cosine"):
        Asperity.from_section(filled("asperity", {"model": "fe"}), Units("um", "MPa"))
    with pytest.raises(SceneError) as info:
        check_scene({"asperity": {"model": "fe", "geometry": "cube"}}, path)
    assert str(info.value).startswith(f"{path}: asperity.geometry: unknown geometry 'cube'")
    path.write_text(SCENE + "asperity: {model: fe, geometry: sphere}\n"
                            "material: {youngs_modulus: 210000.0, poisson: 0.3}\n")
    assert main(["check", str(path)]) == 0


@pytest.mark.parametrize("material, key, words", [
    # Pa typed into an MPa scene: 2.1e11 MPa = 2.1e8 GPa, and 2.1e11 Pa = 2.1e5 MPa
    ("{youngs_modulus: 2.1e+11, poisson: 0.3}", "material.youngs_modulus",
     "youngs_modulus 2.1e+11 MPa is 2.1e+08 GPa: a Young's modulus is 0.001 MPa to 2000 GPa "
     "(did you give Pa? write 2.1e5 in MPa"),
    # 0.0002 MPa = 200 Pa = 2e-7 GPa: below the softest gel; as GPa it is 0.2 MPa
    ("{youngs_modulus: 0.0002, poisson: 0.3}", "material.youngs_modulus",
     "youngs_modulus 0.0002 MPa is 2e-07 GPa: a Young's modulus is 0.001 MPa to 2000 GPa (did you give GPa? "
     "write 0.2 in MPa"),
    ("{youngs_modulus: 210000.0, poisson: 0.3, yield_stress: 3.5e+8}", "material.yield_stress",
     "yield_stress 3.5e+08 MPa is 3.5e+05 GPa: at or above youngs_modulus 2.1e+05 MPa (did you give Pa? "
     "write 350 in MPa"),
    ("{youngs_modulus: 210000.0, poisson: 0.3, yield_stress: 0.00035}", "material.yield_stress",
     "below 1e-05 youngs_modulus"),
    ("{youngs_modulus: 210000.0, poisson: 0.3, yield_stress: 350.0, hardness: 200.0}", "material.hardness",
     "hardness 200 MPa is below yield_stress 350 MPa (a hardness is about 2.8 yield stresses"),
    ("{youngs_modulus: 210e9, poisson: 0.3}", "material.youngs_modulus",
     "'210e9' is not of type 'number' (YAML reads 210e9 as text: write 210.0e+9)"),
    ("{youngs_modulus: 210.0e9, poisson: 0.3}", "material.youngs_modulus",
     "'210.0e9' is not of type 'number' (YAML reads 210.0e9 as text: write 210.0e+9)"),
])
def test_sizes_that_say_the_unit_is_wrong_are_refused(tmp_path, capsys, material, key, words):
    path = tmp_path / "units.yaml"
    path.write_text(SCENE + f"material: {material}\n")
    line = one_error_line(capsys, ["check", str(path)])
    assert line.startswith(f"{path}: {key}: "), line
    assert words in line, line


def test_a_modulus_in_mpa_in_a_pascal_scene_names_gpa_as_the_likely_unit():
    """210 in a Pa scene: as kPa, MPa and GPa it is a modulus (2.1e5, 2.1e8, 2.1e11 Pa); GPa
    puts it nearest a metal's 1e11 Pa, and 210 GPa is 2.1e11 Pa."""
    with pytest.raises(SceneError) as info:
        check_scene({"units": {"pressure": "Pa"}, "material": {"youngs_modulus": 210.0, "poisson": 0.3}})
    assert str(info.value) == ("material.youngs_modulus: youngs_modulus 210 Pa is 2.1e-07 GPa: a Young's "
                               "modulus is 0.001 MPa to 2000 GPa (did you give GPa? write 2.1e11 in Pa, "
                               "or set units.pressure: GPa)")


def test_the_material_section_is_checked_where_it_becomes_si():
    """Material.from_scene, which every stage calls, refuses the sizes; a plausible material
    in the same unit passes and is in SI (2.1e5 MPa = 2.1e11 Pa exactly)."""
    with pytest.raises(SceneError, match=r"^material.youngs_modulus: .*did you give Pa\? write 2.1e5"):
        Material.from_scene({"model": "elastic", "youngs_modulus": 2.1e11, "poisson": 0.3}, Units("um", "MPa"))
    ok = Material.from_scene({"model": "elastic", "youngs_modulus": 2.1e5, "poisson": 0.3}, Units("um", "MPa"))
    assert ok.youngs_modulus == 2.1e11
    # a dimensionless verification scene is not judged
    assert Material.from_scene({"model": "elastic", "youngs_modulus": 1e20, "poisson": 0.3},
                               Units("1", "1")).youngs_modulus == 1e20


def test_new_scene_without_a_material_says_which_option_to_give(tmp_path, capsys):
    line = one_error_line(capsys, ["new-scene", str(DATA / "di-3.di"), "--scene-dir", str(tmp_path)])
    assert line.startswith("--material: no material given (give --material NAME, one of steel, aluminum")
    assert "--youngs-modulus E --poisson NU in MPa" in line
    line = one_error_line(capsys, ["new-scene", str(DATA / "di-3.di"), "--scene-dir", str(tmp_path),
                                   "--youngs-modulus", "2.1e11", "--poisson", "0.3"])
    assert line.startswith("--youngs-modulus: youngs_modulus 2.1e+11 MPa") and "pass --pressure-unit Pa" in line
    line = one_error_line(capsys, ["new-scene", str(DATA / "di-3.di"), "--scene-dir", str(tmp_path),
                                   "--youngs-modulus", "210000"])
    assert line == "--poisson: missing (give it too, or --material NAME)"
    line = one_error_line(capsys, ["new-scene", str(DATA / "di-3.di"), "--scene-dir", str(tmp_path),
                                   "--material", "unobtainium"])
    assert line.startswith("--material: unknown material 'unobtainium' (known: steel")
    assert list(tmp_path.iterdir()) == []


def test_show_on_a_file_that_is_not_a_result(tmp_path, capsys):
    path = tmp_path / "notes.nc"
    path.write_text("not netCDF\n")
    line = one_error_line(capsys, ["show", str(path)])
    assert line.startswith(f"{path}: not a netCDF result file (")
    line = one_error_line(capsys, ["show", str(tmp_path / "absent")])
    assert line == f"{tmp_path / 'absent'}: no such file or folder"
