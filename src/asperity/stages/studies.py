"""Stage `studies` (workflow/rules/studies.smk): the report's single-asperity studies that
are no scene, run from a section of config/config.yaml (`asperity.studies`)."""

from __future__ import annotations

from typing import Any, Mapping

import xarray as xr

from asperity.plots import adhesion as adhesion_plots
from asperity.studies import adhesion

Config = Mapping[str, Any]


def adhesion_curves_dataset(study: Config) -> xr.Dataset:
    """Fig. 7.6: smooth elastic aluminum asperities with adhesion, approached and retracted
    at each tip radius (`asperity.studies.adhesion.smooth_aluminum_curves`)."""
    return adhesion.smooth_aluminum_curves(
        radii=tuple(study["radii"]), d=study["equilibrium_separation"], dgamma=study["dgamma"],
        w_max=study["max_interference"], accuracy=study["accuracy"])


def adhesion_curves_figure(ds: xr.Dataset):
    return adhesion_plots.curves_figure(ds)
