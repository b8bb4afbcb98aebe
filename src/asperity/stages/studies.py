"""Stage `studies` (workflow/rules/studies.smk): the studies that are no scene, run from a
section of config/config.yaml (`asperity.studies`): the report's single-asperity studies,
and the tables gathered over several scenes' results."""

from __future__ import annotations

import logging
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity.io.netcdf import read_dataset
from asperity.plots import adhesion as adhesion_plots
from asperity.studies import adhesion, friction_report, j2_sphere, route_errors, summit_scale, validity_summary

Config = Mapping[str, Any]
log = logging.getLogger(__name__)


def adhesion_curves_dataset(study: Config) -> xr.Dataset:
    """Fig. 7.6: smooth elastic aluminum asperities with adhesion, approached and retracted
    at each tip radius (`asperity.studies.adhesion.smooth_aluminum_curves`)."""
    return adhesion.smooth_aluminum_curves(
        radii=tuple(study["radii"]), d=study["equilibrium_separation"], dgamma=study["dgamma"],
        w_max=study["max_interference"], accuracy=study["accuracy"])


def adhesion_curves_figure(ds: xr.Dataset):
    return adhesion_plots.curves_figure(ds)


def route_errors_dataset(files: Mapping[str, Mapping[str, Any]]) -> xr.Dataset:
    """Every route's error against the boundary elements, per reference scene
    (`asperity.studies.route_errors`); `files`: scene -> its ``comparison``, ``reference``
    and ``surface`` files, and ``routes``: route -> its interface file."""
    return route_errors.route_errors({
        scene: (*(read_dataset(paths[k]) for k in ("comparison", "reference", "surface")),
                {route: read_dataset(path) for route, path in paths.get("routes", {}).items()})
        for scene, paths in files.items()})


def route_errors_figure(ds: xr.Dataset):
    return route_errors.route_errors_figure(ds)


#: the interacting route's asperity laws the scale study runs (`asperity.stages.routes.LAWS`
#: less ``fe``, which needs a scene's finite element table)
SCALE_LAWS = ("shape", "elliptic", "hertz")


def _routes_at_scale(z0, dx: float, dy: float, factor: float, h_sigma, modulus: float) -> dict:
    """One map at one lateral scale lambda_s = factor max(dx, dy) (0: the pixel's peaks,
    unfiltered), prepared as the surface stage prepares it: its summits, the elastic boundary
    elements, the interacting route with each of `SCALE_LAWS` and Persson's theory, and each
    route's errors against the boundary elements (`reference.errors_against`)."""
    from asperity.homogenize.interacting import interacting_interface
    from asperity.references import persson
    from asperity.references.boundary_element import solve_map
    from asperity.stages.reference import errors_against
    from asperity.stages.routes import INTERACTING_ACCEPT, INTERACTING_TOLERANCE, asperity_law
    from asperity.surface.maps import map_peaks
    from asperity.surface.summits import lowpass_map, map_summits

    scale = factor * max(dx, dy)
    if factor > 0:
        z = lowpass_map(z0, dx, dy, scale)
        peaks = map_summits(z0, dx, dy, scale).rename(summit="peak")
    else:
        z = np.array(z0, dtype=float)
        peaks = map_peaks(z, dx, dy)
    peaks = peaks.isel(peak=np.flatnonzero(peaks["curvature"].values > 0))  # as the route does
    z = z - np.nanmean(z)
    sigma = float(np.nanstd(z))
    h = np.asarray(h_sigma) * sigma
    ny, nx = z.shape
    bem = solve_map(z, dx, dy, h, modulus)
    p_ref, a_ref = bem["nominal_pressure"].values, bem["contact_area_ratio"].values
    out = {"scale": scale, "sigma": sigma, "summits": peaks.sizes["peak"],
           "summit_density": peaks.sizes["peak"] / (nx * dx * ny * dy),
           "mean_curvature": float(peaks["curvature"].mean()),
           "bem_area_ratio": a_ref, "cells_per_patch": bem["cells_per_patch"].values, "routes": {}}
    curves = {}
    for law in SCALE_LAWS:
        try:
            ds = interacting_interface(peaks["x"].values, peaks["y"].values, peaks["height"].values,
                                       peaks["curvature"].values, h, modulus, (nx * dx, ny * dy),
                                       law=asperity_law(law, z, dx, dy, peaks, modulus),
                                       tolerance=INTERACTING_TOLERANCE, accept=INTERACTING_ACCEPT)
        except (RuntimeError, ValueError) as err:  # a failed route is a row of NaN, said in the log
            log.warning("scale study: interacting_%s at %g grid steps failed: %s", law, factor, err)
            continue
        curves[f"interacting_{law}"] = ds
    q, C = persson.isotropic_spectrum(z, dx, dy)
    curves["persson"] = persson.persson_interface(q, C, modulus, h)
    for name, ds in curves.items():
        p, a = ds["nominal_pressure"].values, ds["contact_area_ratio"].values
        out["routes"][name] = errors_against(p, p, a, p_ref, a_ref)
    return out


