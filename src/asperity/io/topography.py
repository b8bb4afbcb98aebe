"""Reading a measured profile or height map, whatever wrote it (the input of report 2.3, 2.4.3).

One entry point, :func:`read_measurement`, for every file a scene can name:

* plain text tables (``.txt``, ``.csv``, ``.tsv``, ``.asc``), ``.npy`` and
  netCDF (``.nc``): asperity's own readers (:mod:`asperity.io.inputs`);
* every other file, and a text file that asperity's reader does not take
  (a header line, positions rounded in print so that the steps differ by
  more than 1e-6): SurfaceTopography's readers (about 40 instrument formats:
  Sensofar .plu, Zygo .dat/.datx, Digital Surf .sur, ISO 5436-2 .x3p,
  Bruker/DI, Wyko .opd, Keyence .vk, FRT, Gwyddion, ...), with their
  metadata: length unit, physical size, channels, undefined points.

A text export with a header that neither reader takes (or whose unit only the
header states, "Z unit: µm") is read by asperity past its header, with the units
the header states; text in Windows-1252 or Latin-1 is read as such (given to
SurfaceTopography as a UTF-8 copy).  An instrument file whose own reader fails
on it (a truncated or damaged file: its format told by its magic bytes or its
suffix) is an error naming the file, the format and the reader's words.

The unit of the numbers comes from the file where the file states it (an
instrument's metadata, a netCDF ``units`` attribute, a text export's header).  Where it does not
(text, ``.npy``, some instrument files), the scene must say it
(``surface.<kind>.unit``); a unit given in the scene overrides the file's,
and so does a spacing, and the notes returned say so (for the job's log).

Heights are returned in metres with NaN at undefined points and a ``defined``
mask; a map as ``z[i, j] = z(x = j dx, y = i dy)`` (SurfaceTopography's
arrays have x along axis 0: they are transposed here).  Errors are
:class:`~asperity.io.inputs.InputError` naming the file (and the line, or the
scene key to set).
"""

from __future__ import annotations

import tempfile
import warnings
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from asperity.io.inputs import (InputError, known_length_unit, read_map, read_profile, read_text,
                                text_header)
from asperity.units import LENGTH, length_scale

__all__ = ["Measurement", "read_measurement", "OWN_TEXT", "describe_file"]

#: suffixes read by asperity's own text reader first
OWN_TEXT = (".txt", ".csv", ".tsv", ".asc")
KINDS = {1: "profile", 2: "map"}


@dataclass
class Measurement:
    """A measured profile or map in SI, as read from its file."""

    path: str
    kind: str  # "profile" or "map"
    heights: np.ndarray  # metres, NaN where undefined
    defined: np.ndarray  # bool, True where measured
    dx: float  # metres
    dy: float | None  # metres (maps)
    unit: str  # the length unit the file's numbers were taken in
    reader: str  # which reader read it
    channel: str | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def undefined_share(self) -> float:
        return 1.0 - float(np.count_nonzero(self.defined)) / self.defined.size

    @property
    def spacing(self):
        """dx for a profile, (dx, dy) for a map."""
        return self.dx if self.kind == "profile" else (self.dx, self.dy)


def _unit_error(path, key: str) -> InputError:
    return InputError(path, f"the file states no length unit; give the unit of its numbers in the "
                            f"scene as {key}.unit (one of {', '.join(u for u in LENGTH if u != '1')})")


