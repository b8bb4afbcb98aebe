"""Readers of profile and map files (asperity.io.inputs): values, units, every error path."""

from __future__ import annotations

import re

import numpy as np
import pytest
import xarray as xr

from asperity.io.inputs import InputError, read_map, read_profile


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def raises_at(path, line, call, *fragments):
    """`call` raises InputError whose message starts '<path>:<line>: ' and holds `fragments`."""
    with pytest.raises(InputError) as info:
        call()
    msg = str(info.value)
    head = f"{path}:{line}: " if line is not None else f"{path}: "
    assert msg.startswith(head), msg
    assert path.name in msg
    for frag in fragments:
        assert re.search(frag, msg), (frag, msg)
    assert info.value.line == line
    assert isinstance(info.value, ValueError)
    return msg


# --------------------------------------------------------------------------
# profiles: valid files
# --------------------------------------------------------------------------


def test_one_column_profile_in_micrometres(tmp_path):
    p = write(tmp_path, "prof.txt", "# heights in um\n\n1.5\n-2.0\n  0.25  \n# end\n3\n")
    z, dx = read_profile(p, spacing=0.5, length_unit="um")
    np.testing.assert_array_equal(z, np.array([1.5, -2.0, 0.25, 3.0]) * 1e-6)
    assert dx == pytest.approx(0.5e-6, rel=1e-15)
    assert z.dtype == np.float64


@pytest.mark.parametrize("sep", [",", ";", " ", "\t", " , ", "; "])
def test_two_column_profile_delimiters(tmp_path, sep):
    x = 10.0 + 0.25 * np.arange(6)
    zv = np.sin(x)
    body = "\n".join(f"{float(a)!r}{sep}{float(b)!r}" for a, b in zip(x, zv))
    p = write(tmp_path, "prof.csv", "# x, z (mm)\n" + body + "  # trailing comment\n\n")
    z, dx = read_profile(p, length_unit="mm")
    np.testing.assert_allclose(z, zv * 1e-3, rtol=1e-15)
    assert dx == pytest.approx(0.25e-3, rel=1e-12)


def test_two_column_profile_with_agreeing_spacing(tmp_path):
    p = write(tmp_path, "p.txt", "0 1\n2 2\n4 3\n")
    z, dx = read_profile(p, spacing=2.0)
    assert dx == 2.0 and z.tolist() == [1.0, 2.0, 3.0]


def test_npy_profile(tmp_path):
    p = tmp_path / "prof.npy"
    np.save(p, np.array([1.0, 2.0, 4.0, 8.0]))
    z, dx = read_profile(p, spacing=2.0, length_unit="um")
    np.testing.assert_allclose(z, [1e-6, 2e-6, 4e-6, 8e-6], rtol=1e-15)
    assert dx == pytest.approx(2e-6, rel=1e-15)


# --------------------------------------------------------------------------
# profiles: errors, each naming the file and the line
# --------------------------------------------------------------------------


def test_profile_needs_spacing_for_one_column(tmp_path):
    p = write(tmp_path, "one.txt", "1\n2\n3\n")
    raises_at(p, None, lambda: read_profile(p), "pass spacing")


def test_profile_non_numeric_token(tmp_path):
    p = write(tmp_path, "bad.csv", "# header comment\n0, 1\n1, 2\n\n2, abc\n3, 4\n")
    raises_at(p, 5, lambda: read_profile(p), "column 2", "'abc' is not a number")


def test_profile_header_line_is_not_numeric(tmp_path):
    p = write(tmp_path, "hdr.csv", "x,z\n0,1\n1,2\n2,3\n")
    raises_at(p, 1, lambda: read_profile(p), "'x' is not a number")


@pytest.mark.parametrize("token", ["nan", "NaN", "inf", "-inf"])
def test_profile_non_finite(tmp_path, token):
    p = write(tmp_path, "nan.txt", f"0 1\n1 2\n# c\n2 {token}\n3 4\n")
    raises_at(p, 4, lambda: read_profile(p), "must be finite")


