"""Readers of measured profiles and height maps (the inputs of report 2.3 and 2.4.3).

Everything returned is in SI metres: heights, spacings.  Conversion from the
unit of the file happens here, once (see :mod:`asperity.units`).

Text files (any extension but ``.npy`` / ``.nc``):

* read in UTF-8, else Windows-1252, else Latin-1 (`ENCODINGS`: the code pages of
  profilometer software, whose micro sign is the single byte 0xB5); a byte no text
  holds (a C0 control but tab, LF, VT, FF, CR) is an error naming its offset;
* a header (the lines before the first line of numbers) is an error, unless the
  caller asks to skip it (``header=True``); `text_header` and `header_units` read the
  length units it states ("Z unit: µm", "x-unit = mm", "Height units: [nm]");
* ``#`` starts a comment that runs to the end of the line; blank lines and
  comment-only lines are ignored;
* fields are separated by commas, semicolons or whitespace (a comma or
  semicolon with nothing before or after it on the line is an empty field,
  an error);
* every other token must be a finite number.

Errors are :class:`InputError`, a ``ValueError`` whose message reads
``<path>:<line>: <what is wrong>`` (``<path>: <what is wrong>`` when no line
applies, e.g. binary files).
"""

from __future__ import annotations

import io
import math
import os
import re
from pathlib import Path

import numpy as np

from asperity.units import LENGTH, length_scale

__all__ = ["InputError", "known_length_unit", "read_profile", "read_map", "read_text", "text_header",
           "header_units", "ENCODINGS"]

# relative tolerance on the uniformity of the sampling steps
STEP_TOLERANCE = 1e-6

# spellings of length units found in instrument files, mapped to units.LENGTH keys
_UNIT_ALIASES = {
    "meter": "m",
    "metre": "m",
    "meters": "m",
    "metres": "m",
    "centimeter": "cm",
    "centimetre": "cm",
    "millimeter": "mm",
    "millimetre": "mm",
    "micrometer": "um",
    "micrometre": "um",
    "micron": "um",
    "microns": "um",
    "µm": "um",  # micro sign
    "μm": "um",  # greek mu
    "nanometer": "nm",
    "nanometre": "nm",
}


class InputError(ValueError):
    """A bad input file: ``<path>:<line>: <what is wrong>``.

    Attributes ``path``, ``line`` (1-based, or None) and ``reason``.
    """

    def __init__(self, path, reason: str, line: int | None = None):
        self.path = os.fspath(path)
        self.line = line
        self.reason = reason
        where = self.path if line is None else f"{self.path}:{line}"
        super().__init__(f"{where}: {reason}")


def known_length_unit(unit) -> str | None:
    if unit is None:
        return None
    u = str(unit).strip()
    if u in LENGTH and u != "1":
        return u
    return _UNIT_ALIASES.get(u.lower(), _UNIT_ALIASES.get(u))


def _scale(path, length_unit: str | None) -> float:
    if length_unit is None:
        raise InputError(path, "the file states no length unit")
    try:
        return length_scale(length_unit)
    except ValueError as exc:
        raise InputError(path, f"length_unit: {exc}") from None


def _spacing_arg(path, spacing, name: str = "spacing") -> float:
    try:
        h = float(spacing)
    except (TypeError, ValueError):
        raise InputError(path, f"{name} must be a positive number; got {spacing!r}") from None
    if not (math.isfinite(h) and h > 0.0):
        raise InputError(path, f"{name} must be a positive finite number; got {spacing!r}")
    return h


# --------------------------------------------------------------------------
# text tables
# --------------------------------------------------------------------------

_COMMENT = re.compile(r"#[^\n]*")
_EMPTY_FIELD = re.compile(r"^[ \t]*[,;]|[,;][ \t]*[,;]|[,;][ \t]*$", re.MULTILINE)
_DELIMS = str.maketrans(",;", "  ")


class _DataLines:
    """1-based file line of each data row, computed on first use (error paths only)."""

    def __init__(self, text: str):
        self._text = text
        self._lines: np.ndarray | None = None

    def __getitem__(self, i: int) -> int:
        if self._lines is None:
            self._lines = np.array(
                [n for n, line in enumerate(self._text.split("\n"), start=1) if line.strip()],
                dtype=np.int64,
            )
        return int(self._lines[i])


