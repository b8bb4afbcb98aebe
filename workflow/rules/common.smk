# Loading and validating the configuration and the scenes, the targets of each scene,
# and every function the rules of workflow/rules/*.smk use (the other files hold the
# rules alone). All a job depends on reaches it through `params:`, the version of the
# code that computes it included (asperity.versions).

from pathlib import Path

import jsonschema
import yaml
from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from asperity.stages.reference import ROUTE_SEPARATOR, route_scene
from asperity.versions import code_version, sample_version

# read before the configuration is validated (the scene files are needed to validate it)
RESULTS = config.get("results", "results")
SCENE_DIR = Path(config.get("scene_dir", "config/scenes"))
#: the software environment of the rules (snakemake --sdm conda): this package, pinned
ENV = "../envs/asperity.yaml"


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
        name, _, route = str(path[1]).partition(ROUTE_SEPARATOR)
        where = SCENE_DIR / f"{name}.yaml"
        key = ".".join(
            ([f"routes.{route} (as its scene)"] if route else []) + [str(p) for p in path[2:]]
        )
        key = key or "(top level)"
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
    for name, scene in list(definitions.items()):  # the statistical routes of a reference scene
        for route in scene.get("routes") or {}:
            definitions[f"{name}{ROUTE_SEPARATOR}{route}"] = route_scene(
                name, scene, route, RESULTS
            )
    config["scene_definitions"] = definitions
    try:
        validate(config, "../../config/schema.yaml")
    except WorkflowError as err:
        cause = _schema_error(err)
        raise WorkflowError(_explain(cause) if cause is not None else str(err)) from None
    for name, scene in definitions.items():
        if ROUTE_SEPARATOR in name:
            continue  # a route reads its reference scene's map, checked with that scene
        for kind in ("profile", "map"):
            source = scene.get("surface", {}).get(kind, {})
            if "file" in source and not Path(source["file"]).exists():
                raise WorkflowError(
                    f"{SCENE_DIR / f'{name}.yaml'}: key surface.{kind}.file: "
                    f"no such file {source['file']}"
                )
        for i, item in enumerate(scene.get("surface", {}).get("profiles", {}).get("files", [])):
            if not Path(item["file"]).exists():
                raise WorkflowError(
                    f"{SCENE_DIR / f'{name}.yaml'}: key surface.profiles.files.{i}.file: "
                    f"no such file {item['file']}"
                )
    return {name: _canonical(scene) for name, scene in definitions.items()}


PRESETS = ("draft", "standard", "fine")


class _Scenes(dict):
    """Scene name -> definition.  ``<scene>@<preset>`` is the scene run at another
    accuracy preset, in its own results folder (the accuracy study of the scenes);
    its samples share keys, hence files, with runs of the same preset.
    ``<scene>+<route>``, a statistical route of a scene with a deterministic reference
    (asperity.stages.reference.route_scene), is loaded and validated with its scene."""

    def __missing__(self, name):
        base, _, preset = name.partition("@")
        if preset in PRESETS:
            return self[base]
        raise WorkflowError(
            f"scene {name!r} is not among the scenes of config/config.yaml (nor compared with "
            f"by one); add it to `scenes:` or run with --config 'scenes=[{name}]'"
        )


SCENES = _Scenes(_load_scenes())


def accuracy_of(wildcards):
    """The preset of a scene run: ``<scene>@<preset>``'s own, else the scene's `accuracy`
    (a scene that has measured that a cheaper preset suffices), else config `accuracy`."""
    base, _, preset = wildcards.scene.partition("@")
    return preset or SCENES[base].get("accuracy") or config["accuracy"]


def scene_part(part):
    """A params function giving one section of the scene (None if the scene has none;
    the schema's defaults filled in): a change of it reruns the rule."""
    return lambda wildcards: SCENES[wildcards.scene].get(part)


def effect_section(part):
    """A params function giving the section `part` of a scene with the effect of that
    name, None without it (the section is unused then, and its changes rerun nothing)."""
    return lambda w: SCENES[w.scene][part] if part in SCENES[w.scene]["effects"] else None


def surface_kind(name):
    surface = SCENES[name]["surface"]
    return next(
        k for k in ("profile", "profiles", "map", "statistics", "gaussian_heights") if k in surface
    )


def generated(name):
    return SCENES[name]["surface"][surface_kind(name)].get("generate")


def model(name):
    """The asperity model of a scene (None: a scene without asperities)."""
    return SCENES[name]["asperity"]["model"] if "asperity" in SCENES[name] else None


def scene_targets(name):
    out = f"{RESULTS}/{name}"
    if "single_asperity" in SCENES[name]:
        return [f"{out}/verification.nc", f"{out}/figures/verification.png"]
    if "uniaxial" in SCENES[name]:
        return [f"{out}/uniaxial.nc", f"{out}/figures/uniaxial.png"]
    if "sliding" in SCENES[name]:
        return [f"{out}/sliding.nc", f"{out}/figures/sliding.png"]
    if "plane_strain" in SCENES[name]:
        return [
            f"{out}/plane_strain.nc",
            f"{out}/figures/plane_strain.png",
            f"{out}/figures/plane_strain_meshes.png",
        ]
    targets = [f"{out}/surface.nc", f"{out}/figures/surface.png"]
    if "reference" in SCENES[name]:
        targets += [f"{out}/reference.nc", f"{out}/comparison.nc", f"{out}/figures/reference.png"]
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
        if unloads(name):
            targets += [f"{out}/unloading.nc", f"{out}/figures/unloading.png"]
        if "adhesion" in SCENES[name]["effects"]:
            targets.append(f"{out}/figures/adhesion.png")
        if "friction" in SCENES[name]:
            targets += [f"{out}/friction.nc", f"{out}/figures/friction.png"]
        if "laws" in SCENES[name]:
            targets += [f"{out}/laws.nc", f"{out}/figures/laws.png"]
    return targets


