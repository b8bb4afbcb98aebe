"""The ``asperity`` command: browse a results folder, or start a scene from a measured surface.

    asperity show results/greenwood_williamson           every file: variables, dims, headline
                                                         numbers, where the interface is valid
                                                         and what its validity did not check
    asperity show results/greenwood_williamson/interface.nc --var nominal_pressure
                                                         one variable as a table
    asperity show FILE.nc --var nominal_pressure --csv   the same as CSV (with `valid`), full precision
    asperity new-scene data/topographies/mi-1.mi [NAME] --material steel
                                                         config/scenes/NAME.yaml for the file,
                                                         and the command that runs it
    asperity check config/scenes/NAME.yaml               a scene checked as the workflow will
    asperity --version

A file (or figure) written by another version of a stage's code than this one
(`asperity.versions`) is flagged with ``!``: `snakemake` computes it again.  Every
error a user can cause is one line, ``asperity: error: <file>: <key or byte>: <what>
(<likely fix>)``, and exit status 2.
"""

from __future__ import annotations

import argparse
import csv
import io
import os
import sys
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from asperity import __version__, units, versions
from asperity.homogenize.validity import valid_ranges
from asperity.io.figures import figure_version
from asperity.io.netcdf import read_dataset
from asperity.new_scene import UserError, material_section, new_scene, workflow_root


def _headline(var: xr.DataArray) -> str:
    values = np.asarray(var.values)
    units_ = var.attrs.get("units", "")
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
        return f"{finite.item():.6g} {units_}".strip()
    return f"{finite.min():.4g} .. {finite.max():.4g} {units_}".strip()


def version_note(written: str | None) -> str | None:
    """Why a file whose code version is `written` (None: it records none) is out of date,
    or None if it is not (`asperity.versions.stale`)."""
    if written is None:
        return "written before asperity recorded the version of its code: computed again by snakemake"
    stale = versions.stale(written)
    return None if stale is None else f"{stale}: computed again by snakemake"


def _open_result(path: Path) -> xr.Dataset:
    """A result file, or a UserError naming it."""
    try:
        return read_dataset(path)
    except FileNotFoundError:
        raise UserError(f"{path}: no such result file") from None
    except Exception as exc:  # netCDF4 and xarray raise OSError, ValueError, RuntimeError...
        first = (str(exc).strip().splitlines() or [""])[0]
        raise UserError(f"{path}: not a netCDF result file ({type(exc).__name__}: {first})") from None


def caveats(ds: xr.Dataset) -> list[str]:
    """What the validity of an interface (`asperity.homogenize.validity`) holds beside
    ``valid: N of M``: the limits it applied and what it did not check (``not_checked``)."""
    if "valid" not in ds:
        return []
    a = ds["valid"].attrs
    lines = []
    limits = {k[len("limit_"):]: v for k, v in a.items() if k.startswith("limit_")}
    if limits:
        lines.append("limits: " + ", ".join(f"{k} <= {float(v):.3g}" for k, v in limits.items()))
    unchecked = str(a.get("not_checked", "none"))
    if unchecked and unchecked != "none":
        lines += ["not checked:"] + [f"  - {item}" for item in unchecked.split("; ")]
    return lines


def describe(path: Path) -> str:
    """Variables, dimensions and headline numbers of one result file, where its interface
    is valid and what that did not check, and a note if another version of its stage's
    code wrote it."""
    ds = _open_result(path)
    dims = ", ".join(f"{k}={v}" for k, v in ds.sizes.items()) or "scalars"
    lines = [f"{path}  [{dims}]  {ds.attrs.get('title', '')}"]
    note = version_note(ds.attrs.get(versions.ATTRIBUTE))
    if note and str(ds.attrs.get("source", "")).startswith("asperity"):
        lines.append(f"  ! {note}")
    numbers = {k: v for k, v in ds.attrs.items()
               if isinstance(v, (int, float, np.number)) and not isinstance(v, bool)}
    if numbers:  # the file's headline numbers (FE cost, errors against closed forms, ...)
        lines.append("  " + ", ".join(f"{k} = {float(v):.6g}" for k, v in numbers.items()))
    lines += [f"  {line}" for line in valid_ranges(ds)]  # where the interface holds
    lines += [f"  {line}" for line in caveats(ds)]  # and what that did not check
    lines += [f"  {line}" for line in recommendations(ds)]  # a reference's closest route
    for name, var in ds.data_vars.items():
        shape = f"({', '.join(var.dims)})" if var.dims else ""
        lines.append(f"  {name:<32s}{shape:<34s}{_headline(var)}")
        long_name = var.attrs.get("long_name")
        if long_name:
            lines.append(f"  {'':<32s}{long_name}")
    return "\n".join(lines)


