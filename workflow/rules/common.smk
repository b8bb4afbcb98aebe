# Loading and validating the configuration and the scenes, the targets of each scene,
# and every function the rules of workflow/rules/*.smk use (the other files hold the
# rules alone). All a job depends on reaches it through `params:`, the version of the
# code that computes it included (asperity.versions).

import os
import re
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import jsonschema
from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from asperity.io.run_report import failure_lines, logs_since, warning_summary
from asperity.scene.checks import SceneError, check_scene, text_number_hint
from asperity.scene.files import read_scene
from asperity.stages.reference import ROUTE_SEPARATOR, route_scene
from asperity.versions import code_version, sample_version

# read before the configuration is validated (the scene files are needed to validate it)
RESULTS = config.get("results", "results")
SCENE_DIR = Path(config.get("scene_dir", "config/scenes"))
#: the software environment of the rules (snakemake --sdm conda): this package, pinned
ENV = "../envs/asperity.yaml"
#: when this invocation started: the job logs written since are those of its jobs
STARTED = time.time()


def tell_the_end(failed):
    """On the console where a run ends (the Snakefile's onsuccess and onerror): the
    WARNING lines of the jobs of this run, grouped, and the error of each failed job
    in one line (asperity.io.run_report); the job logs keep the whole lines."""
    logs = logs_since(RESULTS, STARTED)
    lines = warning_summary(logs, RESULTS)
    if failed:
        lines += failure_lines(logs)
    if lines:
        print("\n".join(lines), file=sys.stderr, flush=True)


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
    return f"{where}: key {key}: {error.message}{text_number_hint(error.instance)}"


def _canonical(obj):
    """Dicts with sorted keys, recursively: the params of a rule then do not
    change (and trigger no rerun) when a scene file is merely reformatted."""
    if isinstance(obj, dict):
        return {k: _canonical(obj[k]) for k in sorted(obj)}
    if isinstance(obj, list):
        return [_canonical(v) for v in obj]
    return obj


#: the schema of config and scenes, by absolute path (scenes are also validated when a
#: target asks for one, after parsing, when the include directory is no longer known)
SCHEMA = str(Path(workflow.basedir) / "config" / "schema.yaml")


def _read_scene(name, missing):
    """The scene `name` (asperity.scene.files.read_scene: YAML, and the scene it is `like`);
    `missing(file)`: the message if it has no file."""
    scene_file = SCENE_DIR / f"{name}.yaml"
    if not scene_file.exists():
        raise WorkflowError(missing(scene_file))
    try:
        return read_scene(scene_file)
    except SceneError as err:
        raise WorkflowError(str(err)) from None


def _load_scenes(names, loaded=None):
    """Scenes `names`, the scenes they compare with and the routes of a reference scene,
    validated against the schema (its defaults filled in) and their input files checked.
    At start `names` are config `scenes` and the whole config is validated; later
    (`loaded`: the scenes known so far) a scene a target asks for, validated alone."""
    at_start = loaded is None
    loaded = {} if at_start else loaded
    definitions = {}
    pending = list(names)
    while pending:  # the scenes asked for and the scenes they compare with
        name = pending.pop(0)
        if name in definitions or name in loaded:
            continue
        definitions[name] = _read_scene(
            name,
            lambda f: (
                f"config/config.yaml: key scenes: no scene file {f}"
                if at_start
                else f"no scene file {f} (a scene is a file {SCENE_DIR}/<name>.yaml)"
            ),
        )
        pending += list(definitions[name].get("compare_with", []) or [])
    for name, scene in list(definitions.items()):  # the statistical routes of a reference scene
        for route in scene.get("routes") or {}:
            definitions[f"{name}{ROUTE_SEPARATOR}{route}"] = route_scene(
                name, scene, route, RESULTS
            )
    if not at_start:  # a scene not in config `scenes`: validated on its own
        checked = {k: config[k] for k in ("scenes", "accuracy", "results", "scene_dir")}
        checked["scene_definitions"] = definitions
        config["scene_definitions"].update(definitions)
    else:
        config["scene_definitions"] = definitions
        checked = config
    try:
        validate(checked, SCHEMA)
    except WorkflowError as err:
        cause = _schema_error(err)
        raise WorkflowError(_explain(cause) if cause is not None else str(err)) from None
    for name, scene in definitions.items():
        if ROUTE_SEPARATOR in name:
            continue  # a route reads its reference scene's map, checked with that scene
        try:  # what the schema cannot say: a modulus in the wrong unit, an FE shape
            check_scene(scene, SCENE_DIR / f"{name}.yaml")
        except SceneError as err:
            raise WorkflowError(str(err)) from None
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
    """Scene name -> definition.  A scene of config `scenes` (and those it compares
    with) is loaded at start; any other scene file of `scene_dir` when a target or a
    rule asks for it (config `scenes` only chooses what `rule all` runs), validated
    the same way.  ``<scene>@<preset>`` is the scene run at another accuracy preset,
    in its own results folder (the accuracy study of the scenes); its samples share
    keys, hence files, with runs of the same preset.  ``<scene>+<route>``, a statistical
    route of a scene with a deterministic reference
    (asperity.stages.reference.route_scene), is loaded and validated with its scene."""

    def __missing__(self, name):
        base, _, preset = name.partition("@")
        if preset in PRESETS:
            return self[base]
        if preset:
            raise WorkflowError(f"scene {name!r}: no preset {preset!r} (one of {PRESETS})")
        scene, _, route = name.partition(ROUTE_SEPARATOR)
        if scene not in self:
            self.update(_load_scenes([scene], loaded=self))
        if name not in self:
            raise WorkflowError(
                f"scene {scene!r}: no route {route!r} in {SCENE_DIR / f'{scene}.yaml'}"
            )
        return dict.__getitem__(self, name)


