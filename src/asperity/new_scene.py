"""What ``asperity new-scene`` writes for a measured profile or map, and how it decides it.

``asperity new-scene FILE [NAME] --material steel`` reads the file whole (its unit and
spacing from the file's metadata, or from ``--unit`` and ``--spacing``) and writes
config/scenes/NAME.yaml in the workflow folder (where the Snakefile is: `workflow_root`):
the file, tilt removal, the population the heights allow -- Nayak's density for a profile
(2.4.1), the map's own peaks for a map (2.4.3) --, elastic Hertz asperities, the material
given (`material_section`: a named material and/or its constants) and the separations.
It judges the surface first (`assess_surface`): heights that are not Gaussian (skewness,
kurtosis), a removed tilt much larger than the roughness (`TILT_RATIO`) and a form that
dominates it (`FORM_SHARE`) are noted in the scene's comment (`surface_notes`), with a
cut-off of a fifth of the record (ISO 4288, `CUTOFFS_PER_LENGTH`) where a filter helps.
The scene is checked (`asperity.scene.check_scene`) before it is written; `new_scene`
returns the command that runs it.  Every error a user can cause is a `UserError`, which
the command line (`asperity.cli`) prints as one line.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import yaml

from asperity import units


class UserError(Exception):
    """What a user can change: printed as one line ``asperity: error: <file>: <key>: <what> (<fix>)``."""


#: a 2nd-degree polynomial that removes more than this share of the variance left after the
#: tilt is form (the curvature of the part), not roughness
FORM_SHARE = 0.5
#: a removed tilt whose rms exceeds this many rms roughnesses is noted
TILT_RATIO = 10.0
#: ISO 4288: the evaluation length of a profile is five cut-off wavelengths
CUTOFFS_PER_LENGTH = 5

#: what the written scene says about a profile's population (Gaussian: 2.4.1) and a map's (2.4.3)
_POPULATION = {
    "nayak": ("population:\n"
              "  density: nayak          # Nayak/Francis peaks of a Gaussian isotropic surface (2.4.1)\n"
              "  samples: {height: 11, curvature: 21, interference: 241}\n"),
    "sampled": ("population:\n"
                "  density: sampled        # the map's own peaks, eight-neighbour rule (2.4.3)\n"
                "  histogram_bins: [20, 20]\n"),
}
_HOMOGENIZATION = {
    "nayak": ("homogenization:\n"
              "  rule: gauss             # 2 x 2 Gauss points per cell of the (height, curvature) plane (2.5)\n"
              "  cells: [60, 40]\n"),
    "sampled": ("homogenization:\n"
                "  rule: peaks             # the expectation over the map's actual peaks (2.5.3)\n"),
}


def scene_name(path: Path) -> str:
    """A scene name from a file name: lower case, letters, digits and underscores."""
    name = re.sub(r"[^a-z0-9]+", "_", path.stem.lower()).strip("_")
    return name if name and name[0].isalpha() else f"surface_{name}"


def workflow_root(start: Path | None = None) -> Path | None:
    """The workflow folder (where the Snakefile is, and `snakemake` runs): the first of
    `start` (default the current folder) and its parents that holds one, else the
    checkout this package is installed from, else None."""
    here = (start or Path.cwd()).resolve()
    for folder in (here, *here.parents):
        if (folder / "Snakefile").is_file():
            return folder
    checkout = Path(__file__).resolve().parents[2]
    return checkout if (checkout / "Snakefile").is_file() else None


def scene_path(file: Path, root: Path | None) -> str:
    """How a scene names `file`: relative to the workflow folder `root` when the file is
    inside it (the workflow runs there), else absolute; never relative to the shell's folder."""
    resolved = file.resolve()
    if root is not None:
        try:
            return resolved.relative_to(root).as_posix()
        except ValueError:
            pass
    return resolved.as_posix()