def recommendations(ds: xr.Dataset) -> list[str]:
    """For a reference's comparison.nc: per separation, the route closest to the boundary
    elements and its larger error, or why none is named; where even the closest is off by
    more than the scene's `agreement`, that no route holds there and that the boundary
    elements (a route of their own) are the interface law."""
    if "recommended_route" not in ds:
        return []
    sigma = float(ds.attrs.get("sigma", np.nan))
    agreement = float(ds.attrs.get("agreement", np.nan))
    lines = ["recommended route (closest to the elastic boundary elements):"]
    for h, route, error, resolved in zip(ds["separation"].values, ds["recommended_route"].values,
                                         ds["recommended_error"].values, ds["reference_resolved"].values):
        where = f"separation {h:.4g} m" + (f" ({h / sigma:.3g} sigma)" if np.isfinite(sigma) else "")
        if route and error > agreement:
            lines.append(f"  {where}: {route}, off by {100 * error:.3g} %: no route holds within the "
                         f"agreement of {100 * agreement:.3g} %; the law here is the boundary "
                         "elements' (route: {kind: boundary_elements})")
        elif route:
            lines.append(f"  {where}: {route}, within {100 * error:.3g} %")
        else:
            lines.append(f"  {where}: none ({'no route defined' if resolved else 'the boundary elements do not resolve the contact'})")
    return lines


def _variable(ds: xr.Dataset, path: Path, name: str) -> xr.DataArray:
    if name not in ds:
        raise UserError(f"{path}: {name}: no such variable (it has: {', '.join(ds.data_vars)})")
    return ds[name]


def table(path: Path, name: str) -> str:
    """One variable of a result file as a text table over its dimensions."""
    ds = _open_result(path)
    var = _variable(ds, path, name)
    header = f"# {name} [{var.attrs.get('units', '')}]: {var.attrs.get('long_name', '')}"
    if var.ndim == 0:
        return f"{header}\n{var.values.item()}"
    frame = var.to_dataframe(name=name)[[name]]
    return f"{header}\n{frame.to_string()}"


def csv_table(path: Path, name: str) -> str:
    """One variable of a result file as CSV: a column per coordinate of its dimensions, the
    variable, and ``valid`` (1 or 0) where the file has it on those dimensions; the header
    names each column with its unit, ``name [unit]``; numbers with 17 significant digits
    (a float64 reads back exactly)."""
    ds = _open_result(path)
    var = _variable(ds, path, name)
    names = [name]
    if "valid" in ds and name != "valid" and set(ds["valid"].dims) <= set(var.dims):
        names.append("valid")
    if var.ndim == 0:
        frame = ds[names].expand_dims("row").to_dataframe().reset_index(drop=True)
    else:
        frame = ds[names].to_dataframe().reset_index()
    frame = frame[[c for c in frame.columns if c in var.dims or c in var.coords or c in names]]
    for column in frame.columns:
        if frame[column].dtype == bool:
            frame[column] = frame[column].astype(int)
    labels = {}
    for column in frame.columns:
        unit = ds[column].attrs.get("units", "") if column in ds.variables else ""
        labels[column] = f"{column} [{unit}]" if unit else str(column)
    out = io.StringIO()
    frame.rename(columns=labels).to_csv(out, index=False, float_format="%.17g",
                                        quoting=csv.QUOTE_MINIMAL, lineterminator="\n")
    return out.getvalue()


