"""Asperity kinds: how a sample of the plan becomes a response, one protocol per kind.

A kind answers, for the plan (`asperity.population.samples`), the sample job and the
gather, every question that differs between asperities:

- `Kind.check`: whether the scene's asperity, material and effects make sense for it;
- `Kind.grid`: the interference grid of the plan;
- `Kind.scalable`: whether its samples may form a self-similar family;
- `Kind.unloads`, `Kind.levels`: whether, and from which levels, a sample is unloaded (8.3);
- `Kind.spec`: exactly what the job of one sample depends on (its hash is the key);
- `Kind.solve`: the response of one sample from its spec (the ``sample`` job);
- `Kind.gather`: every sample on the plan's (height, curvature, interference) grid;
- `Kind.interface`: the homogenized interface of the gathered table (2.5).

The kinds, in `KINDS` by name: ``hertz`` (the closed form of 6.1, no job of its
own), ``elastic`` (FE, 6.1, 7.2), ``inelastic`` (FE with J2 or Bodner-Partom, loaded
and unloaded from levels, 7.3, 8.2, 8.3), ``adhesive`` (FE with Lennard-Jones
adhesion, 3.3.3, 7.3), ``elliptic`` (3-D FE elliptic paraboloids of a J2 body, one per
curvature ratio, for the anisotropic route: 2.4.2, 2.5.2). A scene chooses one through its
asperity model, geometry and effects (`kind_of`); a job chooses its kind from its spec (`kind_of_spec`); the gather from
the plan (`kind_of_plan`). A new effect is a new kind: one module, registered here.

Each kind has a code version, ``sample:<name>`` in `asperity.versions.VERSIONS`: bumped
whenever the responses of its samples change, it is part of what a ``sample`` job
depends on, so that after an upgrade exactly the samples whose code changed are
computed again.
"""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.population.kinds.adhesive import ADHESIVE
from asperity.population.kinds.base import FiniteElementKind, Kind, Planning, SampleFailed
from asperity.population.kinds.elastic import ELASTIC
from asperity.population.kinds.elliptic import ELLIPTIC
from asperity.population.kinds.hertz import HERTZ
from asperity.population.kinds.inelastic import INELASTIC

Config = Mapping[str, Any]

#: every kind, by name
KINDS: dict[str, Kind] = {kind.name: kind for kind in (HERTZ, ELASTIC, INELASTIC, ADHESIVE, ELLIPTIC)}

__all__ = ["KINDS", "FiniteElementKind", "Kind", "Planning", "SampleFailed", "kind_of",
           "kind_of_plan", "kind_of_spec"]


def kind_of(model: str, effects, geometry: str | None = None) -> Kind:
    """The kind of a scene's asperity ``model`` (and FE ``geometry``) under its ``effects``."""
    effects = set(effects)
    if model == "fe" and geometry == "elliptic":
        return KINDS["elliptic"]
    if model == "hertz":
        if "adhesion" in effects:
            raise ValueError("effect `adhesion` needs a finite element asperity (asperity.model: fe)")
        return KINDS["hertz"]
    if model != "fe":
        raise ValueError(f"asperity.model {model!r} has no population of samples "
                         "(`constant` is the expectation check of report 2.6.2)")
    if "adhesion" in effects:
        return KINDS["adhesive"]
    if "plasticity" in effects:
        return KINDS["inelastic"]
    return KINDS["elastic"]


def kind_of_spec(spec: Config) -> Kind:
    """The kind of a sample job from its spec."""
    return kind_of(spec["model"], spec.get("effects", ()), spec.get("geometry"))


def kind_of_plan(plan: xr.Dataset) -> Kind:
    """The kind of a plan's samples (its attribute ``kind``)."""
    name = plan.attrs.get("kind")
    if name not in KINDS:
        raise ValueError(f"plan of kind {name!r}: known kinds {', '.join(KINDS)} "
                         "(a plan written by an older version: make it again)")
    return KINDS[name]