SCENES = _Scenes(_load_scenes(config["scenes"]))


# --- what a scene makes ---------------------------------------------------------------

#: what a scene needs to make a product: (test of the scene's name, what it lacks)
_NEEDS = {
    "surface": (
        lambda n: "surface" in SCENES[n],
        "has no surface (key `surface:` with a profile, profiles, map, statistics or "
        "gaussian_heights)",
    ),
    "population": (
        lambda n: model(n) not in (None, "constant"),
        "has no asperity population (key `asperity.model`: hertz or fe)",
    ),
    "law": (
        lambda n: model(n) not in (None, "constant") or "route" in SCENES[n],
        "makes no interface law (key `asperity.model`: hertz or fe, or a `route:` section)",
    ),
    "constant": (
        lambda n: model(n) == "constant",
        "takes no expectation of a constant (key `asperity.model: constant`)",
    ),
    "unloading": (
        lambda n: unloads(n),
        "does not unload (add `effects: [unloading]`, or `unloading` to its `effects:` list)",
    ),
    "adhesion": (
        lambda n: "adhesion" in SCENES[n]["effects"],
        "has no adhesion (add `adhesion` to its `effects:` list)",
    ),
    "verification": (
        lambda n: "single_asperity" in SCENES[n] or bool(SCENES[n].get("verification")),
        "verifies nothing (key `verification:` greenwood_williamson or hertz, or a "
        "`single_asperity:` section)",
    ),
    "convergence": (
        lambda n: bool((generated(n) or {}).get("convergence_spacings")),
        "has no convergence study (key `surface.profile.generate.convergence_spacings`)",
    ),
    **{
        section: (lambda n, s=section: s in SCENES[n], f"has no `{section}:` section")
        for section in ("friction", "laws", "uniaxial", "sliding", "plane_strain", "reference")
    },
}

#: product (path under results/<scene>/) -> what the scene needs to make it, in order
PRODUCT_NEEDS = {
    "surface.nc": ["surface"],
    "figures/surface.png": ["surface"],
    "convergence.nc": ["convergence"],
    "expectation.nc": ["constant"],
    "figures/expectation.png": ["constant"],
    **{f: ["population"] for f in ("plan.nc", "asperities.nc", "figures/asperities.png")},
    "interface.nc": ["law"],
    "figures/interface.png": ["law"],
    "unloading.nc": ["population", "unloading"],
    "figures/unloading.png": ["population", "unloading"],
    "figures/adhesion.png": ["population", "adhesion"],
    "friction.nc": ["law", "friction"],
    "figures/friction.png": ["law", "friction"],
    "laws.nc": ["population", "laws"],
    "figures/laws.png": ["population", "laws"],
    "verification.nc": ["verification"],
    "figures/verification.png": ["verification"],
    "uniaxial.nc": ["uniaxial"],
    "figures/uniaxial.png": ["uniaxial"],
    "sliding.nc": ["sliding"],
    "figures/sliding.png": ["sliding"],
    "plane_strain.nc": ["plane_strain"],
    "figures/plane_strain.png": ["plane_strain"],
    "figures/plane_strain_meshes.png": ["plane_strain"],
    "reference.nc": ["reference"],
    "comparison.nc": ["reference"],
    "figures/reference.png": ["reference"],
}