def test_profile_non_uniform_step(tmp_path):
    # steps 1, 1, 1.001 (1e-3 relative > 1e-6), 1: the bad step ends on line 5
    p = write(tmp_path, "step.txt", "0 0\n1 1\n2 2\n# gap\n3.001 3\n4.001 4\n")
    raises_at(p, 5, lambda: read_profile(p), "non-uniform x spacing", "median step")


def test_profile_step_within_tolerance_is_accepted(tmp_path):
    # 1e-9 jitter (1e-9 relative < 1e-6): accepted, dx is the mean step
    p = write(tmp_path, "ok.txt", "0 0\n1.000000001 1\n2 2\n3 3\n")
    _, dx = read_profile(p)
    assert dx == pytest.approx(1.0, rel=1e-15)


def test_profile_x_must_increase(tmp_path):
    p = write(tmp_path, "dec.txt", "0 0\n1 1\n1 2\n2 3\n")
    raises_at(p, 3, lambda: read_profile(p), "x must increase")


def test_profile_too_many_columns(tmp_path):
    p = write(tmp_path, "three.txt", "\n# c\n0 1 2\n1 2 3\n2 3 4\n")
    raises_at(p, 3, lambda: read_profile(p), "1 column .* or 2 columns .* found 3")


def test_profile_ragged_line(tmp_path):
    p = write(tmp_path, "ragged.txt", "0 1\n1 2\n2\n3 4\n")
    raises_at(p, 3, lambda: read_profile(p), "found 1 columns where the first data line has 2")


def test_profile_empty_field(tmp_path):
    p = write(tmp_path, "empty.csv", "0,1\n1,,2\n2,3\n")
    raises_at(p, 2, lambda: read_profile(p), "empty field")


def test_profile_too_short(tmp_path):
    p = write(tmp_path, "short.txt", "0 1\n1 2\n")
    raises_at(p, None, lambda: read_profile(p), "at least 3 points; found 2")


def test_profile_without_data(tmp_path):
    p = write(tmp_path, "nodata.txt", "# only a comment\n\n")
    raises_at(p, None, lambda: read_profile(p, spacing=1.0), "no data")


def test_profile_spacing_disagrees_with_x(tmp_path):
    p = write(tmp_path, "p.txt", "0 1\n2 2\n4 3\n")
    raises_at(p, None, lambda: read_profile(p, spacing=1.0), "disagrees")


def test_profile_bad_spacing_and_unit(tmp_path):
    p = write(tmp_path, "p.txt", "1\n2\n3\n")
    raises_at(p, None, lambda: read_profile(p, spacing=-1.0), "positive")
    raises_at(p, None, lambda: read_profile(p, spacing=1.0, length_unit="furlong"), "unknown length unit")


def test_npy_profile_errors(tmp_path):
    p = tmp_path / "p.npy"
    np.save(p, np.array([1.0, 2.0, 3.0]))
    raises_at(p, None, lambda: read_profile(p), "pass spacing")
    q = tmp_path / "q.npy"
    np.save(q, np.ones((3, 3)))
    raises_at(q, None, lambda: read_profile(q, spacing=1.0), "1-D array", r"\(3, 3\)")
    r = tmp_path / "r.npy"
    np.save(r, np.array([1.0, np.nan, 3.0]))
    raises_at(r, None, lambda: read_profile(r, spacing=1.0), "index 1 is nan")
    t = tmp_path / "t.npy"
    t.write_bytes(b"not numpy")
    raises_at(t, None, lambda: read_profile(t, spacing=1.0), "cannot read as .npy")


def test_missing_and_binary_files(tmp_path):
    p = tmp_path / "absent.txt"
    raises_at(p, None, lambda: read_profile(p, spacing=1.0), "cannot read")
    b = tmp_path / "bin.dat"
    b.write_bytes(b"\xff\xfe\x00\x01")
    raises_at(b, None, lambda: read_profile(b, spacing=1.0), r"byte 0x00 at offset 2: not a text file")


# --------------------------------------------------------------------------
# maps
# --------------------------------------------------------------------------

MAP = np.arange(12.0).reshape(3, 4) ** 1.5


