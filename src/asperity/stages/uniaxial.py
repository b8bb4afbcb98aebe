"""Stage `uniaxial` (workflow/rules/uniaxial.smk): Bodner-Partom material points under the
report's uniaxial histories (5, 6.3.1, 8.2.1), and implicit against explicit integration."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.plots import uniaxial as uniaxial_plots
from asperity.uniaxial import scene

Config = Mapping[str, Any]


def uniaxial_dataset(uniaxial: Config, units_cfg: Config) -> xr.Dataset:
    """Every test of a scene's ``uniaxial`` section (dims test, step)."""
    return scene.run_uniaxial_scene(uniaxial, units_cfg)


def uniaxial_figure(ds: xr.Dataset):
    return uniaxial_plots.uniaxial_figure(ds)


def accuracy_dataset(study: Config) -> xr.Dataset:
    """The integrators over their tolerance sweeps against an ODE reference."""
    if not study.get("tests"):
        raise ValueError("config/config.yaml: key accuracy_bodner_partom.tests: no tests given")
    reference = study.get("reference", {})
    return scene.accuracy_study(
        study["tests"], study.get("units", {}), tolerances=study.get("tolerances"),
        pairing=study.get("pairing"), implicit_outputs=study.get("implicit_outputs", 100),
        explicit_outputs=study.get("explicit_outputs", 20), target=study.get("target", 0.01),
        reference_rtol=reference.get("rtol", 1e-10), reference_method=reference.get("method", "LSODA"))


def accuracy_figure(ds: xr.Dataset):
    return uniaxial_plots.uniaxial_accuracy_figure(ds)
