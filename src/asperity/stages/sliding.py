"""Stage `sliding` (workflow/rules/sliding.smk): one 3-D asperity pressed and slid by a
rigid flat (report 9.2, Figs. 9.4, 9.5)."""

from __future__ import annotations

from typing import Any, Callable, Mapping

import xarray as xr

from asperity.fe.solid3d import solve_sliding_scene
from asperity.plots import sliding as sliding_plots

Config = Mapping[str, Any]


def sliding_dataset(scene_name: str, sliding: Config, units_cfg: Config, accuracy: str,
                    progress: Callable[..., None] | None = None) -> xr.Dataset:
    """Force histories, the deformed section and the largest deformation; a failure names
    the scene."""
    try:
        return solve_sliding_scene(sliding, units_cfg, accuracy, progress=progress)
    except Exception as err:
        raise RuntimeError(f"scene {scene_name}, sliding asperity: {err}") from err


def sliding_figure(ds: xr.Dataset, units_cfg: Config):
    return sliding_plots.sliding_figure(ds, units_cfg["length"])
