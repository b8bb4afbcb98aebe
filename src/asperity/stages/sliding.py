"""Stage `sliding` (workflow/rules/sliding.smk): one 3-D asperity pressed and slid by a
rigid flat (report 9.2, Figs. 9.4, 9.5)."""

from __future__ import annotations

from typing import Any, Callable, Mapping

import xarray as xr

from asperity.fe.drivers.solid3d import solve_sliding
from asperity.scene import Sliding, Units

Config = Mapping[str, Any]
# the figure functions import their plots (matplotlib) themselves: the data jobs start without


def sliding_dataset(scene_name: str, sliding: Config, units_cfg: Config, accuracy: str,
                    progress: Callable[..., None] | None = None) -> xr.Dataset:
    """Force histories, the deformed section and the largest deformation of the scene's
    ``sliding`` section at the accuracy preset `accuracy` (the section's steps, mesh
    sizes and inelastic step limit override the preset's); a failure names the scene."""
    try:
        s = Sliding.from_section(sliding, Units.from_section(units_cfg))
        ds = solve_sliding(s.geometry(), s.body(), s.motion(), s.friction(),
                           accuracy=s.preset(accuracy), penalty_factor=s.penalty_factor,
                           progress=progress)
    except Exception as err:
        raise RuntimeError(f"scene {scene_name}, sliding asperity: {err}") from err
    ds.attrs["accuracy"] = accuracy
    return ds


def sliding_figure(ds: xr.Dataset, units_cfg: Config):
    from asperity.plots import sliding as sliding_plots

    return sliding_plots.sliding_figure(ds, units_cfg["length"])
