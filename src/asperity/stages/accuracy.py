"""Stage `accuracy` (workflow/rules/accuracy.smk): what accuracy costs in time, on the
Hertz problem (report 6.1), for whole scenes, for an inelastic and for a sliding asperity
(`asperity.studies`)."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.plots import accuracy_hertz, accuracy_inelastic, accuracy_scenes, accuracy_sliding
from asperity.studies import hertz, inelastic_accuracy, scenes, sliding_accuracy

Config = Mapping[str, Any]


def hertz_accuracy_dataset(study: Config) -> xr.Dataset:
    """Every preset and a refinement sequence on the Hertz problem, and the penalty's error."""
    return hertz.hertz_accuracy_study(
        radius=study["radius"], youngs_modulus=study["youngs_modulus"], poisson=study["poisson"],
        interferences=tuple(study["interferences"]), penalty_factors=tuple(study["penalty_factors"]))


def hertz_accuracy_figure(ds: xr.Dataset):
    return accuracy_hertz.accuracy_figure(ds)


def scenes_accuracy_dataset(interfaces: Mapping[tuple[str, str], xr.Dataset], study: Config
                            ) -> xr.Dataset:
    """Deviation of each (scene, preset) from the finest preset, with its FE cost; each
    variant of a scene (`variants`: variant -> scene) against that scene's finest run."""
    variants = study.get("variants") or {}
    return scenes.scene_accuracy(interfaces, [*study["scenes"], *variants], study["presets"],
                                 threshold=study["threshold"], against=variants)


def scenes_accuracy_figure(ds: xr.Dataset):
    return accuracy_scenes.scene_accuracy_figure(ds)


def sliding_accuracy_dataset(files: Mapping[str, str], study: Config) -> xr.Dataset:
    """Each preset's force histories against the next finer one's, with what each run costs
    (`asperity.studies.sliding_accuracy`); `files`: preset -> its sliding.nc."""
    from asperity.io.netcdf import read_dataset

    return sliding_accuracy.sliding_accuracy({p: read_dataset(path) for p, path in files.items()}, study["presets"])


def sliding_accuracy_figure(ds: xr.Dataset):
    return accuracy_sliding.sliding_accuracy_figure(ds)


def inelastic_accuracy_dataset(case: str, study: Config, progress=None) -> xr.Dataset:
    """One inelastic asperity's meshes and kinematics at each preset against the reference
    run (`asperity.studies.inelastic_accuracy`)."""
    return inelastic_accuracy.inelastic_accuracy(case, study["presets"], study["variants"], study["reference"],
                                                 progress=progress)


def inelastic_accuracy_figure(ds: xr.Dataset):
    return accuracy_inelastic.inelastic_accuracy_figure(ds)
