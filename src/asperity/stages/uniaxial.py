"""Stage `uniaxial` (workflow/rules/uniaxial.smk): Bodner-Partom material points under the
report's uniaxial histories (5, 6.3.1, 8.2.1), and implicit against explicit integration."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.scene import Units
from asperity.scene.uniaxial import IntegratorStudy, tests
from asperity.studies import uniaxial as uniaxial_study

Config = Mapping[str, Any]
# the figure functions import their plots (matplotlib) themselves: the data jobs start without


def uniaxial_dataset(uniaxial: Config, units_cfg: Config) -> xr.Dataset:
    """Every test of a scene's ``uniaxial`` section (dims test, step)."""
    return uniaxial_study.run_uniaxial_scene(tests(uniaxial["tests"], Units.from_section(units_cfg)))


def uniaxial_figure(ds: xr.Dataset):
    from asperity.plots import uniaxial as uniaxial_plots

    return uniaxial_plots.uniaxial_figure(ds)


def accuracy_dataset(study: Config) -> xr.Dataset:
    """The integrators over their tolerance sweeps against an ODE reference."""
    return uniaxial_study.accuracy_study(IntegratorStudy.from_section(study))


def accuracy_figure(ds: xr.Dataset):
    from asperity.plots import uniaxial as uniaxial_plots

    return uniaxial_plots.uniaxial_accuracy_figure(ds)
