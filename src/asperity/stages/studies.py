"""Stage `studies` (workflow/rules/studies.smk): the studies that are no scene, run from a
section of config/config.yaml (`asperity.studies`): the report's single-asperity studies,
and the tables gathered over several scenes' results."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity.io.netcdf import read_dataset
from asperity.plots import adhesion as adhesion_plots
from asperity.studies import (adhesion, adhesion_report, friction_report, j2_sphere, plane_strain_table,
                              route_errors, summit_scale, validity_summary)

Config = Mapping[str, Any]


def adhesion_curves_dataset(study: Config) -> xr.Dataset:
    """Fig. 7.6: smooth elastic aluminum asperities with adhesion, approached and retracted
    at each tip radius (`asperity.studies.adhesion.smooth_aluminum_curves`)."""
    return adhesion.smooth_aluminum_curves(
        radii=tuple(study["radii"]), d=study["equilibrium_separation"], dgamma=study["dgamma"],
        w_max=study["max_interference"], accuracy=study["accuracy"])


def adhesion_curves_figure(ds: xr.Dataset):
    return adhesion_plots.curves_figure(ds)


def files_by_scene(inputs) -> dict:
    """The input files of a study rule that gathers scenes, keyed ``<scene>__<file>`` or
    ``<scene>__route__<route>`` (workflow/rules/common.smk), as scene -> {file: path,
    ``routes``: {route: path}}."""
    files: dict = {}
    for key, path in inputs:
        scene, kind, *route = key.split("__")
        if route:
            files.setdefault(scene, {}).setdefault("routes", {})[route[0]] = path
        else:
            files.setdefault(scene, {})[kind] = path
    return files


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


def _scale_routes(modulus: float) -> dict:
    """The routes of the scale study, each ``route(z, dx, dy, peaks, h) -> interface``: the
    interacting route with each of `SCALE_LAWS` (its tolerances and laws as the route
    stage's) and Persson's theory."""
    from asperity.homogenize.interacting import interacting_interface
    from asperity.references import persson
    from asperity.stages.routes import INTERACTING_ACCEPT, INTERACTING_TOLERANCE, asperity_law

    def interacting(law):
        def route(z, dx, dy, peaks, h):
            ny, nx = z.shape
            return interacting_interface(peaks["x"].values, peaks["y"].values, peaks["height"].values,
                                         peaks["curvature"].values, h, modulus, (nx * dx, ny * dy),
                                         law=asperity_law(law, z, dx, dy, peaks, modulus),
                                         tolerance=INTERACTING_TOLERANCE, accept=INTERACTING_ACCEPT)
        return route

    def persson_route(z, dx, dy, peaks, h):
        return persson.persson_interface(*persson.isotropic_spectrum(z, dx, dy), modulus, h)

    return {**{f"interacting_{law}": interacting(law) for law in SCALE_LAWS}, "persson": persson_route}


def scale_study_dataset(files: Mapping[str, str], scenes: Mapping[str, Config], study: Config) -> xr.Dataset:
    """The lateral scale of the asperities against what it changes (issue #48, item 1;
    `asperity.studies.summit_scale.scale_study`): the map of each scene (scene -> its map
    file, and its ``surface``, ``units`` and ``material`` sections) read and prepared as the
    surface stage does, without its low-pass (the study applies each scale of
    ``study["scales"]``), at the separations ``study["separations"]`` (start, stop, count
    in sigma of the prepared map)."""
    from asperity.io.topography import read_measurement
    from asperity.references.boundary_element import solve_map
    from asperity.stages.reference import errors_against
    from asperity.stages.routes import contact_modulus_and_hardness
    from asperity.stages.surface import prepared_roughness, reading

    maps = {}
    for scene, path in files.items():
        cfg = scenes[scene]
        surface = {k: v for k, v in cfg["surface"].items() if k != "scale"}  # every scale here
        data = read_measurement(path, **reading(surface, cfg["units"]))
        z = prepared_roughness(data.heights, data.spacing, surface, cfg["units"], defined=data.defined)
        modulus = contact_modulus_and_hardness(cfg["material"], cfg["units"])[0]
        maps[scene] = (z, *data.spacing, lambda z, dx, dy, h, m=modulus: solve_map(z, dx, dy, h, m),
                       _scale_routes(modulus))
    return summit_scale.scale_study(maps, study["scales"], np.linspace(*study["separations"]), errors_against)


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


def adhesion_report_dataset(files: Mapping[str, str]) -> xr.Dataset:
    """An adhesive scene beside its elastic twin (`asperity.studies.adhesion_report`);
    `files`: the scene's ``asperities``, ``interface``, ``friction`` and ``surface`` files,
    the twin's ``twin_interface``, ``twin_friction`` and ``twin_surface``."""
    return adhesion_report.adhesion_report(
        tuple(read_dataset(files[k]) for k in ("asperities", "interface", "friction", "surface")),
        tuple(read_dataset(files[f"twin_{k}"]) for k in ("interface", "friction", "surface")))


def plane_strain_table_dataset(files: Mapping[str, str]) -> xr.Dataset:
    """The plane-strain scenes side by side (`asperity.studies.plane_strain_table`);
    `files`: ``<scene>__<preset>`` -> its plane_strain.nc."""
    return plane_strain_table.plane_strain_table(
        {key.replace("__", "@"): read_dataset(path) for key, path in files.items()})