#: bytes no text file holds (C0 controls but tab, line feed, vertical tab, form feed, carriage return)
_BINARY = re.compile(rb"[\x00-\x08\x0e-\x1f]")
#: the encodings a text export is tried in: UTF-8 (with or without its byte-order mark), then the
#: Windows-1252 and ISO 8859-1 (Latin-1) code pages of profilometer software, in which the micro
#: sign is the single byte 0xB5 (Latin-1 decodes every byte: it is the last resort)
ENCODINGS = ("utf-8-sig", "cp1252", "latin-1")


def read_text(path) -> tuple[str, str]:
    """The text of a file and the encoding it was read in (the first of `ENCODINGS` that
    decodes it); InputError naming the first byte no text file holds, and its offset."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(path, f"cannot read: {exc.strerror or exc}") from None
    binary = _BINARY.search(data)
    if binary:
        raise InputError(path, f"byte 0x{data[binary.start()]:02x} at offset {binary.start()}: not a "
                               f"text file (a binary file given as text: give an instrument file "
                               f"its own suffix, e.g. .di, .plu, .sur, .x3p)")
    for encoding in ENCODINGS:
        try:
            return data.decode(encoding), encoding.replace("-sig", "")
        except UnicodeDecodeError:
            continue
    raise AssertionError("latin-1 decodes every byte")  # pragma: no cover


#: a header line stating a length unit: "Z unit: µm", "x-unit = mm", "Height units: [nm]", "Unit: um"
_UNIT_LINE = re.compile(
    r"^[\s#;%*/]*(?:(?P<axis>[xyz]|height|value|values|data|lateral|length|position)[\s_-]*)?"
    r"units?\s*(?:[:=]\s*|\s+)\[?\s*(?P<unit>[^\]\s,;]+)", re.IGNORECASE)
_AXES = {"x": "x", "y": "x", "lateral": "x", "length": "x", "position": "x",
         "z": "z", "height": "z", "value": "z", "values": "z", "data": "z", None: "any"}


def header_units(lines) -> dict[str, str]:
    """The length units the header `lines` of a text export state: ``{"x": ..., "z": ...,
    "any": ...}`` (keys of `asperity.units.LENGTH`; an axis the header does not name is left
    out; "any": a unit stated for no axis)."""
    out: dict[str, str] = {}
    for line in lines:
        m = _UNIT_LINE.match(line)
        if m is None:
            continue
        unit = known_length_unit(m["unit"])
        axis = _AXES[(m["axis"] or "").lower() or None]
        if unit is not None:
            out.setdefault(axis, unit)
    return out


def _is_data(line: str) -> bool:
    tokens = line.translate(_DELIMS).split()
    try:
        [float(t) for t in tokens]
    except ValueError:
        return False
    return bool(tokens)


def _split_header(text: str) -> tuple[list[str], str]:
    """The leading lines of `text` before its first line of numbers (a text export's header),
    and the text with those lines blanked (so that line numbers stay the file's)."""
    lines = text.split("\n")
    first = next((i for i, line in enumerate(lines) if _is_data(_COMMENT.sub("", line))), len(lines))
    return lines[:first], "\n" * first + "\n".join(lines[first:])


def text_header(path) -> tuple[list[str], dict[str, str], str]:
    """The header of a text export (its lines before the first line of numbers), the length
    units it states (`header_units`) and the file's encoding (`read_text`)."""
    text, encoding = read_text(path)
    lines, _ = _split_header(text.replace("\r\n", "\n").replace("\r", "\n"))
    return lines, header_units(lines), encoding


def _read_table(path: Path, ragged, header: bool = False) -> tuple[np.ndarray, _DataLines]:
    """Numbers of a text table, shape (rows, columns), and the file line of each row.

    ``ragged(row, count, first_count)`` words the error for a row whose
    length differs from the first row's; `header`: skip the lines before the
    first line of numbers (a text export's header).
    """
    text, _ = read_text(path)
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    if header:
        _, text = _split_header(text)
    if "#" in text:
        text = _COMMENT.sub("", text)  # comments end at the end of the line
    m = _EMPTY_FIELD.search(text)
    if m:
        number = text.count("\n", 0, m.start()) + 1
        content = text.split("\n")[number - 1].strip()
        raise InputError(path, f"empty field in {content!r} (delimiters: comma, semicolon or whitespace)", number)
    text = text.translate(_DELIMS)
    lines = _DataLines(text)
    if not text.strip():
        raise InputError(path, "no data: the file holds only comments or blank lines")
    try:  # fast path: numpy's C parser
        values = np.loadtxt(io.StringIO(text), dtype=np.float64, ndmin=2, comments=None)
    except ValueError:
        values = _parse_slowly(path, text, ragged)  # raises, naming the line
    return values, lines


def _parse_slowly(path: Path, text: str, ragged) -> np.ndarray:
    """Line-by-line parse that names the first bad line (the fast parser failed)."""
    rows: list[list[float]] = []
    for number, content in enumerate(text.split("\n"), start=1):
        tokens = content.split()
        if not tokens:
            continue
        if rows and len(tokens) != len(rows[0]):
            raise InputError(path, ragged(len(rows), len(tokens), len(rows[0])), number)
        row = []
        for col, tok in enumerate(tokens, start=1):
            try:
                row.append(float(tok))
            except ValueError:
                raise InputError(path, f"column {col}: {tok!r} is not a number", number) from None
        rows.append(row)
    return np.array(rows, dtype=np.float64)  # numbers numpy rejects but float() takes, e.g. 1_000


def _check_finite(path: Path, values: np.ndarray, lines, kind: str):
    bad = ~np.isfinite(values)
    if bad.any():
        r, c = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), values.shape)
        if kind == "profile":
            where = f"column {c + 1}" if values.shape[1] > 1 else "value"
            msg = f"{where} is {values[r, c]}; heights and positions must be finite"
        else:
            msg = f"height at (row {r}, column {c}) is {values[r, c]}; a map must have no gaps"
        raise InputError(path, msg, None if lines is None else int(lines[r]))