# --- surface (surface.smk) ------------------------------------------------------------


def surface_inputs(wildcards):
    kind = surface_kind(wildcards.scene)
    source = SCENES[wildcards.scene]["surface"][kind]
    if kind in ("profile", "map"):
        if "generate" in source:
            suffix = "txt" if kind == "profile" else "npy"
            return {"data": f"{RESULTS}/{wildcards.scene}/input/{kind}.{suffix}"}
        return {"data": source["file"]}
    if kind == "profiles":
        if "generate" in source:
            return {"data": f"{RESULTS}/{wildcards.scene}/input/profiles"}
        return {"data": [item["file"] for item in source["files"]]}
    return {}


# --- population (population.smk) ------------------------------------------------------

SAMPLE_SPECS = {}  # key -> the JSON spec of its job, from the plans read so far
SAMPLE_KINDS = {}  # key -> the asperity kind of its job (the plan's attribute `kind`)


def _register_specs(plan):
    for key, spec in zip(plan["key"].values, plan["spec"].values):
        SAMPLE_SPECS.setdefault(str(key), str(spec))
        SAMPLE_KINDS.setdefault(str(key), plan.attrs.get("kind"))


def sample_files(wildcards):
    """The per-sample job outputs the plan asks for (none for analytic asperities).
    Samples live in one folder for all scenes: a key is the hash of what its job
    depends on, so scenes (and presets) that need the same asperity share it."""
    from asperity.population.plan import job_keys
    from asperity.io.netcdf import read_dataset

    plan = read_dataset(checkpoints.plan.get(scene=wildcards.scene).output[0])
    _register_specs(plan)
    return [f"{RESULTS}/samples/{key}.nc" for key in job_keys(plan)]


def _registered(key):
    """Register the specs of every plan on disk, if `key` is not among those read so far
    (a job run on its own, e.g. by a cluster executor)."""
    from asperity.io.netcdf import read_dataset

    if key not in SAMPLE_SPECS:
        for plan_file in sorted(Path(RESULTS).glob("*/plan.nc")):
            _register_specs(read_dataset(plan_file))
    if key not in SAMPLE_SPECS:
        raise WorkflowError(
            f"sample {key}: in no plan under {RESULTS}/*/plan.nc; "
            "samples are made for a scene (build its plan first)"
        )
    return key


def sample_spec(wildcards):
    """The spec of sample `key` (the JSON the plan stores; its hash is the key)."""
    return SAMPLE_SPECS[_registered(wildcards.key)]


def sample_code_version(wildcards):
    """The code version of sample `key`: that of its asperity kind (asperity.versions)."""
    return sample_version(SAMPLE_KINDS[_registered(wildcards.key)])


# --- homogenize (homogenize.smk) ------------------------------------------------------


def unloads(name):
    return "unloading" in SCENES[name]["effects"]


def interface_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {
        "surface": f"{out}/surface.nc",
        "plan": f"{out}/plan.nc",
        "asperities": f"{out}/asperities.nc",
    }
    if unloads(wildcards.scene):
        inputs["unloading"] = f"{out}/unloading.nc"
    return inputs


def verification_inputs(wildcards):
    if "single_asperity" in SCENES[wildcards.scene]:
        return {}  # one asperity against Hertz: nothing upstream
    out = f"{RESULTS}/{wildcards.scene}"
    return {"surface": f"{out}/surface.nc", "interface": f"{out}/interface.nc"}


# --- figures (figures.smk) ------------------------------------------------------------


def compared(wildcards, name):
    """The `name` result files of the scenes this scene compares with."""
    return [f"{RESULTS}/{other}/{name}" for other in compare_with(wildcards)]


def compare_with(wildcards):
    """The scenes this scene compares with."""
    return SCENES[wildcards.scene]["compare_with"]


def interface_figure_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {
        "interface": f"{out}/interface.nc",
        "surface": f"{out}/surface.nc",
        "others": compared(wildcards, "interface.nc"),
    }
    if SCENES[wildcards.scene].get("verification"):
        inputs["verification"] = f"{out}/verification.nc"
    return inputs


def surface_figure_inputs(wildcards):
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {"surface": f"{out}/surface.nc"}
    gen = generated(wildcards.scene)
    if gen and gen.get("convergence_spacings"):
        inputs["convergence"] = f"{out}/convergence.nc"
    return inputs


# --- friction (friction.smk) ----------------------------------------------------------


def friction_compared(wildcards):
    """The compared scenes that have a friction section (their friction.nc is drawn)."""
    return [other for other in compare_with(wildcards) if "friction" in SCENES[other]]


# --- accuracy (accuracy.smk) ----------------------------------------------------------


def accuracy_scene_runs():
    """(scene, preset) of every run the scene accuracy study compares."""
    study = config["accuracy_scenes"]
    return [(name, preset) for name in study["scenes"] for preset in study["presets"]]


# --- reference (reference.smk) --------------------------------------------------------


def reference_routes(wildcards):
    return list(SCENES[wildcards.scene].get("routes") or {})


def route_interfaces(wildcards):
    """interface.nc of every route of the scene (at the scene's preset, if it has one)."""
    base, at, preset = wildcards.scene.partition("@")
    return [
        f"{RESULTS}/{base}{ROUTE_SEPARATOR}{route}{at}{preset}/interface.nc"
        for route in reference_routes(wildcards)
    ]


def reference_map(wildcards):
    return surface_inputs(wildcards)["data"]