def test_text_map(tmp_path):
    body = "\n".join(";".join(repr(float(v)) for v in row) for row in MAP)
    p = write(tmp_path, "map.csv", "# z in um, rows are y\n" + body + "\n")
    z, dx, dy = read_map(p, spacing=(2.0, 3.0), length_unit="um")
    np.testing.assert_allclose(z, MAP * 1e-6, rtol=1e-15)
    assert (dx, dy) == (pytest.approx(2e-6, rel=1e-15), pytest.approx(3e-6, rel=1e-15))


def test_text_map_errors(tmp_path):
    p = write(tmp_path, "ragged.txt", "1 2 3\n# c\n4 5 6\n7 8\n")
    raises_at(p, 4, lambda: read_map(p, spacing=1.0), "row 2 has 2 values where the first row has 3")
    q = write(tmp_path, "nan.txt", "1 2 3\n4 5 6\n\n7 nan 9\n")
    raises_at(q, 4, lambda: read_map(q, spacing=1.0), r"\(row 2, column 1\)", "nan")
    r = write(tmp_path, "word.txt", "1 2 3\n4 five 6\n7 8 9\n")
    raises_at(r, 2, lambda: read_map(r, spacing=1.0), "'five' is not a number")
    s = write(tmp_path, "small.txt", "1 2 3\n4 5 6\n")
    raises_at(s, None, lambda: read_map(s, spacing=1.0), "3 x 3")
    t = write(tmp_path, "nospacing.txt", "1 2 3\n4 5 6\n7 8 9\n")
    raises_at(t, None, lambda: read_map(t), "pass spacing")
    raises_at(t, None, lambda: read_map(t, spacing=(1.0, 2.0, 3.0)), "pair")


def test_npy_map(tmp_path):
    p = tmp_path / "m.npy"
    np.save(p, MAP)
    z, dx, dy = read_map(p, spacing=0.5, length_unit="mm")
    np.testing.assert_allclose(z, MAP * 1e-3, rtol=1e-15)
    assert dx == dy == pytest.approx(0.5e-3, rel=1e-15)
    bad = MAP.copy()
    bad[1, 2] = np.nan
    q = tmp_path / "n.npy"
    np.save(q, bad)
    raises_at(q, None, lambda: read_map(q, spacing=1.0), r"\(row 1, column 2\)")
    r = tmp_path / "one.npy"
    np.save(r, np.ones(5))
    raises_at(r, None, lambda: read_map(r, spacing=1.0), "2-D array")


def netcdf_map(path, z, x=None, y=None, name="z", units="um", coord_units="um", extra=None):
    coords = {}
    if x is not None:
        coords["x"] = ("x", x, {"units": coord_units})
    if y is not None:
        coords["y"] = ("y", y, {"units": coord_units})
    attrs = {} if units is None else {"units": units}
    ds = xr.Dataset({name: (("y", "x"), z, attrs)}, coords=coords)
    if extra:
        for k, v in extra.items():
            ds[k] = v
    ds.to_netcdf(path, engine="netcdf4")
    return path


def test_netcdf_map_units_from_the_file(tmp_path):
    x = 5.0 + 0.5 * np.arange(4)
    y = 2.0 * np.arange(3)
    p = netcdf_map(tmp_path / "m.nc", MAP, x, y, units="micrometre", coord_units="mm")
    z, dx, dy = read_map(p, length_unit="m")  # file units win over length_unit
    np.testing.assert_allclose(z, MAP * 1e-6, rtol=1e-15)
    assert dx == pytest.approx(0.5e-3, rel=1e-12)
    assert dy == pytest.approx(2.0e-3, rel=1e-12)


def test_netcdf_map_without_units_or_coordinates(tmp_path):
    p = netcdf_map(tmp_path / "bare.nc", MAP, name="height", units=None)
    raises_at(p, None, lambda: read_map(p), "pass spacing")
    z, dx, dy = read_map(p, spacing=(1.0, 2.0), length_unit="nm")  # the only 2-D variable
    np.testing.assert_allclose(z, MAP * 1e-9, rtol=1e-15)
    assert (dx, dy) == (pytest.approx(1e-9), pytest.approx(2e-9))


