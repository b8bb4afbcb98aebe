"""Stage `accuracy` (workflow/rules/accuracy.smk): what accuracy costs in time, on the
Hertz problem (report 6.1) and for whole scenes (`asperity.studies`)."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.plots import accuracy_hertz, accuracy_scenes
from asperity.studies import hertz, scenes

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
    """Deviation of each (scene, preset) from the finest preset, with its FE cost."""
    return scenes.scene_accuracy(interfaces, study["scenes"], study["presets"],
                                 threshold=study["threshold"])


def scenes_accuracy_figure(ds: xr.Dataset):
    return accuracy_scenes.scene_accuracy_figure(ds)