def scale_study_dataset(files: Mapping[str, str], scenes: Mapping[str, Config], study: Config) -> xr.Dataset:
    """The lateral scale of the asperities against what it changes (issue #48, item 1): for
    the map of each scene (scene -> its map file, and its ``surface``, ``units`` and
    ``material`` sections), with the scene's form removed and no low-pass, and each scale of
    ``study["scales"]`` (in grid steps), the summits, the elastic boundary elements'
    resolution and every route's errors against them at the separations
    ``study["separations"]`` (start, stop, count in sigma of the prepared map)."""
    from asperity.io.topography import read_measurement
    from asperity.stages.routes import contact_modulus_and_hardness
    from asperity.stages.surface import prepared_roughness, reading
    from asperity.units import attrs

    maps = {}
    for scene, path in files.items():
        cfg = scenes[scene]
        surface = {k: v for k, v in cfg["surface"].items() if k != "scale"}  # every scale here
        data = read_measurement(path, **reading(surface, cfg["units"]))
        z = prepared_roughness(data.heights, data.spacing, surface, cfg["units"], defined=data.defined)
        maps[scene] = (z, *data.spacing, contact_modulus_and_hardness(cfg["material"], cfg["units"])[0])

    factors = np.asarray(study["scales"], dtype=float)
    h_sigma = np.linspace(*study["separations"])
    routes = [f"interacting_{law}" for law in SCALE_LAWS] + ["persson"]
    n_s, n_f, n_h, n_r = len(maps), factors.size, h_sigma.size, len(routes)
    per_scale = {k: np.full((n_s, n_f), np.nan) for k in ("scale", "sigma", "summits", "summit_density",
                                                          "mean_curvature")}
    per_h = {k: np.full((n_s, n_f, n_h), np.nan) for k in ("bem_area_ratio", "cells_per_patch")}
    errors = {k: np.full((n_s, n_f, n_r, n_h), np.nan) for k in ("pressure_error", "area_error")}
    for i, (scene, (z, dx, dy, modulus)) in enumerate(maps.items()):  # a few maps and scales, each vectorized
        for j, factor in enumerate(factors):
            log.info("scale study: %s at %g grid steps", scene, factor)
            row = _routes_at_scale(z, dx, dy, factor, h_sigma, modulus)
            for k in per_scale:
                per_scale[k][i, j] = row[k]
            for k in per_h:
                per_h[k][i, j] = row[k]
            for r, name in enumerate(routes):
                if name in row["routes"]:
                    errors["pressure_error"][i, j, r], errors["area_error"][i, j, r] = row["routes"][name]
    meta = {
        "scale": ("m", "lateral scale lambda_s of the asperities (0: the pixel's peaks, unfiltered)"),
        "sigma": ("m", "rms height of the prepared map"),
        "summits": ("1", "summits with a positive mean curvature"),
        "summit_density": ("1/m^2", "summits per unit area"),
        "mean_curvature": ("1/m", "mean of the summits' mean curvature"),
        "bem_area_ratio": ("1", "real contact area ratio of the elastic boundary elements"),
        "cells_per_patch": ("1", "mean grid cells per contact patch of the elastic boundary elements"),
        "pressure_error": ("1", "route's nominal pressure at equal separation over the boundary elements', less 1"),
        "area_error": ("1", "route's contact area ratio at equal pressure over the boundary elements', less 1"),
    }
    data = {k: (("scene", "factor"), v, attrs(*meta[k])) for k, v in per_scale.items()}
    data |= {k: (("scene", "factor", "separation"), v, attrs(*meta[k])) for k, v in per_h.items()}
    data |= {k: (("scene", "factor", "route", "separation"), v, attrs(*meta[k])) for k, v in errors.items()}
    return xr.Dataset(data, coords={
        "scene": ("scene", list(maps), attrs("", "scene whose map is studied")),
        "factor": ("factor", factors, attrs("1", "lateral scale in grid steps, lambda_s / max(dx, dy)")),
        "route": ("route", routes, attrs("", "route against the boundary elements")),
        "separation": ("separation", h_sigma, attrs("1", "separation of the flat over sigma of the prepared map")),
    })