# --------------------------------------------------------------------------
# profiles
# --------------------------------------------------------------------------


def _uniform_step(path, x: np.ndarray, lines, what: str) -> float:
    """The uniform step of increasing positions x; InputError names the line of a bad step."""
    step = np.diff(x)
    nonpos = np.flatnonzero(step <= 0.0)
    if nonpos.size:
        i = int(nonpos[0]) + 1
        raise InputError(
            path,
            f"{what} must increase: {x[i]!r} follows {x[i - 1]!r}",
            None if lines is None else int(lines[i]),
        )
    med = float(np.median(step))
    off = np.flatnonzero(np.abs(step - med) > STEP_TOLERANCE * med)
    if off.size:
        i = int(off[0]) + 1
        raise InputError(
            path,
            f"non-uniform {what} spacing: step {float(step[i - 1]):.9g} from {float(x[i - 1]):.9g} to {float(x[i]):.9g} "
            f"differs from the median step {float(med):.9g} by more than {STEP_TOLERANCE:g} relative; "
            "resample the data to uniform spacing",
            None if lines is None else int(lines[i]),
        )
    # the mean step is the least-squares slope of x over the index for a uniform grid
    return float((x[-1] - x[0]) / (x.size - 1))


def read_profile(path, spacing: float | None = None, length_unit: str = "m", header: bool = False,
                 height_unit: str | None = None) -> tuple[np.ndarray, float]:
    """Read a profile z(s) sampled at uniform spacing (input of report 2.3.1).

    Parameters
    ----------
    path : str or Path
        A text table with one column (z) or two columns (x, z), or a ``.npy``
        file holding a 1-D array of z.
    spacing : float, optional
        Sampling interval in ``length_unit``; required for one-column and
        ``.npy`` files.  For two-column files it is taken from x (steps
        uniform to 1e-6 relative, x increasing); if given as well it must
        agree.
    length_unit : str
        Unit of the file's numbers and of ``spacing`` (``asperity.units``:
        m, cm, mm, um, nm).
    header : bool
        Skip the lines before the first line of numbers (a text export's
        header, `text_header`); else such a line is an error.
    height_unit : str, optional
        Unit of the heights where it differs from that of the positions.

    Returns
    -------
    z : ndarray of float64
        Heights in metres (at least 3).
    dx : float
        Sampling interval in metres.
    """
    p = Path(path)
    scale = _scale(p, length_unit)
    zscale = scale if height_unit is None else _scale(p, height_unit)
    if p.suffix.lower() == ".npy":
        z = _load_npy(p)
        if z.ndim != 1:
            raise InputError(p, f"a .npy profile must hold a 1-D array of heights; found shape {z.shape}")
        bad = np.flatnonzero(~np.isfinite(z))
        if bad.size:
            raise InputError(p, f"height at index {bad[0]} is {z[bad[0]]}; heights must be finite")
        if spacing is None:
            raise InputError(p, "a .npy profile holds heights only: pass spacing (in length_unit)")
        dx = _spacing_arg(p, spacing)
    else:
        values, lines = _read_table(
            p, lambda i, count, first: f"found {count} columns where the first data line has {first}", header
        )
        ncol = values.shape[1]
        if ncol not in (1, 2):
            raise InputError(p, f"a profile has 1 column (z) or 2 columns (x, z); found {ncol}", lines[0])
        _check_finite(p, values, lines, "profile")
        z = values[:, -1]
        if z.size < 3:
            raise InputError(p, f"a profile needs at least 3 points; found {z.size}")
        if ncol == 2:
            dx = _uniform_step(p, values[:, 0], lines, "x")
            if spacing is not None:
                given = _spacing_arg(p, spacing)
                if abs(given - dx) > STEP_TOLERANCE * dx:
                    raise InputError(p, f"spacing {given!r} disagrees with the step {dx!r} of the x column")
        else:
            if spacing is None:
                raise InputError(p, "one column of heights and no x column: pass spacing (in length_unit)")
            dx = _spacing_arg(p, spacing)
    if z.size < 3:
        raise InputError(p, f"a profile needs at least 3 points; found {z.size}")
    return np.ascontiguousarray(z, dtype=np.float64) * zscale, dx * scale


