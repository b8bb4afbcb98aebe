"""Compare two results trees file by file: the same netCDF files, with the same variables,
dimensions and values (and, on request, attributes), timings aside.

    python benchmarks/compare_results.py RESULTS REFERENCE [--rtol 0] [--attributes]

`make compare-results REFERENCE=<folder>` compares results/ with REFERENCE bit for bit
(--rtol 0): what a refactoring must leave unchanged. Data variables and coordinates are
compared; variables and attributes that time a job (``wall_time``, ``cpu_time``, ...)
and the write date are not. Attributes are listed where they differ, and fail the
comparison only with --attributes (a new version of the code writes its version and
its filled-in configuration into them). Exit status 1 if a file is missing on either
side or a value differs. The workflow tests compare two runs with `differences`.
"""

from __future__ import annotations

import argparse
import glob
import re
import sys
from pathlib import Path

import numpy as np

#: what differs between two runs of the same jobs by nature: how long they took
TIMING = re.compile(r"(^|_)(wall|cpu)_time($|_)")
#: attributes that say when and by which version of the code a file was written
PROVENANCE = ("history", "source", "code_version", "config")


def nc_files(root: Path) -> list[str]:
    """The netCDF files under `root`, relative to it."""
    return sorted(str(Path(f).relative_to(root)) for f in glob.glob(f"{root}/**/*.nc", recursive=True))


def equal(a, b, rtol: float) -> bool:
    """Arrays (or attributes) of the same shape and values: floats to `rtol` relative
    (0: exactly, NaN equal to NaN), anything else exactly."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return False
    if a.dtype.kind in "fc" and b.dtype.kind in "fc":
        return bool(np.allclose(a, b, rtol=rtol, atol=0.0, equal_nan=True))
    return bool(np.array_equal(a, b))


def differences(got: Path, reference: Path, rtol: float = 0.0,
                attributes: bool = True) -> tuple[list[str], list[str], int]:
    """How the netCDF file `got` differs from `reference`: (differences of variables,
    dimensions and values; differences of attributes; the number of values compared).
    Timings are left out, and the write date always; with `attributes` False so are
    the provenance attributes (history, source, code version, config)."""
    import xarray as xr

    data, attrs = [], []
    compared = 0
    with xr.open_dataset(got, decode_times=False) as a, \
            xr.open_dataset(reference, decode_times=False) as b:
        if set(a.variables) != set(b.variables):
            data.append(f"variables: only here {sorted(set(a.variables) - set(b.variables))}, "
                        f"only in the reference {sorted(set(b.variables) - set(a.variables))}")
        for var in sorted(set(a.variables) & set(b.variables)):
            if a[var].dims != b[var].dims:
                data.append(f"{var}: dims {a[var].dims} != {b[var].dims}")
                continue
            if set(a[var].attrs) != set(b[var].attrs):
                attrs.append(f"{var}: attributes {sorted(set(a[var].attrs) ^ set(b[var].attrs))}")
            for key in set(a[var].attrs) & set(b[var].attrs):
                if not equal(a[var].attrs[key], b[var].attrs[key], rtol):
                    attrs.append(f"{var}.{key}")
            if TIMING.search(var):
                continue
            if not equal(a[var].values, b[var].values, rtol):
                data.append(f"{var}: values differ")
            compared += a[var].size
        skip = {"history"} | (set() if attributes else set(PROVENANCE))
        keys = {k for k in set(a.attrs) | set(b.attrs) if k not in skip and not TIMING.search(k)}
        for key in sorted(keys):
            if key not in a.attrs or key not in b.attrs:
                attrs.append(f"attribute {key}: only {'here' if key in a.attrs else 'in the reference'}")
            elif not equal(a.attrs[key], b.attrs[key], rtol):
                attrs.append(f"attribute {key}")
    return data, attrs, compared


def compare_trees(got: Path, reference: Path, rtol: float = 0.0, attributes: bool = False) -> bool:
    """Print how the trees differ; True if they hold the same files and values."""
    mine, theirs = set(nc_files(got)), set(nc_files(reference))
    ok = True
    for name in sorted(theirs - mine):
        print(f"MISSING {name}")
        ok = False
    for name in sorted(mine - theirs):
        print(f"EXTRA   {name}")
        ok = False
    values = files_with_attrs = 0
    for name in sorted(mine & theirs):
        data, attrs, compared = differences(got / name, reference / name, rtol, attributes)
        values += compared
        if data or (attributes and attrs):
            ok = False
            print(f"DIFFERS {name}: " + "; ".join(data + (attrs if attributes else [])))
        elif attrs:
            files_with_attrs += 1
            print(f"same    {name} (attributes differ: {', '.join(attrs)})")
    print(f"{len(mine & theirs)} files, {values} values compared "
          f"({'to rtol ' + format(rtol, 'g') if rtol else 'bit for bit'}), timings aside: "
          + ("the same" if ok else "DIFFERENT")
          + (f"; {files_with_attrs} files with other attributes" if files_with_attrs else ""))
    return ok


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", type=Path)
    parser.add_argument("reference", type=Path)
    parser.add_argument("--rtol", type=float, default=0.0, help="relative tolerance of floats (0: exact)")
    parser.add_argument("--attributes", action="store_true",
                        help="attributes must be the same too (provenance included)")
    args = parser.parse_args(argv)
    for folder in (args.results, args.reference):
        if not folder.is_dir():
            parser.error(f"{folder}: no such folder")
    return 0 if compare_trees(args.results, args.reference, args.rtol, args.attributes) else 1


if __name__ == "__main__":
    sys.exit(main())
