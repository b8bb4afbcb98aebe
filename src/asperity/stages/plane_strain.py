"""Stage `plane_strain` (workflow/rules/plane_strain.smk): a plane-strain asperity of
6061-T4 aluminum pressed by a rigid flat, elastic and viscoplastic, on a coarse and a
refined mesh (report 6.3.2, Figs. 6.15-6.18; 6.3.3, Figs. 6.19-6.23)."""

from __future__ import annotations

import logging
from typing import Any, Callable, Mapping

import xarray as xr

from asperity.studies.plane_strain import plane_strain_study
from asperity.scene.plane_strain import PlaneStrain

Config = Mapping[str, Any]
# the figure functions import their plots (matplotlib) themselves: the data jobs start without
log = logging.getLogger("asperity")


def plane_strain_dataset(scene_name: str, scene: Config, accuracy: str,
                         progress: Callable[..., None] | None = None) -> xr.Dataset:
    """The study of the scene's ``plane_strain`` section (with its ``material``, ``units``
    and ``effects``) at the accuracy preset `accuracy`; a failure names the scene."""
    try:
        s = PlaneStrain.from_scene(scene)
        ds = plane_strain_study(s.geometry(), s.body(), s.elastic(), s.history(),
                                s.presets(accuracy), points=s.points, kinematics=s.kinematics,
                                progress=progress)
    except Exception as err:
        raise RuntimeError(f"scene {scene_name}, plane-strain asperity: {err}") from err
    ds.attrs.update(accuracy=accuracy, shape=s.shape, velocity=s.velocity)
    if s.shape == "truncated_v":
        ds.attrs.update(pitch=s.pitch, groove_angle=s.groove_angle, top_width=s.top_width,
                        sharp_ridge_height=s.sharp_ridge_height)
    else:
        ds.attrs.update(radius=s.radius, cap_angle=s.cap_angle)
    if s.test_load is not None:
        ds.attrs["test_load"] = s.test_load
    warnings = []
    if s.unloading and ds["residual_interference"].isnull().any():
        never = ds.isel(mesh=ds["residual_interference"].isnull().values)
        strain = {str(m): float(e) for m, e in zip(never["mesh"].values,
                                                   never["largest_inelastic_strain"].values)}
        warnings.append(f"the unloading force reached zero only with the flat back at first "
                        f"touch: no permanent set resolved (mesh: largest nonelastic strain "
                        f"{strain})")
    inverted = {str(m): int(n) for m, n in zip(ds["mesh"].values, ds["inverted_elements"].values)
                if n > 0}
    if inverted:
        message = f"the displacement at the end turns elements inside out (mesh: count {inverted})"
        if s.kinematics == "small":
            message += (": the small-strain solution is past its range there (the effect "
                        "finite_strain solves it in finite strain)")
        warnings.append(message)
    for message in warnings:
        log.warning(message)
    if warnings:
        ds.attrs["warnings"] = "; ".join(warnings)
    return ds


def plane_strain_figure(ds: xr.Dataset, units_cfg: Config):
    from asperity.plots import plane_strain as plane_strain_plots

    return plane_strain_plots.plane_strain_figure(ds, units_cfg["length"])


def plane_strain_mesh_figure(ds: xr.Dataset, units_cfg: Config):
    from asperity.plots import plane_strain as plane_strain_plots

    return plane_strain_plots.plane_strain_mesh_figure(ds, units_cfg["length"])