# --------------------------------------------------------------------------
# maps
# --------------------------------------------------------------------------


def _load_npy(p: Path) -> np.ndarray:
    try:
        a = np.load(p, allow_pickle=False)
    except (OSError, ValueError) as exc:
        raise InputError(p, f"cannot read as .npy: {exc}") from None
    if not np.issubdtype(a.dtype, np.number) or np.issubdtype(a.dtype, np.complexfloating):
        raise InputError(p, f"expected a real numeric array; found dtype {a.dtype}")
    return np.asarray(a, dtype=np.float64)


def _map_spacing(p: Path, spacing) -> tuple[float, float]:
    if spacing is None:
        raise InputError(p, "this map has no coordinates: pass spacing (in length_unit), a number or (dx, dy)")
    if np.ndim(spacing) == 0:
        h = _spacing_arg(p, spacing)
        return h, h
    if np.ndim(spacing) == 1 and len(spacing) == 2:
        return _spacing_arg(p, spacing[0], "dx"), _spacing_arg(p, spacing[1], "dy")
    raise InputError(p, f"spacing must be a number or a pair (dx, dy); got {spacing!r}")


def _check_map_size(p: Path, z: np.ndarray):
    if z.shape[0] < 3 or z.shape[1] < 3:
        raise InputError(p, f"a map needs at least 3 x 3 points; found shape {z.shape} (rows, columns)")


