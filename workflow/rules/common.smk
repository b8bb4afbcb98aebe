# Loading and validating the configuration and the scenes, and the targets of
# each scene. Everything a rule depends on reaches it through `params:`.

from pathlib import Path

import jsonschema
import yaml
from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

RESULTS = config.get("results", "results")
SCENE_DIR = Path(config.get("scene_dir", "config/scenes"))


def _schema_error(error):
    """The jsonschema error behind a snakemake validation failure."""
    seen = error
    while seen is not None and not isinstance(seen, jsonschema.ValidationError):
        seen = seen.__cause__ or seen.__context__
    return seen


def _explain(error):
    """'file: key.path: message' for a validation error of config or a scene."""
    path = list(error.absolute_path)
    if len(path) >= 2 and path[0] == "scene_definitions":
        where = SCENE_DIR / f"{path[1]}.yaml"
        key = ".".join(str(p) for p in path[2:]) or "(top level)"
    else:
        where = Path("config/config.yaml")
        key = ".".join(str(p) for p in path) or "(top level)"
    return f"{where}: key {key}: {error.message}"


def _canonical(obj):
    """Dicts with sorted keys, recursively: the params of a rule then do not
    change (and trigger no rerun) when a scene file is merely reformatted."""
    if isinstance(obj, dict):
        return {k: _canonical(obj[k]) for k in sorted(obj)}
    if isinstance(obj, list):
        return [_canonical(v) for v in obj]
    return obj


def _load_scenes():
    definitions = {}
    pending = list(config["scenes"])
    while pending:  # the configured scenes and the scenes they compare with
        name = pending.pop(0)
        if name in definitions:
            continue
        scene_file = SCENE_DIR / f"{name}.yaml"
        if not scene_file.exists():
            raise WorkflowError(f"config/config.yaml: key scenes: no scene file {scene_file}")
        with open(scene_file) as fh:
            try:
                definitions[name] = yaml.safe_load(fh) or {}
            except yaml.YAMLError as err:
                raise WorkflowError(f"{scene_file}: not valid YAML: {err}")
        pending += list(definitions[name].get("compare_with", []) or [])
    config["scene_definitions"] = definitions
    try:
        validate(config, "../../config/schema.yaml")
    except WorkflowError as err:
        cause = _schema_error(err)
        raise WorkflowError(_explain(cause) if cause is not None else str(err)) from None
    for name, scene in definitions.items():
        for kind in ("profile", "map"):
            source = scene.get("surface", {}).get(kind, {})
            if "file" in source and not Path(source["file"]).exists():
                raise WorkflowError(
                    f"{SCENE_DIR / (name + '.yaml')}: key surface.{kind}.file: "
                    f"no such file {source['file']}"
                )
        for i, item in enumerate(scene.get("surface", {}).get("profiles", {}).get("files", [])):
            if not Path(item["file"]).exists():
                raise WorkflowError(
                    f"{SCENE_DIR / (name + '.yaml')}: key surface.profiles.files.{i}.file: "
                    f"no such file {item['file']}"
                )
    return {name: _canonical(scene) for name, scene in definitions.items()}


PRESETS = ("draft", "standard", "fine")


class _Scenes(dict):
    """Scene name -> definition.  ``<scene>@<preset>`` is the scene run at another
    accuracy preset, in its own results folder (the accuracy study of the scenes);
    its samples share keys, hence files, with runs of the same preset."""

    def __missing__(self, name):
        base, _, preset = name.partition("@")
        if preset in PRESETS and base in self:
            return self[base]
        raise WorkflowError(
            f"scene {name!r} is not among the scenes of config/config.yaml (nor compared with "
            f"by one); add it to `scenes:` or run with --config 'scenes=[{name}]'"
        )


SCENES = _Scenes(_load_scenes())


def scene(wildcards):
    return SCENES[wildcards.scene]


def accuracy_of(wildcards):
    """The preset of a scene run: ``<scene>@<preset>``'s own, else the scene's `accuracy`
    (a scene that has measured that a cheaper preset suffices), else config `accuracy`."""
    base, _, preset = wildcards.scene.partition("@")
    return preset or SCENES[base].get("accuracy") or config["accuracy"]


def scene_part(part, default=None):
    """A params function giving one subtree of the scene (triggers reruns on change)."""
    return lambda wildcards: SCENES[wildcards.scene].get(part, default)


def surface_kind(name):
    surface = SCENES[name]["surface"]
    return next(
        k for k in ("profile", "profiles", "map", "statistics", "gaussian_heights") if k in surface
    )


def generated(name):
    return SCENES[name]["surface"].get(surface_kind(name), {}).get("generate")


def model(name):
    return SCENES[name].get("asperity", {}).get("model")


def scene_targets(name):
    out = f"{RESULTS}/{name}"
    if "single_asperity" in SCENES[name]:
        return [f"{out}/verification.nc", f"{out}/figures/verification.png"]
    if "uniaxial" in SCENES[name]:
        return [f"{out}/uniaxial.nc", f"{out}/figures/uniaxial.png"]
    if "sliding" in SCENES[name]:
        return [f"{out}/sliding.nc", f"{out}/figures/sliding.png"]
    targets = [f"{out}/surface.nc", f"{out}/figures/surface.png"]
    gen = generated(name)
    if gen and gen.get("convergence_spacings"):
        targets.append(f"{out}/convergence.nc")
    if model(name) == "constant":
        targets += [f"{out}/expectation.nc", f"{out}/figures/expectation.png"]
    elif model(name) is not None:
        targets += [
            f"{out}/interface.nc",
            f"{out}/figures/interface.png",
            f"{out}/figures/asperities.png",
        ]
        if SCENES[name].get("verification"):
            targets.append(f"{out}/verification.nc")
        if "unloading" in SCENES[name].get("effects", []):
            targets += [f"{out}/unloading.nc", f"{out}/figures/unloading.png"]
        if "adhesion" in SCENES[name].get("effects", []):
            targets.append(f"{out}/figures/adhesion.png")
        if "friction" in SCENES[name]:
            targets += [f"{out}/friction.nc", f"{out}/figures/friction.png"]
        if "laws" in SCENES[name]:
            targets += [f"{out}/laws.nc", f"{out}/figures/laws.png"]
    return targets