def check_product(scene, product):
    """Raise a one-line WorkflowError if scene `scene` does not make `product` (a path
    under results/<scene>/ of PRODUCT_NEEDS), naming the scene file and the key that
    would make it; loads the scene if it is not loaded yet."""
    target = f"{RESULTS}/{scene}/{product}"
    base = scene.partition("@")[0]
    name, _, route = base.partition(ROUTE_SEPARATOR)
    where = f"scene {SCENE_DIR / f'{name}.yaml'}" + (f" (route {route})" if route else "")
    try:
        SCENES[scene]
    except WorkflowError as err:
        raise WorkflowError(f"{target}: {err}") from None
    for need in PRODUCT_NEEDS.get(product, []):
        test, lacks = _NEEDS[need]
        if not test(base):
            raise WorkflowError(f"{target}: {where} {lacks}")


def made(product):
    """An input function with no files that fails (before any job runs) where the
    scene does not make `product` (`check_product`)."""

    def check(wildcards):
        check_product(wildcards.scene, product)
        return []

    return check


def _named_targets():
    """The paths named on the command line (relative to the working directory), as
    (scene, product) where they are ``<RESULTS>/<scene>/<product>``; Snakemake hands its
    targets to the workflow only after parsing."""
    root = Path(RESULTS).parts
    named = []
    for arg in sys.argv[1:]:
        if arg.startswith("-"):
            continue
        parts = Path(os.path.relpath(arg) if os.path.isabs(arg) else os.path.normpath(arg)).parts
        if len(parts) >= len(root) + 2 and parts[: len(root)] == root:
            named.append((parts[len(root)], Path(*parts[len(root) + 1 :]).as_posix()))
    return named


def check_targets(targets):
    """`check_product` of every (scene, product) of `targets` that PRODUCT_NEEDS knows."""
    for scene, product in targets:
        if scene not in ("samples", "accuracy") and product in PRODUCT_NEEDS:
            check_product(scene, product)


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
        for route, part in (SCENES[name].get("routes") or {}).items():
            if "friction" in part:  # friction of that route's interface law
                routed = f"{RESULTS}/{name}{ROUTE_SEPARATOR}{route}"
                targets += [f"{routed}/friction.nc", f"{routed}/figures/friction.png"]
    gen = generated(name)
    if gen and gen.get("convergence_spacings"):
        targets.append(f"{out}/convergence.nc")
    if "route" in SCENES[name]:  # a route beyond independent asperities (routes.smk)
        targets += [f"{out}/interface.nc", f"{out}/figures/interface.png"]
        if "friction" in SCENES[name]:
            targets += [f"{out}/friction.nc", f"{out}/figures/friction.png"]
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
    """(scene, preset) of every run the scene accuracy study compares: each scene at each
    preset, each variant at each preset but the last (compared with its scene's last)."""
    study = config["accuracy_scenes"]
    variants = study.get("variants") or {}
    return [(name, preset) for name in study["scenes"] for preset in study["presets"]] + [
        (name, preset) for name in variants for preset in study["presets"][:-1]
    ]


def accuracy_sliding_files(wildcards):
    """sliding.nc of the scene of config `accuracy_sliding` at each of its presets (its own
    folder at the run's `accuracy`, else ``<scene>@<preset>``), keyed by preset."""
    study = config["accuracy_sliding"]
    return {
        preset: f"{scene_folder(study['scene'], preset)}/sliding.nc" for preset in study["presets"]
    }


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


# a target the scene does not make fails here, before any job (the rules check it too)
check_targets(_named_targets())


# --- routes (routes.smk) ----------------------------------------------------------------


