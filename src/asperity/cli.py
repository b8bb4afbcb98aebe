"""The ``asperity`` command: browse a results folder, or start a scene from a measured surface.

    asperity show results/greenwood_williamson           every file: variables, dims, headline numbers
    asperity show results/greenwood_williamson/interface.nc --var nominal_pressure
                                                         one variable as a table
    asperity new-scene data/topographies/mi-1.mi [NAME]  config/scenes/NAME.yaml for the file,
                                                         and the command that runs it

A file (or figure) written by another version of a stage's code than this one
(`asperity.versions`) is flagged with ``!``: `snakemake` computes it again.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from asperity import versions
from asperity.io.figures import figure_version
from asperity.homogenize.validity import valid_ranges
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
    lines += [f"  {line}" for line in valid_ranges(ds)]  # where the interface holds
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


# --------------------------------------------------------------------------
# asperity new-scene FILE [NAME]
# --------------------------------------------------------------------------

#: what the written scene says about a profile's and a map's population (report 2.4.1, 2.4.3)
_POPULATION = {
    "profile": ("population:\n"
                "  density: nayak          # Nayak/Francis peaks of a Gaussian isotropic surface (2.4.1)\n"
                "  samples: {height: 11, curvature: 21, interference: 241}\n"),
    "map": ("population:\n"
            "  density: sampled        # the map's own peaks, eight-neighbour rule (2.4.3)\n"
            "  histogram_bins: [20, 20]\n"),
}
_HOMOGENIZATION = {
    "profile": ("homogenization:\n"
                "  rule: gauss             # 2 x 2 Gauss points per cell of the (height, curvature) plane (2.5)\n"
                "  cells: [60, 40]\n"),
    "map": ("homogenization:\n"
            "  rule: peaks             # the expectation over the map's actual peaks (2.5.3)\n"),
}


def scene_name(path: Path) -> str:
    """A scene name from a file name: lower case, letters, digits and underscores."""
    name = re.sub(r"[^a-z0-9]+", "_", path.stem.lower()).strip("_")
    return name if name and name[0].isalpha() else f"surface_{name}"


def scene_text(path: Path, info: dict, unit: str | None, spacing: float | None) -> str:
    """The YAML of a scene for the measured file `path` (`info`: what its metadata says)."""
    kind = info["kind"]
    source = [f"    file: {path.as_posix()}"]
    if info["unit"] is None:
        source.append(f"    unit: {unit}                # the file states no unit: given to new-scene")
    elif unit is not None and unit != info["unit"]:
        source.append(f"    unit: {unit}                # overrides the file's {info['unit']}")
    if spacing is not None:
        source.append(f"    spacing: {spacing:g}           # in um; overrides the file's")
    points = " x ".join(str(n) for n in info["points"])
    where = (f"{info['reader']}, channel {info['channel']!r}" if info.get("channel")
             else info["reader"])
    file_unit = unit or info["unit"]
    return (
        f"title: Measured {kind} {path.name} with elastic Hertz asperities\n"
        f"report: \"2.3 statistics, {'2.4.1' if kind == 'profile' else '2.4.3'} peaks, 6.1 Hertz, 2.5 expectation\"\n"
        f"# Written by: asperity new-scene {path.as_posix()}\n"
        f"# The {kind} of {path.name}: {points} points, read by {where}; its numbers in {file_unit}.\n"
        f"# Its least-squares tilt is removed before the statistics (surface.form); add\n"
        f"# surface.filter: {{lambda_c: ...}} (um) to keep only the roughness shorter than a cut-off\n"
        f"# wavelength. Every asperity is an elastic Hertz tip.\n"
        f"units: {{length: um, pressure: MPa}}\n"
        f"surface:\n"
        f"  {kind}:\n" + "\n".join(source) + "\n"
        f"  form: tilt\n"
        + _POPULATION[kind]
        + "asperity:\n"
        "  model: hertz            # or {model: fe, geometry: sphere | paraboloid | cosine}\n"
        "material:                 # EDIT: a placeholder (steel); give your material's constants, or for\n"
        "  youngs_modulus: 210000.0  # two rough bodies the sum surface and the effective modulus\n"
        "  poisson: 0.3\n"
        + _HOMOGENIZATION[kind]
        + "  separations: {start: 0.0, stop: 3.0, count: 31, unit: sigma}\n"
    )


def new_scene(file: Path, name: str | None, scene_dir: Path, unit: str | None, spacing: float | None,
              force: bool) -> tuple[Path, str]:
    """Write scene_dir/NAME.yaml for a measured file; returns its path and the command that runs it."""
    from asperity.io.inputs import InputError
    from asperity.io.topography import describe_file

    if not file.exists():
        raise SystemExit(f"{file}: no such file")
    try:
        info = describe_file(file)
    except InputError as err:
        raise SystemExit(str(err)) from None
    if info["kind"] not in ("profile", "map"):
        raise SystemExit(f"{file}: holds neither a profile nor a map ({info['points']} points)")
    if info["unit"] is None and unit is None:
        raise SystemExit(f"{file}: the file states no length unit; give the unit of its numbers with "
                         f"--unit (m, cm, mm, um, nm)")
    if info["spacing"] is None and spacing is None:
        raise SystemExit(f"{file}: the file states no spacing; give it with --spacing (in um)")
    name = name or scene_name(file)
    if not re.fullmatch(r"[a-z0-9_]+", name):
        raise SystemExit(f"scene name {name!r}: use lower-case letters, digits and underscores")
    target = scene_dir / f"{name}.yaml"
    if target.exists() and not force:
        raise SystemExit(f"{target} exists; choose another NAME or pass --force")
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_name(f".{target.name}.tmp")
    tmp.write_text(scene_text(file, info, unit, spacing))
    tmp.replace(target)
    command = f"snakemake --cores 2 --config 'scenes=[{name}]' studies=False"
    return target, command


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="asperity", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    show = sub.add_parser("show", help="list a results folder or file, or print one variable")
    show.add_argument("path", type=Path, help="a results folder (results/<scene>) or a .nc file")
    show.add_argument("--var", help="print this variable as a table (with a .nc file)")
    new = sub.add_parser("new-scene", help="write a scene for a measured profile or map file",
                         description="Write config/scenes/NAME.yaml for a measured profile or height map: "
                                     "units and spacing from the file, tilt removal, the population that "
                                     "fits a profile (Nayak) or a map (its peaks), elastic Hertz asperities "
                                     "and a placeholder material to edit; print the command that runs it.")
    new.add_argument("file", type=Path, help="the measured file (text, .npy, netCDF, or an instrument format)")
    new.add_argument("name", nargs="?", help="scene name (default: from the file name)")
    new.add_argument("--unit", choices=["m", "cm", "mm", "um", "nm"],
                     help="the unit of the file's numbers, where the file states none (or to override it)")
    new.add_argument("--spacing", type=float, help="the sampling interval in um, where the file states none")
    new.add_argument("--scene-dir", type=Path, default=Path("config/scenes"), help="default: config/scenes")
    new.add_argument("--force", action="store_true", help="overwrite an existing scene file")
    args = parser.parse_args(argv)

    if args.command == "new-scene":
        target, command = new_scene(args.file, args.name, args.scene_dir, args.unit, args.spacing, args.force)
        print(f"wrote {target}: edit its material (a placeholder), then run it with\n\n    {command}\n\n"
              f"(results in results/{target.stem}/: surface.nc, interface.nc and figures/)")
        return 0

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