def read_measurement(path, kind: str, unit: str | None = None, spacing: float | None = None,
                     channel: str | None = None, key: str | None = None) -> Measurement:
    """Read a measured profile (``kind="profile"``) or map (``kind="map"``).

    Parameters
    ----------
    path : file name
    kind : what the scene expects; a file of the other kind is an error.
    unit : the length unit of the file's numbers (heights and positions),
        if the scene gives it; it overrides the file's own.
    spacing : sampling interval in metres, if the scene gives it; it
        overrides the file's own (and is needed where the file has none).
    channel : the instrument channel to read (by name), default the file's
        default (height) channel.
    key : the scene key of the source, for error messages
        (default ``surface.<kind>``).
    """
    p = Path(path)
    key = key or f"surface.{kind}"
    if kind not in ("profile", "map"):
        raise ValueError(f"kind must be 'profile' or 'map'; got {kind!r}")
    if not p.exists():
        raise InputError(p, f"no such file (scene key {key}.file)")
    suffix = p.suffix.lower()
    if suffix in (".npy", ".nc") or suffix in OWN_TEXT:
        try:
            return _read_own(p, kind, unit, spacing, key)
        except InputError as err:
            if suffix not in OWN_TEXT or not _instrument_text(err):
                raise
            own = err  # a header, or positions rounded in print: perhaps an instrument's export
        try:
            found = _read_instrument(p, kind, unit, spacing, channel, key)
        except InputError as err:
            try:  # a header SurfaceTopography cannot read (or a unit only the header states)
                return _read_export(p, kind, unit, spacing, key)
            except InputError as export:
                if "states no" in err.reason:
                    raise err from None  # SurfaceTopography read the file; the scene must add what it lacks
                if "states no" in export.reason:
                    raise export from None
            raise own from None  # the line asperity's reader could not take says most
        found.notes.insert(0, f"read by {found.reader}, which takes it as uniformly sampled "
                              f"(asperity's reader: {own})")
        return found
    return _read_instrument(p, kind, unit, spacing, channel, key)


def _read_export(p: Path, kind: str, unit, spacing, key) -> Measurement:
    """A text export with a header (lines before the first line of numbers) through asperity's
    reader: the header's length units (`asperity.io.inputs.header_units`: "Z unit: µm", ...) unless
    the scene gives one, the numbers after it."""
    lines, stated, encoding = text_header(p)
    if not lines:
        raise InputError(p, "no header")
    z_unit = unit or stated.get("z") or stated.get("any")
    x_unit = unit or stated.get("x") or stated.get("any") or z_unit
    if z_unit is None:
        raise _unit_error(p, key)
    notes = [f"read by asperity past its {len(lines)}-line header ({encoding})"]
    notes.append(f"length unit {unit} from the scene ({key}.unit)" if unit else
                 f"length units from the header: heights in {z_unit}, positions in {x_unit}")
    if kind == "profile":
        given = None if spacing is None else spacing / length_scale(x_unit)
        z, dx = read_profile(p, spacing=given, length_unit=x_unit, header=True, height_unit=z_unit)
        dy = None
    else:
        if x_unit != z_unit and spacing is None:
            raise InputError(p, f"a map's header with heights in {z_unit} and positions in {x_unit}: "
                                f"give the spacing as {key}.spacing")
        z, dx, dy = read_map(p, spacing=spacing, length_unit=z_unit, spacing_unit="m", header=True)
    if spacing is not None:
        notes.append(f"spacing {spacing:.6g} m from the scene ({key}.spacing)")
    return Measurement(str(p), kind, z, np.ones(z.shape, dtype=bool), dx, dy, z_unit,
                       "asperity (text export)", notes=notes)


def _instrument_text(err: InputError) -> bool:
    """Whether asperity's text reader failed on what an instrument's text export holds: a
    header line, or positions printed so coarsely that the steps look non-uniform."""
    return err.line is not None and ("is not a number" in err.reason or "non-uniform" in err.reason)


def _read_own(p: Path, kind: str, unit, spacing, key) -> Measurement:
    """Text, .npy, netCDF through asperity.io.inputs."""
    states_unit = p.suffix.lower() == ".nc"
    file_unit = unit or "m"  # parsed first: a header that asperity cannot read may state the unit
    given = None if spacing is None else spacing / length_scale(file_unit)  # in the file's unit
    notes = [f"length unit {unit} from the scene ({key}.unit)"] if unit else []
    if kind == "profile":
        if states_unit:
            raise InputError(p, f"a netCDF file holds a map: name it under surface.map, not {key}")
        z, dx = read_profile(p, spacing=given, length_unit=file_unit)
        heights, dy = z, None
        if unit is None:
            raise _unit_error(p, key)
    else:
        try:
            z, dx, dy = read_map(p, spacing=spacing, length_unit=unit if states_unit else file_unit,
                                 spacing_unit="m")
        except InputError as err:
            if "states no length unit" in err.reason:
                raise _unit_error(p, key) from None
            raise
        if unit is None and not states_unit:
            raise _unit_error(p, key)
        heights = z
        if states_unit and unit is None:
            notes.append("length units from the netCDF file's units attributes")
    if spacing is not None:
        notes.append(f"spacing {spacing:.6g} m from the scene ({key}.spacing)")
    return Measurement(str(p), kind, heights, np.ones(heights.shape, dtype=bool), dx, dy,
                       unit or "file units", "asperity", notes=notes)


