"""The ``asperity`` command: browse a results folder.

    asperity show results/greenwood_williamson           every file: variables, dims, headline numbers
    asperity show results/greenwood_williamson/interface.nc --var nominal_pressure
                                                         one variable as a table

A file (or figure) written by another version of a stage's code than this one
(`asperity.versions`) is flagged with ``!``: `snakemake` computes it again.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from asperity import versions
from asperity.io.figures import figure_version
from asperity.io.netcdf import read_dataset


def _headline(var: xr.DataArray) -> str:
    values = np.asarray(var.values)
    units = var.attrs.get("units", "")
    if values.dtype.kind in "SUO":
        return f"{values.size} strings"
    if values.size == 0:
        return "empty"
    if values.dtype == bool:
        return f"{int(values.sum())} of {values.size} true"
    finite = values[np.isfinite(values)] if values.dtype.kind == "f" else values
    if finite.size == 0:
        return "all NaN"
    if values.size == 1:
        return f"{finite.item():.6g} {units}".strip()
    return f"{finite.min():.4g} .. {finite.max():.4g} {units}".strip()


def version_note(written: str | None) -> str | None:
    """Why a file whose code version is `written` (None: it records none) is out of date,
    or None if it is not (`asperity.versions.stale`)."""
    if written is None:
        return "written before asperity recorded the version of its code: computed again by snakemake"
    stale = versions.stale(written)
    return None if stale is None else f"{stale}: computed again by snakemake"


def describe(path: Path) -> str:
    """Variables, dimensions and headline numbers of one result file, and a note if
    another version of its stage's code wrote it."""
    ds = read_dataset(path)
    dims = ", ".join(f"{k}={v}" for k, v in ds.sizes.items()) or "scalars"
    lines = [f"{path}  [{dims}]  {ds.attrs.get('title', '')}"]
    note = version_note(ds.attrs.get(versions.ATTRIBUTE))
    if note and str(ds.attrs.get("source", "")).startswith("asperity"):
        lines.append(f"  ! {note}")
    numbers = {k: v for k, v in ds.attrs.items()
               if isinstance(v, (int, float, np.number)) and not isinstance(v, bool)}
    if numbers:  # the file's headline numbers (FE cost, errors against closed forms, ...)
        lines.append("  " + ", ".join(f"{k} = {float(v):.6g}" for k, v in numbers.items()))
    for name, var in ds.data_vars.items():
        shape = f"({', '.join(var.dims)})" if var.dims else ""
        lines.append(f"  {name:<32s}{shape:<34s}{_headline(var)}")
        long_name = var.attrs.get("long_name")
        if long_name:
            lines.append(f"  {'':<32s}{long_name}")
    return "\n".join(lines)


def table(path: Path, name: str) -> str:
    """One variable of a result file as a text table over its dimensions."""
    ds = read_dataset(path)
    if name not in ds:
        known = ", ".join(ds.data_vars)
        raise SystemExit(f"{path}: no variable {name!r}; it has: {known}")
    var = ds[name]
    header = f"# {name} [{var.attrs.get('units', '')}]: {var.attrs.get('long_name', '')}"
    if var.ndim == 0:
        return f"{header}\n{var.values.item()}"
    frame = var.to_dataframe(name=name)[[name]]
    return f"{header}\n{frame.to_string()}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="asperity", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    show = sub.add_parser("show", help="list a results folder or file, or print one variable")
    show.add_argument("path", type=Path, help="a results folder (results/<scene>) or a .nc file")
    show.add_argument("--var", help="print this variable as a table (with a .nc file)")
    args = parser.parse_args(argv)

    path: Path = args.path
    if not path.exists():
        parser.error(f"{path}: no such file or folder")
    if args.var:
        if path.is_dir():
            parser.error("--var needs a .nc file, not a folder")
        print(table(path, args.var))
        return 0
    files = [path] if path.is_file() else sorted(path.glob("*.nc"))
    if not files:
        parser.error(f"{path}: no .nc files")
    print("\n\n".join(describe(f) for f in files))
    for figure in sorted(path.glob("figures/*.png")) if path.is_dir() else []:
        note = version_note(figure_version(figure))
        if note:
            print(f"! {figure}: {note}")
    plan = path / "plan.nc"
    if path.is_dir() and plan.exists():  # the scene's FE jobs, in the folder shared by all scenes
        ds = read_dataset(plan)
        keys = set(ds["key"].values[ds["job"].values.astype(bool)])
        done = [path.parent / "samples" / f"{k}.nc" for k in keys]
        done = [f for f in done if f.exists()]
        print(f"\n{len(done)} of {len(keys)} sample files of this scene in {path.parent / 'samples'}")
        for f in done:
            note = version_note(read_dataset(f).attrs.get(versions.ATTRIBUTE))
            if note:
                print(f"! {f}: {note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