def test_netcdf_map_decreasing_coordinate_is_reversed(tmp_path):
    y = np.array([4.0, 2.0, 0.0])
    x = np.arange(4.0)
    p = netcdf_map(tmp_path / "dec.nc", MAP, x, y, units="m", coord_units="m")
    z, dx, dy = read_map(p)
    np.testing.assert_array_equal(z, MAP[::-1])
    assert (dx, dy) == (1.0, 2.0)


def test_netcdf_map_errors(tmp_path):
    x = np.array([0.0, 1.0, 2.0, 3.5])
    p = netcdf_map(tmp_path / "nonuni.nc", MAP, x, np.arange(3.0))
    raises_at(p, None, lambda: read_map(p), "non-uniform coordinate 'x' spacing")
    bad = MAP.copy()
    bad[2, 1] = np.nan
    q = netcdf_map(tmp_path / "nan.nc", bad, np.arange(4.0), np.arange(3.0))
    raises_at(q, None, lambda: read_map(q), r"\(row 2, column 1\)")
    two = xr.DataArray(MAP, dims=("y", "x"))
    r = netcdf_map(tmp_path / "two.nc", MAP, name="a", extra={"b": two})
    raises_at(r, None, lambda: read_map(r, spacing=1.0), "not exactly one 2-D variable", "a, b")
    s = tmp_path / "junk.nc"
    s.write_bytes(b"CDF junk")
    raises_at(s, None, lambda: read_map(s, spacing=1.0), "cannot read as netCDF")
    t = netcdf_map(tmp_path / "agree.nc", MAP, np.arange(4.0), np.arange(3.0), units="m", coord_units="m")
    raises_at(t, None, lambda: read_map(t, spacing=2.0), "disagrees")


# --------------------------------------------------------------------------
# text exports: encodings other than UTF-8, a header that states the units
# --------------------------------------------------------------------------

EXPORT_Z = np.array([0.125, -1.5, 2.25, 0.75, -0.375])


@pytest.mark.parametrize("encoding, extra", [
    ("cp1252", "\u20ac"),  # the euro sign: 0x80 in Windows-1252, undefined in Latin-1's C1 range
    ("latin-1", "\x81"),  # 0x81: undefined in Windows-1252, so only Latin-1 decodes the file
])
def test_a_latin1_or_cp1252_export_is_read_with_the_unit_its_header_states(tmp_path, encoding, extra):
    from asperity.io.inputs import text_header
    from asperity.io.topography import read_measurement

    head = f"Profile export {extra}\r\nX unit: mm\r\nZ unit: \u00b5m\r\nX;Z\r\n"
    body = "".join(f"{0.002 * k:.3f};{z}\r\n" for k, z in enumerate(EXPORT_Z))
    p = tmp_path / "export.txt"
    p.write_bytes((head + body).encode(encoding))
    assert p.read_bytes().count(b"\xb5") == 1  # the micro sign is one byte
    lines, units, found = text_header(p)
    assert (len(lines), units, found) == (4, {"x": "mm", "z": "um"}, encoding)
    m = read_measurement(p, "profile")
    np.testing.assert_array_equal(m.heights, EXPORT_Z * 1e-6)  # um, exactly as the product
    assert m.dx == pytest.approx(0.002e-3, rel=1e-12)  # the x column in mm
    assert m.unit == "um" and f"({encoding})" in m.notes[0]
    z, dx = read_profile(p, length_unit="mm", header=True, height_unit="um")
    np.testing.assert_array_equal(z, EXPORT_Z * 1e-6)
    # the scene's unit overrides the header's, for positions and heights alike
    m = read_measurement(p, "profile", unit="nm")
    np.testing.assert_array_equal(m.heights, EXPORT_Z * 1e-9)
    assert m.dx == pytest.approx(0.002e-9, rel=1e-12)


def test_header_units_spellings():
    from asperity.io.inputs import header_units

    assert header_units(["# Z unit: [µm]", "x-unit = mm"]) == {"z": "um", "x": "mm"}
    assert header_units(["Height units: nm", "Lateral unit: micrometre"]) == {"z": "nm", "x": "um"}
    assert header_units(["Unit: um", "Z unit: volts"]) == {"any": "um"}  # a unit asperity knows only