#: suffixes instruments write that SurfaceTopography's readers do not list as theirs
SUFFIX_READERS = {"di": ("DIReader",)}
#: what a reader that fails on a file of its own format most likely means
DAMAGED = "is the file truncated or damaged? copy it again from the instrument, or export it anew"


@contextmanager
def _utf8(p: Path):
    """`p`, or for a text export in another encoding (`asperity.io.inputs.read_text`) a UTF-8
    copy of it under the same name (SurfaceTopography reads text as UTF-8)."""
    if p.suffix.lower() not in OWN_TEXT:
        yield p
        return
    text, encoding = read_text(p)
    if encoding == "utf-8":
        yield p
        return
    with tempfile.TemporaryDirectory(prefix="asperity-") as tmp:
        copy = Path(tmp) / p.name
        copy.write_text(text, encoding="utf-8")
        yield copy


def _surface_topography():
    try:
        with warnings.catch_warnings():  # NuMPI says it runs without MPI: so do we
            warnings.filterwarnings("ignore", message="Could not import mpi4py", category=ImportWarning)
            import SurfaceTopography as ST
    except ImportError as exc:  # a broken installation, not a user error
        raise InputError("SurfaceTopography", f"instrument files need it: {exc}") from None
    return ST


def _open(p: Path, source: Path | None = None):
    """SurfaceTopography's reader of the file `source` (default `p`; errors name `p`)."""
    ST = _surface_topography()
    from SurfaceTopography.Exceptions import CannotDetectFileFormat

    try:
        return ST.open_topography(str(source or p))
    except CannotDetectFileFormat:
        failure = _own_format_failure(source or p)
        if failure is not None:
            name, exc = failure
            raise InputError(p, f"a {name} file whose reader fails: {type(exc).__name__}: "
                                f"{_first_line(exc)} ({DAMAGED})") from None
        raise InputError(
            p, "not a format asperity can read: a plain text table (.txt, .csv, .tsv: x z, z, or a "
               "matrix), .npy, netCDF (.nc), or one of the instrument formats SurfaceTopography "
               "reads (.plu, .datx, .sur, .x3p, .di, .opd, .frt, .gwy, ...)") from None
    except Exception as exc:  # a reader recognized the file and failed on it
        raise InputError(p, f"cannot read: {type(exc).__name__}: {_first_line(exc)} ({DAMAGED})") from None


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else "(no message)"


def _own_format_failure(p: Path):
    """(format name, exception) of the first SurfaceTopography reader whose format the file
    claims (its magic bytes say so, or its suffix is the reader's) and which fails on it;
    None if no reader claims it."""
    from SurfaceTopography.IO import readers
    from SurfaceTopography.IO.Reader import MagicMatch

    try:
        with open(p, "rb") as fh:
            magic = fh.read(4096)
    except OSError:
        return None
    suffix = p.suffix.lower().lstrip(".")
    claims = [r for r in readers if _magic(r, magic) == MagicMatch.YES]
    claims += [r for r in readers if r not in claims and _magic(r, magic) != MagicMatch.NO and (
        suffix in getattr(r, "_file_extensions", ()) or r.__name__ in SUFFIX_READERS.get(suffix, ()))]
    for reader in claims:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                reader(str(p)).topography()
        except Exception as exc:  # the failure of the reader of the file's own format
            return getattr(reader, "_name", reader.__name__), exc
    return None


def _magic(reader, magic: bytes):
    try:
        return reader.can_read(magic)
    except Exception:
        return None


def _channel(reader, p: Path, channel: str | None):
    names = [ch.name for ch in reader.channels]
    if channel is None:
        return reader.default_channel
    matches = [ch for ch in reader.channels if ch.name == channel]
    if not matches:
        raise InputError(p, f"no channel {channel!r}; the file has: {', '.join(map(str, names))}")
    return matches[0]


