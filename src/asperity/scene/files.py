"""Reading a scene file: YAML, and a scene that is another scene with a few keys changed.

A scene file may start from another scene of the same folder::

    like: afm_reference
    title: The measured map mi-1.mi, routes against its boundary-element contact
    surface: {map: {file: data/topographies/mi-1.mi}}

is ``afm_reference.yaml`` with its title and map file replaced and everything else
as it is (`merged`: a mapping is merged key by key, at any depth; any other value, a list
included, replaces the other scene's).  The scene it starts from may itself start from
another; a circle is an error.  The result is what the workflow validates and runs, so a
scene written this way and a full copy with the same values are the same scene, with the
same sample keys and cached results.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

import yaml

from asperity.scene.checks import SceneError

__all__ = ["merged", "read_scene"]

#: libyaml's parser where PyYAML has it (the same documents, read about seven times faster)
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def merged(base: Mapping[str, Any], changes: Mapping[str, Any]) -> dict:
    """`base` with `changes` applied: mappings merged key by key at any depth, every other
    value of `changes` (numbers, text, lists) replacing the one of `base`."""
    out = dict(base)
    for key, value in changes.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = merged(out[key], value)
        else:
            out[key] = value
    return out


def _load(path: Path) -> dict:
    try:
        with open(path) as fh:
            scene = yaml.load(fh, Loader=_LOADER) or {}
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else str(path)
        raise SceneError("(top level)", f"not valid YAML ({getattr(err, 'problem', None) or err})",
                         file=where) from None
    if not isinstance(scene, dict):
        raise SceneError("(top level)", f"a scene is a mapping of sections, not {type(scene).__name__}",
                         file=path)
    return scene


def read_scene(path: str | Path) -> dict:
    """The scene of file `path`, with the scene it is `like` (module text) filled in; the key
    `like` stays, naming where it started.  A `SceneError` names the file and the key."""
    path = Path(path)
    seen = [path.stem]
    scene = _load(path)
    changes = [scene]
    while "like" in changes[-1]:
        name = changes[-1]["like"]
        if not isinstance(name, str):
            raise SceneError("like", f"{name!r} is not the name of a scene",
                             f"the name of another scene file of {path.parent}", file=path)
        if name in seen:
            raise SceneError("like", f"{' -> '.join(seen + [name])} is a circle", file=path)
        other = path.parent / f"{name}.yaml"
        if not other.is_file():
            raise SceneError("like", f"no scene file {other}", file=path)
        seen.append(name)
        changes.append(_load(other))
    out: dict = {}
    for change in reversed(changes):
        out = merged(out, {k: v for k, v in change.items() if k != "like"})
    if "like" in scene:
        out["like"] = scene["like"]
    return out
