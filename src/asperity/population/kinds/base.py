"""The protocol of an asperity kind (`Kind`), what the plan tells a kind (`Planning`),
and what the finite element kinds share (`FiniteElementKind`)."""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, Callable, Mapping

import numpy as np
import xarray as xr

from asperity.scene import Adhesion, Asperity, Material

Config = Mapping[str, Any]

log = logging.getLogger("asperity")


class SampleFailed(RuntimeError):
    """A sample's FE job failed (Newton even with step cutting, the contact zone,
    rupture); the message names the sample (key, curvature) and the step."""


@dataclass(frozen=True)
class Planning:
    """What the plan knows when it asks a kind about a sample: the scene's asperity,
    material (None: none given), effects, accuracy preset and adhesion (None without
    the effect); the plan's interference `grid` [m]; `family`: the curvatures [1/m]
    derived from one job by scaling (None: every curvature its own job); and the
    representative `width_to_height` of a cosine hill (None if not one)."""

    asperity: Asperity
    material: Material | None
    effects: frozenset[str]
    accuracy: str
    adhesion: Adhesion | None
    grid: np.ndarray
    family: np.ndarray | None
    width_to_height: float | None


class Kind:
    """The protocol of an asperity kind (module docstring); the defaults are those of
    a kind without unloading levels whose interface is the plain expectation."""

    name: str = ""
    #: whether a sample needs a job of its own (False: a closed form, evaluated by the gather)
    job: bool = True
    #: whether its jobs take ``asperity.edge_band`` (a mesh refined where the plastic
    #: contact edge goes: the inelastic kind's)
    edge_band: bool = False

    def check(self, asperity: Asperity, material: Material | None, effects: frozenset[str]) -> None:
        """Raise ValueError, naming the scene's key, where its asperity, material and
        effects do not make sense for the kind."""
        if "unloading" in effects:
            raise ValueError("effect `unloading` needs an FE asperity with effect `plasticity` "
                             "(an elastic asperity unloads along its loading curve)")
        if "finite_strain" in effects:
            raise ValueError("effect `finite_strain` needs an FE asperity with effect `plasticity` "
                             "(the finite-strain kinematics are the inelastic asperity's)")
        if asperity.edge_band and not self.edge_band:
            raise ValueError("asperity.edge_band needs an FE asperity with effect `plasticity` "
                             "(it refines the mesh where the plastic contact edge goes)")

    def grid(self, base: np.ndarray, largest: float, count: int, adhesion: Adhesion | None) -> np.ndarray:
        """The interference grid [m] of the plan; `base` is the geometric grid of
        `count` levels up to `largest` (`asperity.population.plan.interference_grid`)."""
        return base

    def scalable(self, asperity: Asperity, material: Material | None, effects) -> bool:
        """Whether the samples may form a self-similar family (one job, the others scaled)."""
        return False

    def unloads(self, effects: frozenset[str]) -> bool:
        """Whether the samples are unloaded from levels (`levels`)."""
        return False

    def levels(self, planning: Planning, height: float, curvature: float) -> tuple[np.ndarray, float]:
        """The unloading levels [m] of a sample and the left-out check level (NaN: none)."""
        raise NotImplementedError

    def spec(self, planning: Planning, height: float, curvature: float, level: float) -> dict:
        """Exactly what the job of a sample (peak height, the job's tip curvature,
        unloading level or NaN) depends on, as plain JSON values: its hash is the key."""
        raise NotImplementedError

    def solve(self, spec: Config, key: str) -> xr.Dataset:
        """The response of sample `key` (dim ``step``) from its spec; `SampleFailed`
        naming the sample and the step where the solver fails."""
        raise NotImplementedError

    def gather(self, plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> xr.Dataset:
        """Every sample of the plan on its (height, curvature, interference) grid."""
        raise NotImplementedError

    def plan_attrs(self, planning: Planning) -> dict[str, Any]:
        """Attributes of the plan that the later stages need (e.g. the adhesive reach)."""
        return {}

    def interface(self, asperities: xr.Dataset, separations: np.ndarray,
                  homogenized: Callable[..., xr.Dataset]) -> xr.Dataset:
        """The interface versus `separations`: `homogenized(table)` is the pipeline's
        expectation of one (height, curvature, interference) table
        (`asperity.stages.homogenize`)."""
        return homogenized(asperities)


class FiniteElementKind(Kind):
    """A kind whose samples are jobs of the finite element asperity (`asperity.fe`)."""

    def check(self, asperity, material, effects):
        super().check(asperity, material, effects)
        if material is None:
            raise ValueError("a finite element asperity needs the scene's `material` section")

    def base_spec(self, planning: Planning, height: float, curvature: float) -> dict:
        """What every FE job depends on: the geometry (kind, mapping, resolved
        width-to-height ratio, the job's tip curvature; the peak height only for the
        coupled hill, whose shape depends on it), the interference range the job
        computes (from the plan's grid, stretched over a self-similar family; for a job
        of the coupled hills' family of aspects the same fraction of its own depth), and the
        body (material in SI, effects, preset). Nothing else of the scene enters: a
        change of the population grid that leaves the range alone keeps the key."""
        from asperity.population.geometry import aspect_job_range, job_range, sample_geometry

        asperity = planning.asperity
        geometry = sample_geometry(asperity, curvature, planning.width_to_height, height)
        if asperity.aspect_family:  # a job of the coupled hills' family of aspects: scale free
            first, top = aspect_job_range(geometry, asperity, planning.grid)
        else:
            first, top = job_range(geometry, asperity, planning.grid, curvature, planning.family)
        spec = {
            "model": "fe",
            "geometry": asperity.geometry,
            "curvature": float(curvature),
            "range": [first, top],
            "material": planning.material.spec(),
            "effects": sorted(planning.effects),
            "accuracy": planning.accuracy,
        }
        if asperity.geometry == "cosine":
            spec["mapping"] = asperity.mapping
            spec["width_to_height"] = (asperity.width_to_height if asperity.width_to_height is not None
                                       else planning.width_to_height)
        if asperity.coupled:
            spec["height"] = float(height)
        return spec

    def gather(self, plan, samples):
        from asperity.population.gather import gather, gather_aspects

        if plan.attrs.get("aspect_family"):
            return gather_aspects(plan, samples)
        return gather(plan, samples)

    @staticmethod
    def failed(key: str, curvature: float, err: Exception, detail: str = "") -> SampleFailed:
        """The `SampleFailed` of sample `key` (curvature, `detail`) from the solver's error
        (a `ConvergenceError` is told the sample, so that it names it wherever it goes)."""
        from asperity.fe import ConvergenceError

        who = f"{key} (curvature {curvature:.6g} 1/m{detail})"
        if isinstance(err, ConvergenceError):
            err.sample = who
            return SampleFailed(str(err))
        return SampleFailed(f"sample {who}: {err}")

    @staticmethod
    def progress(key: str) -> Callable[[str], None]:
        """The progress of sample `key`'s solver as lines of the ``asperity`` log (the
        job's log file in the pipeline)."""
        return lambda line: log.info("sample %s: %s", key, line)

    @staticmethod
    def record(ds: xr.Dataset, spec: Config, key: str, geometry, level: float, cpu: float) -> xr.Dataset:
        """A sample's dataset with what names it: key, model, curvature, geometry, peak
        height (NaN unless coupled), unloading level (NaN: loading only), CPU time."""
        ds.attrs.update(key=key, model="fe", curvature=float(spec["curvature"]), geometry=repr(geometry),
                        height=float(spec.get("height", math.nan)), unloading_level=level,
                        cpu_time=cpu)
        return ds