def _read_instrument(p: Path, kind: str, unit, spacing, channel, key) -> Measurement:
    """An instrument file (or a text export in any of `asperity.io.inputs.ENCODINGS`)
    through SurfaceTopography."""
    with _utf8(p) as source:
        reader = _open(p, source)
        return _read_channel(reader, p, kind, unit, spacing, channel, key)


def _read_channel(reader, p: Path, kind: str, unit, spacing, channel, key) -> Measurement:
    try:
        ch = _channel(reader, p, channel)
    except InputError:
        raise
    except Exception as exc:  # a reader that fails on its metadata
        raise InputError(p, f"cannot read its channels: {type(exc).__name__}: {_first_line(exc)} "
                            f"({DAMAGED})") from None
    file_kind = KINDS.get(ch.dim)
    if file_kind != kind:
        raise InputError(p, f"holds a {file_kind or f'{ch.dim}-D data set'} (channel {ch.name!r}); "
                            f"name it under surface.{file_kind or kind} in the scene, not {key}")
    file_unit = known_length_unit(ch.unit) if isinstance(ch.unit, str) else None
    if isinstance(ch.unit, tuple):
        raise InputError(p, f"channel {ch.name!r} holds no heights (its units are {ch.unit!r}); "
                            f"choose a height channel as {key}.channel")
    notes = []
    if unit is None and file_unit is None:
        if ch.unit is not None:
            raise InputError(p, f"the file's length unit {ch.unit!r} is not one asperity knows; "
                                f"give the unit of its numbers as {key}.unit")
        raise _unit_error(p, key)
    if unit is not None and file_unit is not None and unit != file_unit:
        notes.append(f"length unit {unit} from the scene ({key}.unit) overrides the file's {file_unit}")
    elif unit is not None and file_unit is None:
        notes.append(f"length unit {unit} from the scene ({key}.unit); the file states none")
    else:
        notes.append(f"length unit {file_unit} from the file")
    use_unit = unit or file_unit
    kwargs = {}
    if ch.unit is None:
        kwargs["unit"] = use_unit
    sized = ch.physical_sizes is not None
    if not sized:
        if spacing is None:
            raise InputError(p, f"the file states no physical size; give the spacing in the scene as "
                                f"{key}.spacing")
        kwargs["physical_sizes"] = tuple(spacing / length_scale(use_unit) * n for n in ch.nb_grid_pts)
    try:
        topo = reader.topography(channel_index=ch.index, **kwargs)
        if not topo.is_uniform:
            raise InputError(p, "the profile is not uniformly sampled; resample it to uniform spacing")
        heights = topo.heights()
        pixel = np.atleast_1d(np.asarray(topo.pixel_size, dtype=np.float64))
    except InputError:
        raise
    except Exception as exc:
        raise InputError(p, f"cannot read channel {ch.name!r}: {type(exc).__name__}: {_first_line(exc)} "
                            f"({DAMAGED})") from None
    # the numbers ST returns are in topo.unit; reinterpret them in the scene's unit where it overrides
    scale = length_scale(use_unit)
    undefined = np.ma.getmaskarray(heights)
    z = np.ma.getdata(heights).astype(np.float64) * scale
    z[undefined] = np.nan
    steps = pixel * scale
    if spacing is not None and sized:
        notes.append(f"spacing {spacing:.6g} m from the scene ({key}.spacing) overrides the file's "
                     f"{steps[0]:.6g} m")
        steps = np.full(steps.shape, float(spacing))
    elif spacing is not None:
        notes.append(f"spacing {spacing:.6g} m from the scene ({key}.spacing); the file states none")
    else:
        notes.append(f"spacing {steps[0]:.6g} m from the file")
    if kind == "map":  # ST: heights[i, j] = z(x_i, y_j); here z[i, j] = z(x_j, y_i)
        z, undefined = z.T, undefined.T
        dx, dy = float(steps[0]), float(steps[1])
    else:
        dx, dy = float(steps[0]), None
    defined = ~undefined
    if not defined.any():
        raise InputError(p, f"every point of the {kind} is undefined: there is nothing to measure")
    return Measurement(str(p), kind, np.ascontiguousarray(z), np.ascontiguousarray(defined), dx, dy,
                       use_unit, f"SurfaceTopography {type(reader).__name__}", channel=str(ch.name),
                       notes=notes)