def read_map(path, spacing=None, length_unit: str | None = "m",
             spacing_unit: str | None = None, header: bool = False) -> tuple[np.ndarray, float, float]:
    """Read a height map z(x, y) on a uniform grid (input of report 2.4.3).

    Parameters
    ----------
    path : str or Path
        * text matrix: one grid row per line (constant y, x along the
          line), all rows of equal length;
        * ``.npy``: a 2-D array ``z[row, column]``;
        * netCDF (``.nc``): the variable ``z``, or else the only 2-D
          variable; its first dimension is y (rows), its second x (columns).
          1-D coordinate variables of its dimensions give the spacings
          (uniform to 1e-6 relative; a decreasing coordinate is reversed
          together with the map so that x and y increase); without them
          ``spacing`` is needed.  Heights are in the variable's ``units``
          attribute when it names a known length unit (m, cm, mm, um, nm
          and spellings like "micrometre", "µm"), else in ``length_unit``;
          likewise each coordinate's own ``units``.
    spacing : float or (float, float), optional
        Grid spacing in ``length_unit``, one number or (dx, dy); required
        unless the file's coordinates give it.  If both are present they
        must agree.
    length_unit : str or None
        Unit of the numbers and of ``spacing`` when the file does not say;
        None: the file must say (an error "states no length unit" otherwise).
    spacing_unit : str, optional
        Unit of ``spacing`` if not ``length_unit``.
    header : bool
        Text: skip the lines before the first line of numbers (`text_header`).

    Returns
    -------
    z : ndarray of float64, shape (ny, nx)
        Heights in metres, ``z[i, j] = z(x = j dx, y = i dy)``.
    dx, dy : float
        Spacings along x (axis 1) and y (axis 0), metres.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".nc":
        return _read_map_netcdf(p, spacing, length_unit, spacing_unit)
    scale = _scale(p, length_unit)
    if suffix == ".npy":
        z = _load_npy(p)
        if z.ndim != 2:
            raise InputError(p, f"a .npy map must hold a 2-D array z[row, column]; found shape {z.shape}")
        _check_finite(p, z, None, "map")
    else:
        z, lines = _read_table(
            p,
            lambda i, count, first: (
                f"row {i} has {count} values where the first row has {first}; "
                "all rows of a map must have the same length"
            ),
            header,
        )
        _check_finite(p, z, lines, "map")
    _check_map_size(p, z)
    dx, dy = _map_spacing(p, spacing)
    step_scale = scale if spacing_unit is None else _scale(p, spacing_unit)
    return np.ascontiguousarray(z) * scale, dx * step_scale, dy * step_scale


def _read_map_netcdf(p: Path, spacing, length_unit: str | None, spacing_unit: str | None = None):
    import xarray as xr

    try:
        ds = xr.open_dataset(p, engine="netcdf4")
    except Exception as exc:  # netCDF4 raises OSError, ValueError, RuntimeError...
        raise InputError(p, f"cannot read as netCDF: {exc}") from None
    with ds:
        if "z" in ds.data_vars:
            name = "z"
        else:
            two_d = [str(n) for n, v in ds.data_vars.items() if v.ndim == 2]
            if len(two_d) != 1:
                found = ", ".join(two_d) or "none"
                raise InputError(
                    p, f"no variable named 'z' and not exactly one 2-D variable (2-D variables: {found})"
                )
            name = two_d[0]
        var = ds[name]
        if var.ndim != 2:
            raise InputError(p, f"variable {name!r} must be 2-D (y, x); found dims {var.dims}")
        z = np.asarray(var.values, dtype=np.float64)
        _check_finite(p, z, None, "map")  # before any flip: (row, column) as stored
        z_unit = known_length_unit(var.attrs.get("units"))
        zscale = length_scale(z_unit) if z_unit else _scale(p, length_unit)
        steps = []
        for axis, dim in enumerate(var.dims):
            if dim in ds.coords and ds[dim].ndim == 1:
                coord = np.asarray(ds[dim].values, dtype=np.float64)
                if not np.isfinite(coord).all():
                    raise InputError(p, f"coordinate {dim!r} has non-finite values")
                if coord.size >= 2 and coord[-1] < coord[0]:
                    coord = coord[::-1]
                    z = np.flip(z, axis=axis)
                c_unit = known_length_unit(ds[dim].attrs.get("units"))
                cscale = length_scale(c_unit) if c_unit else _scale(p, length_unit)
                step = _uniform_step(p, coord, None, f"coordinate {dim!r}") if coord.size >= 2 else None
                steps.append(None if step is None else step * cscale)
            else:
                steps.append(None)
    _check_map_size(p, z)
    dy_c, dx_c = steps
    spacing_unit = spacing_unit or length_unit
    if dx_c is None or dy_c is None:
        # missing coordinates: the spacing argument (in spacing_unit) fills in
        dx_s, dy_s = _map_spacing(p, spacing)
        unit = _scale(p, spacing_unit)
        dx = dx_c if dx_c is not None else dx_s * unit
        dy = dy_c if dy_c is not None else dy_s * unit
    else:
        dx, dy = dx_c, dy_c
        if spacing is not None:
            dx_s, dy_s = (x * _scale(p, spacing_unit) for x in _map_spacing(p, spacing))
            if abs(dx_s - dx) > STEP_TOLERANCE * dx or abs(dy_s - dy) > STEP_TOLERANCE * dy:
                raise InputError(
                    p,
                    f"spacing ({dx_s!r}, {dy_s!r}) m disagrees with the coordinates' steps "
                    f"({dx!r}, {dy!r}) m",
                )
    return np.ascontiguousarray(z) * zscale, float(dx), float(dy)