def _route_scenes():
    """The scenes whose interface.nc comes from a route: the scene files with a `route`
    section, and the routes with one of the reference scenes (read at parse time, so
    that rule route_interface of routes.smk matches them alone; rule `interface` makes
    every other one)."""
    names = []
    for path in sorted(SCENE_DIR.glob("*.yaml")):
        try:
            definition = read_scene(path)
        except SceneError:
            continue  # reported with its file and key where the scene is loaded
        if "route" in definition:
            names.append(path.stem)
        for name, part in (definition.get("routes") or {}).items():
            if isinstance(part, dict) and "route" in part:
                names.append(f"{path.stem}{ROUTE_SEPARATOR}{name}")
    return names


ROUTE_SCENES = _route_scenes()


def route_inputs(wildcards):
    """The map and surface.nc of a route scene, and its finite element asperities where
    its interacting route takes their law (route.law: fe)."""
    out = f"{RESULTS}/{wildcards.scene}"
    inputs = {"map": surface_inputs(wildcards)["data"], "surface": f"{out}/surface.nc"}
    if SCENES[wildcards.scene]["route"].get("law") == "fe":
        inputs["asperities"] = f"{out}/asperities.nc"
    return inputs


# --- studies (studies.smk) -------------------------------------------------------------


def scene_folder(scene, preset):
    """The results folder of `scene` run at `preset`: its own at the run's `accuracy`, else
    ``<scene>@<preset>``."""
    return f"{RESULTS}/{scene}" if preset == config["accuracy"] else f"{RESULTS}/{scene}@{preset}"


def route_error_files(wildcards):
    """The comparison, reference and surface files of each scene of table `table` of config
    `route_errors`, and the interface of each of its routes, at the table's preset: the
    scene's own folder at the run's `accuracy`, else ``<scene>@<preset>``."""
    table = config["route_errors"]["tables"].get(wildcards.table)
    if table is None:
        raise WorkflowError(
            f"config/config.yaml: key route_errors.tables: no table {wildcards.table!r} "
            f"(one of {', '.join(config['route_errors']['tables'])})"
        )
    preset = config["route_errors"]["accuracy"]
    files = {
        f"{scene}__{kind}": f"{scene_folder(scene, preset)}/{kind}.nc"
        for scene in table
        for kind in ("comparison", "reference", "surface")
    }
    files |= {
        f"{scene}__route__{route}": f"{scene_folder(scene + ROUTE_SEPARATOR + route, preset)}/interface.nc"
        for scene in table
        for route in SCENES[scene]["routes"]
    }
    return files


def scale_study_files(wildcards):
    """The map file of each scene of config `scale_study` (or its generated map)."""
    return {
        scene: surface_inputs(SimpleNamespace(scene=scene))["data"]
        for scene in config["scale_study"]["scenes"]
    }


def scale_study_scenes(wildcards):
    """The sections of each scene of config `scale_study` the study reads."""
    return {
        scene: {part: SCENES[scene].get(part) for part in ("surface", "units", "material")}
        for scene in config["scale_study"]["scenes"]
    }


def scene_files(study, kinds):
    """An input function: the files `kinds` (e.g. interface, surface) of each scene of config
    `study`'s `scenes`, at the run's preset, keyed ``<scene>__<file>``
    (asperity.stages.studies.files_by_scene)."""
    return lambda wildcards: {
        f"{scene}__{kind}": f"{RESULTS}/{scene}/{kind}.nc"
        for scene in config[study]["scenes"]
        for kind in kinds
    }


def plane_strain_table_files(wildcards):
    """The plane_strain.nc of each scene of config `plane_strain_table` at each of its
    presets (the scene's own folder at the run's `accuracy`, else ``<scene>@<preset>``),
    keyed ``<scene>__<preset>``."""
    study = config["plane_strain_table"]
    return {
        f"{scene}__{preset}": f"{scene_folder(scene, preset)}/plane_strain.nc"
        for preset in study["presets"]
        for scene in study["scenes"]
    }


def friction_report_scenes(wildcards):
    """The material and units of each scene of config `friction_report`."""
    return {
        scene: {part: SCENES[scene][part] for part in ("material", "units")}
        for scene in config["friction_report"]["scenes"]
    }