def describe_file(path) -> dict:
    """What a file holds, from its metadata, without reading the heights: kind, unit (or None),
    points, spacing in the file's unit (or None), channel, reader.  For `asperity new-scene`
    (which then reads the whole file with `read_measurement`)."""
    p = Path(path)
    if not p.exists():
        raise InputError(p, "no such file")
    suffix = p.suffix.lower()
    if suffix in (".npy", ".nc") or suffix in OWN_TEXT:
        try:
            return _describe_own(p)
        except InputError as err:
            if suffix not in OWN_TEXT or not _instrument_text(err):
                raise
            own = err
        try:
            found = _describe_instrument(p)
            if found["unit"] is None:  # a unit only the header states (asperity's reader reads it)
                stated = text_header(p)[1]
                found["unit"] = stated.get("z") or stated.get("any")
            return found
        except InputError:
            try:
                return _describe_own(p, header=True)
            except InputError:
                raise own from None
    return _describe_instrument(p)


def _describe_instrument(p: Path) -> dict:
    with _utf8(p) as source:
        reader = _open(p, source)
        try:
            ch = reader.default_channel
            unit = known_length_unit(ch.unit) if isinstance(ch.unit, str) else None
            sizes = ch.physical_sizes
            spacing = None if sizes is None else float(sizes[0]) / ch.nb_grid_pts[0]
            points = tuple(int(n) for n in ch.nb_grid_pts)
        except Exception as exc:  # a reader that fails on its metadata
            raise InputError(p, f"cannot read its metadata: {type(exc).__name__}: {_first_line(exc)} "
                                f"({DAMAGED})") from None
    return {"kind": KINDS.get(ch.dim), "unit": unit, "points": points, "spacing": spacing,
            "channel": str(ch.name), "reader": type(reader).__name__}


def _describe_own(p: Path, header: bool = False) -> dict:
    suffix = p.suffix.lower()
    if suffix == ".npy":
        try:
            a = np.load(p, mmap_mode="r", allow_pickle=False)
        except (OSError, ValueError) as exc:
            raise InputError(p, f"cannot read as .npy: {exc}") from None
        return {"kind": KINDS.get(a.ndim), "unit": None, "points": tuple(a.shape), "spacing": None,
                "channel": None, "reader": "asperity .npy"}
    if suffix == ".nc":  # the unit and the spacing where the file states them, else None
        unit = spacing = None
        try:
            z, dx, _ = read_map(p, spacing=None, length_unit=None)
            unit, spacing = "m", dx
        except InputError as err:
            if "states no length unit" not in err.reason and "pass spacing" not in err.reason:
                raise
            z, dx, _ = read_map(p, spacing=1.0, length_unit="m")
        return {"kind": "map", "unit": unit, "points": z.shape, "spacing": spacing, "channel": None,
                "reader": "asperity netCDF"}
    stated = text_header(p)[1] if header else {}
    unit = stated.get("z") or stated.get("any")
    x_unit = stated.get("x") or stated.get("any") or unit
    reader = "asperity text export" if header else "asperity text"
    try:  # a text table: one or two columns are a profile (z or x, z), more a map
        z, dx = read_profile(p, spacing=None, length_unit="m", header=header)
        if x_unit is not None and x_unit != unit:  # the spacing in the heights' unit
            dx *= length_scale(x_unit) / length_scale(unit)
        return {"kind": "profile", "unit": unit, "points": (z.size,), "spacing": dx, "channel": None,
                "reader": reader}
    except InputError as err:
        if "one column of heights" in err.reason:
            z, _ = read_profile(p, spacing=1.0, length_unit="m", header=header)
            return {"kind": "profile", "unit": unit, "points": (z.size,), "spacing": None,
                    "channel": None, "reader": reader}
        if "a profile has 1 column" not in err.reason:
            raise
    z, _, _ = read_map(p, spacing=1.0, length_unit="m", header=header)
    return {"kind": "map", "unit": unit, "points": z.shape, "spacing": None, "channel": None,
            "reader": reader}