# --------------------------------------------------------------------------
# asperity check SCENE.yaml
# --------------------------------------------------------------------------

def check_scene_file(path: Path) -> str:
    """Check a scene file as the workflow will, before it runs: YAML, the schema of the
    workflow folder (config/schema.yaml) and `asperity.scene.check_scene`; returns what was
    checked, raises a one-line error naming the file and the key."""
    from asperity.scene.checks import check_scene
    from asperity.scene.files import read_scene

    if not path.is_file():
        raise UserError(f"{path}: no such scene file")
    scene = read_scene(path)
    root = workflow_root(path.parent)
    schema = None if root is None else root / "config" / "schema.yaml"
    checked = "YAML, scene checks"
    if schema is not None and schema.is_file():
        _schema_check(path, scene, schema)
        checked = f"YAML, {schema}, scene checks"
    check_scene(scene, path)
    return checked


def _schema_check(path: Path, scene: dict, schema: Path) -> None:
    from asperity.scene.checks import text_number_hint

    try:
        from jsonschema import Draft202012Validator
        from jsonschema.exceptions import best_match
    except ImportError:  # installed without the workflow's dependencies
        return
    name = path.stem
    config = {"scenes": [name], "accuracy": "standard", "results": "results",
              "scene_dir": str(path.parent), "scene_definitions": {name: scene}}
    error = best_match(Draft202012Validator(yaml.safe_load(schema.read_text())).iter_errors(config))
    if error is None:
        return
    key = ".".join(str(k) for k in list(error.absolute_path)[2:]) or "(top level)"
    raise UserError(f"{path}: {key}: {error.message}{text_number_hint(error.instance)}")


# --------------------------------------------------------------------------
# the command line
# --------------------------------------------------------------------------


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="asperity", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"asperity {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    show = sub.add_parser("show", help="list a results folder or file, or print one variable")
    show.add_argument("path", type=Path, help="a results folder (results/<scene>) or a .nc file")
    show.add_argument("--var", help="print this variable as a table (with a .nc file)")
    show.add_argument("--csv", action="store_true",
                      help="with --var: write the variable, its coordinates and `valid` as CSV to stdout")
    check = sub.add_parser("check", help="check scene files as the workflow will, before a run",
                           description="Check each scene file: YAML, the workflow's schema "
                                       "(config/schema.yaml) and the checks the schema cannot make "
                                       "(an FE asperity's geometry, sizes that say a unit is wrong).")
    check.add_argument("scenes", type=Path, nargs="+", help="config/scenes/NAME.yaml ...")
    new = sub.add_parser(
        "new-scene", help="write a scene for a measured profile or map file",
        description="Write config/scenes/NAME.yaml (in the workflow folder, where the Snakefile is) "
                    "for a measured profile or height map, read whole: units and spacing from the "
                    "file, tilt removal, the population the heights allow (Nayak for a profile, "
                    "the map's own peaks for a map; non-Gaussian heights and a dominating form are "
                    "noted), elastic Hertz asperities and the material given; print the command "
                    "that runs it. The material is required: --material NAME, or --youngs-modulus "
                    "and --poisson (and --yield-stress, --hardness), in the scene's pressure unit "
                    "(--pressure-unit, MPa by default).")
    new.add_argument("file", type=Path, help="the measured file (text, .npy, netCDF, or an instrument format)")
    new.add_argument("name", nargs="?", help="scene name (default: from the file name)")
    new.add_argument("--unit", choices=["m", "cm", "mm", "um", "nm"],
                     help="the unit of the file's numbers, where the file states none (or to override it)")
    new.add_argument("--spacing", type=float, help="the sampling interval in um, where the file states none")
    new.add_argument("--material", help="a named material: steel, aluminum, copper, titanium, glass "
                                        "(E, nu, yield stress and their sources in the scene's comment)")
    new.add_argument("--youngs-modulus", type=float, help="Young's modulus E, in the pressure unit (MPa by default)")
    new.add_argument("--poisson", type=float, help="Poisson's ratio nu")
    new.add_argument("--yield-stress", type=float, help="yield stress, in the pressure unit (MPa by default)")
    new.add_argument("--hardness", type=float, help="indentation hardness H, in the pressure unit (MPa by default)")
    new.add_argument("--pressure-unit", default="MPa", choices=[u for u in units.PRESSURE if u != "1"],
                     help="the scene's pressure unit (default MPa)")
    new.add_argument("--scene-dir", type=Path,
                     help="default: config/scenes of the workflow folder (where the Snakefile is)")
    new.add_argument("--force", action="store_true", help="overwrite an existing scene file")
    return parser