def scale_study_figure(ds: xr.Dataset):
    return summit_scale.scale_study_figure(ds)


def j2_sphere_dataset(study: Config) -> xr.Dataset:
    """The J2 sphere beside Kogut and Etsion's fits and the hardness-limited boundary
    elements (`asperity.studies.j2_sphere`)."""
    return j2_sphere.j2_sphere_study(study["youngs_modulus"], study["poisson"], study["yield_stress"],
                                     study["radius"], presets=tuple(study["presets"]), cells=study["cells"])


def j2_sphere_figure(ds: xr.Dataset):
    return j2_sphere.j2_sphere_figure(ds)


def validity_summary_dataset(files: Mapping[str, Mapping[str, str]]) -> xr.Dataset:
    """Where each scene holds (`asperity.studies.validity_summary`); `files`: scene -> its
    ``interface`` and ``surface`` files."""
    return validity_summary.validity_summary({
        scene: (read_dataset(paths["interface"]), read_dataset(paths["surface"])) for scene, paths in files.items()})


def flow_stresses(material_cfg: Config, units_cfg: Config) -> tuple[float, float]:
    """The body's initial and saturated uniaxial flow stress (Pa): Bodner-Partom's steady
    flow at 1e-3 1/s with the initial and the saturated hardness Z0, Z1 (8.2.1); J2's yield
    stress twice; NaN for an elastic body."""
    from asperity import scene
    from asperity.fe.materials.bodner_partom import BodnerPartom
    from asperity.uniaxial.point import uniaxial_flow_stress

    material = scene.Material.from_scene(material_cfg, scene.Units.from_section(units_cfg))
    if material.model not in ("j2", "bodner_partom"):
        return np.nan, np.nan
    body = scene.build(material, ["plasticity"])
    if isinstance(body, BodnerPartom):
        return float(uniaxial_flow_stress(body, 1e-3)), float(uniaxial_flow_stress(body, 1e-3, body.Z1))
    y = float(getattr(body, "yield_stress", np.nan))
    return y, y


def friction_report_dataset(files: Mapping[str, Mapping[str, str]], scenes: Mapping[str, Config]) -> xr.Dataset:
    """mu_shear against the report's (`asperity.studies.friction_report`); `files`: scene ->
    its ``friction`` and ``interface`` files; `scenes`: scene -> its ``material`` and
    ``units`` sections."""
    return friction_report.friction_against_report({
        scene: (read_dataset(paths["friction"]), read_dataset(paths["interface"]),
                flow_stresses(scenes[scene]["material"], scenes[scene]["units"]))
        for scene, paths in files.items()})