def material_section(name: str | None, youngs_modulus: float | None, poisson: float | None,
                     yield_stress: float | None, hardness: float | None,
                     pressure_unit: str) -> tuple[dict, str]:
    """The ``material`` section (values in `pressure_unit`) from `--material NAME` and the
    constants given (which override the named material's), and where its numbers come from.
    Refused (UserError, SceneError naming the option): no material, an unknown name, a
    modulus without a Poisson's ratio, a size that says the unit is wrong
    (`asperity.scene.checks.check_material`)."""
    from asperity.scene.checks import SceneError, check_material
    from asperity.scene.materials import named_materials

    p = units.pressure_scale(pressure_unit)
    section: dict[str, float] = {}
    source = "given to asperity new-scene"
    if name is not None:
        table = named_materials()
        if name not in table:
            raise UserError(f"--material: unknown material {name!r} (known: {', '.join(table)})")
        known = table[name]
        section = {"youngs_modulus": known.youngs_modulus / p, "poisson": known.poisson}
        if known.yield_stress is not None:
            section["yield_stress"] = known.yield_stress / p
        source = f"{name}: {known.label} ({known.source})"
    given = {"youngs_modulus": youngs_modulus, "poisson": poisson, "yield_stress": yield_stress,
             "hardness": hardness}
    section.update({k: float(v) for k, v in given.items() if v is not None})
    if not section:
        raise UserError(f"--material: no material given (give --material NAME, one of "
                        f"{', '.join(named_materials())}, or --youngs-modulus E --poisson NU in "
                        f"{pressure_unit}; a placeholder would go unnoticed)")
    for key in ("youngs_modulus", "poisson"):
        if key not in section:
            raise UserError(f"--{key.replace('_', '-')}: missing (give it too, or --material NAME)")
    if not -1.0 < section["poisson"] < 0.5:
        raise UserError(f"--poisson: {section['poisson']:g} is outside -1 < nu < 0.5")
    for key, value in section.items():
        if not (math.isfinite(value) and value > 0.0) and key != "poisson":
            raise UserError(f"--{key.replace('_', '-')}: {value:g} must be a positive number")
    try:
        check_material(section, pressure_unit)
    except SceneError as err:
        option = "--" + err.key.split(".")[-1].replace("_", "-")
        fix = (err.fix or "").replace("set units.pressure:", "pass --pressure-unit")
        raise UserError(f"{option}: {err.what} ({fix})") from None
    if name is not None and any(v is not None for v in given.values()):
        source += "; overridden by the constants given"
    return section, source


def assess_surface(m) -> dict:
    """The numbers `new-scene` chooses by, for a `Measurement` `m`: skewness and kurtosis of
    the heights less their least-squares tilt (`asperity.surface.distribution`) and whether
    they are Gaussian; the rms of the removed tilt over the rms roughness; the share of the
    variance left after the tilt that a 2nd-degree polynomial removes (form, not roughness:
    above `FORM_SHARE`); the record length [m] (the longer side of a map)."""
    from asperity.surface.distribution import gaussianity, height_distribution
    from asperity.surface.form import remove_form

    z, defined = m.heights, m.defined
    rough, tilt = remove_form(z, "tilt", defined=defined)
    second, _ = remove_form(z, "polynomial", 2, defined=defined)
    dist = height_distribution(rough, defined)
    gaussian, why = gaussianity(dist["skewness"], dist["kurtosis"])
    r1, r2 = rough[defined], second[defined]
    variance = float(np.mean((r1 - r1.mean()) ** 2))
    tilt_rms = float(np.sqrt(np.mean((tilt[defined] - z[defined].mean()) ** 2)))
    if m.kind == "profile":
        length = (z.size - 1) * m.dx
    else:
        length = max((z.shape[1] - 1) * m.dx, (z.shape[0] - 1) * m.dy)
    return {"skewness": dist["skewness"], "kurtosis": dist["kurtosis"], "gaussian": gaussian,
            "why": why, "rms": dist["rms"], "tilt_ratio": tilt_rms / dist["rms"],
            "form_share": 1.0 - float(np.mean((r2 - r2.mean()) ** 2)) / variance, "length": length}


def surface_notes(kind: str, stats: dict, length_unit: str) -> list[str]:
    """What the scene's comment says about the surface, and `new-scene` prints: non-Gaussian
    heights (and, for a profile, what the Nayak density then assumes) and a dominating form."""
    notes = []
    numbers = f"skewness {stats['skewness']:.3g}, kurtosis {stats['kurtosis']:.3g}"
    if not stats["gaussian"]:
        if kind == "map":
            notes.append(f"the heights are not Gaussian ({stats['why']}): the population is the "
                         f"map's own peaks (density: sampled, 2.4.3)")
        else:
            notes.append(f"the heights are not Gaussian ({stats['why']}); the Nayak density "
                         f"assumes Gaussian heights (2.4.1), and the light-load answer may be off "
                         f"by a factor (asperity.surface.distribution): measure a map of the "
                         f"surface for its own peaks (2.4.3)")
    else:
        notes.append(f"the heights are Gaussian within the limits ({numbers})")
    scale = units.length_scale(length_unit)
    cutoff = stats["length"] / CUTOFFS_PER_LENGTH / scale
    if stats["form_share"] > FORM_SHARE:
        notes.append(f"the form dominates: a 2nd-degree polynomial removes {100 * stats['form_share']:.0f} % "
                     f"of the variance left after the tilt; set surface.form: polynomial with "
                     f"surface.polynomial_degree: 2, or surface.filter: {{lambda_c: {cutoff:.3g}}} "
                     f"({length_unit}: a fifth of the record, ISO 4288)")
    elif stats["tilt_ratio"] > TILT_RATIO:
        notes.append(f"the removed tilt is {stats['tilt_ratio']:.3g} times the rms roughness: if "
                     f"waviness remains, add surface.filter: {{lambda_c: {cutoff:.3g}}} ({length_unit})")
    return notes