def _show(args) -> int:
    path: Path = args.path
    if not path.exists():
        raise UserError(f"{path}: no such file or folder")
    if args.csv and not args.var:
        raise UserError(f"{path}: --csv: give the variable with --var")
    if args.var:
        if path.is_dir():
            raise UserError(f"{path}: --var: needs a .nc file, not a folder")
        if args.csv:
            sys.stdout.write(csv_table(path, args.var))
        else:
            print(table(path, args.var))
        return 0
    files = [path] if path.is_file() else sorted(path.glob("*.nc"))
    if not files:
        raise UserError(f"{path}: no .nc files")
    print("\n\n".join(describe(f) for f in files))
    for figure in sorted(path.glob("figures/*.png")) if path.is_dir() else []:
        note = version_note(figure_version(figure))
        if note:
            print(f"! {figure}: {note}")
    plan = path / "plan.nc"
    if path.is_dir() and plan.exists():  # the scene's FE jobs, in the folder shared by all scenes
        ds = _open_result(plan)
        keys = set(ds["key"].values[ds["job"].values.astype(bool)])
        done = [path.parent / "samples" / f"{k}.nc" for k in keys]
        done = [f for f in done if f.exists()]
        print(f"\n{len(done)} of {len(keys)} sample files of this scene in {path.parent / 'samples'}")
        for f in done:
            note = version_note(_open_result(f).attrs.get(versions.ATTRIBUTE))
            if note:
                print(f"! {f}: {note}")
    return 0


def _run(argv: list[str] | None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command == "show":
        return _show(args)
    if args.command == "check":
        for scene in args.scenes:
            print(f"ok: {scene} ({check_scene_file(scene)})")
        return 0
    material = material_section(args.material, args.youngs_modulus, args.poisson, args.yield_stress,
                                args.hardness, args.pressure_unit)
    target, command, notes = new_scene(args.file, args.name, args.scene_dir, args.unit, args.spacing,
                                       args.force, material, args.pressure_unit)
    for note in notes:
        print(f"note: {note}")
    print(f"wrote {target} ({material[1]}); run it with\n\n    {command}\n\n"
          f"(results in results/{target.stem}/: surface.nc, interface.nc and figures/)")
    return 0


def _fail(message: str) -> int:
    one_line = " ".join(str(message).split())
    print(f"asperity: error: {one_line}", file=sys.stderr)
    return 2


def main(argv: list[str] | None = None) -> int:
    """The ``asperity`` command. Every error a user can cause (a file, a scene, an option)
    is one line on stderr, ``asperity: error: <file>: <key or byte>: <what> (<likely fix>)``,
    and exit status 2, without a traceback (ASPERITY_TRACEBACK=1 shows it)."""
    from asperity.io.inputs import InputError
    from asperity.scene.checks import SceneError

    try:
        return _run(argv)
    except (UserError, InputError, SceneError) as err:
        if os.environ.get("ASPERITY_TRACEBACK"):
            raise
        return _fail(str(err))
    except OSError as err:
        if os.environ.get("ASPERITY_TRACEBACK"):
            raise
        where = f"{err.filename}: " if err.filename else ""
        return _fail(f"{where}{err.strerror or err}")
    except Exception as err:  # a bug, not a user's error: still one line, with how to see more
        if os.environ.get("ASPERITY_TRACEBACK"):
            raise
        first = (str(err).strip().splitlines() or [""])[0]
        return _fail(f"{type(err).__name__}: {first} (unexpected: rerun with ASPERITY_TRACEBACK=1 "
                     f"and report the traceback)")


if __name__ == "__main__":
    sys.exit(main())