def scene_text(file_text: str, path: Path, info: dict, m, unit: str | None, spacing: float | None,
               material: tuple[dict, str], pressure_unit: str, notes: list[str]) -> str:
    """The YAML of a scene for the measured file `path` (named `file_text` in the scene;
    `info`: what its metadata says; `m`: the `Measurement` read from it)."""
    kind = m.kind
    density = "sampled" if kind == "map" else "nayak"
    source = [f"    file: {file_text}"]
    if info["unit"] is None:
        source.append(f"    unit: {unit}                # the file states no unit: given to new-scene")
    elif unit is not None and unit != info["unit"]:
        source.append(f"    unit: {unit}                # overrides the file's {info['unit']}")
    if spacing is not None:
        source.append(f"    spacing: {spacing:g}           # in um; overrides the file's")
    points = " x ".join(str(n) for n in m.heights.shape)
    where = f"{m.reader}, channel {m.channel!r}" if m.channel else m.reader
    section, origin = material
    comment = "".join(f"# NOTE: {n}\n" for n in notes)
    return (
        f"title: Measured {kind} {path.name} with elastic Hertz asperities\n"
        f"report: \"2.3 statistics, {'2.4.3' if density == 'sampled' else '2.4.1'} peaks, 6.1 Hertz, "
        f"2.5 expectation\"\n"
        f"# Written by: asperity new-scene {file_text}\n"
        f"# The {kind} of {path.name}: {points} points, read by {where}; its numbers in {m.unit}.\n"
        f"# Its least-squares tilt is removed before the statistics (surface.form); add\n"
        f"# surface.filter: {{lambda_c: ...}} to keep only the roughness shorter than a cut-off\n"
        f"# wavelength. Every asperity is an elastic Hertz tip.\n"
        + comment
        + f"units: {{length: um, pressure: {pressure_unit}}}\n"
        f"surface:\n"
        f"  {kind}:\n" + "\n".join(source) + "\n"
        f"  form: tilt\n"
        + _POPULATION[density]
        + "asperity:\n"
        "  model: hertz            # or {model: fe, geometry: sphere | paraboloid | cosine}\n"
        f"material:                 # {origin}\n"
        + "".join(f"  {k}: {v:.6g}\n" for k, v in section.items())
        + _HOMOGENIZATION[density]
        + "  separations: {start: 0.0, stop: 3.0, count: 31, unit: sigma}\n"
    )


def new_scene(file: Path, name: str | None, scene_dir: Path | None, unit: str | None,
              spacing: float | None, force: bool, material: tuple[dict, str],
              pressure_unit: str = "MPa") -> tuple[Path, str, list[str]]:
    """Write scene_dir/NAME.yaml for a measured file, read whole (`read_measurement`);
    returns its path, the command that runs it and the notes on the surface."""
    from asperity.io.topography import describe_file, read_measurement
    from asperity.scene.checks import check_scene

    if not file.exists():
        raise UserError(f"{file}: no such file")
    info = describe_file(file)
    if info["kind"] not in ("profile", "map"):
        raise UserError(f"{file}: holds neither a profile nor a map ({info['points']} points)")
    if info["unit"] is None and unit is None:
        raise UserError(f"{file}: the file states no length unit (give the unit of its numbers "
                        f"with --unit: m, cm, mm, um, nm)")
    if info["spacing"] is None and spacing is None:
        raise UserError(f"{file}: the file states no spacing (give it with --spacing, in um)")
    m = read_measurement(file, info["kind"], unit=unit,  # the whole file, as the surface job will
                         spacing=None if spacing is None else spacing * units.length_scale("um"))
    notes = surface_notes(m.kind, assess_surface(m), "um")
    name = name or scene_name(file)
    if not re.fullmatch(r"[a-z0-9_]+", name):
        raise UserError(f"scene name {name!r}: use lower-case letters, digits and underscores")
    root = workflow_root(scene_dir)  # where snakemake runs the scene
    scene_dir = scene_dir if scene_dir is not None else (root or Path.cwd()) / "config" / "scenes"
    target = scene_dir / f"{name}.yaml"
    if target.exists() and not force:
        raise UserError(f"{target}: exists (choose another NAME or pass --force)")
    text = scene_text(scene_path(file, root), file, info, m, unit, spacing, material, pressure_unit,
                      notes)
    check_scene(yaml.safe_load(text), target)
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_name(f".{target.name}.tmp")
    tmp.write_text(text)
    tmp.replace(target)
    # any scene file runs by its targets; one outside the workflow's folder names it
    command = f"snakemake --cores 2 results/{name}/interface.nc results/{name}/figures/interface.png"
    default_dir = None if root is None else (root / "config" / "scenes").resolve()
    if target.parent.resolve() != default_dir:
        command += f" --config scene_dir={target.parent.resolve()}"
    if root is not None:
        command = f"cd {root} && {command}"
    return target, command, notes
