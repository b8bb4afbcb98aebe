"""The routes beyond independent asperities (workflow/rules/routes.smk): the interface law
of a height map from interacting asperities, from Persson's theory, or from the
boundary-element contact of the map itself, each in the contract of every
``interface.nc`` (DESIGN.md: Routes).

A scene asks for one with its ``route`` section; a reference scene's ``routes`` may
hold them beside the statistical routes, each run as the scene ``<scene>+<route>``
(`asperity.stages.reference.route_scene`).

One definition of separation and gap in every route, the boundary elements' with a
periodic boundary: the map is one period of an infinite interface, the separation h
is the height of the rigid flat above the mean plane of the map's (prepared) heights,
and the elastic displacement has zero mean (no q = 0 mode), so the deformed surface's
mean plane stays where it was and the mean gap of an elastic contact equals h.  The
interacting asperities use the same periodic half-space with zero mean (its Green's
function, `asperity.homogenize.interacting`), and Persson's theory is written in the
mean gap itself.  Hence pressure at equal separation is pressure at equal mean gap in
all of them.

Every route runs on the map as the surface stage prepares it (form removed, filtered
at the scene's lateral scale ``surface.scale``: `asperity.stages.surface`), so the
boundary elements, the spectrum of Persson's theory and the summits of the
interacting route see the same heights.
"""

from __future__ import annotations

import logging
import math
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import scene
from asperity.homogenize import validity
from asperity.io.netcdf import scene_config
from asperity.population.density import heights_at_ratios, scene_separations
from asperity.references.hertz import plane_strain_modulus
from asperity.scene.interface import check_positive
# the fewest contacting cells per patch at which the boundary elements resolve the contact
from asperity.stages.reference import MIN_CELLS_PER_PATCH
# the map as the surface stage reads and prepares it: the script of the route rule calls
# this module only
from asperity.stages.surface import prepared_roughness, reading  # noqa: F401
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]

#: the routes a scene's ``route.kind`` names
KINDS = ("interacting", "persson", "boundary_elements", "anisotropic")

#: the interface variables every route writes: units and long names
CONTRACT = {
    "nominal_pressure": ("Pa", "nominal pressure: total force over the nominal area"),
    "contact_area_ratio": ("1", "real contact area ratio A/A0"),
    "normal_stiffness": ("Pa/m", "normal stiffness -dp/dh per unit nominal area"),
    "contact_count": ("1/m^2", "contact spots per unit nominal area"),
    "mean_gap": ("m", "mean gap between the flat and the deformed surface"),
}


def separations(homogenization_cfg: Config, surface_ds: xr.Dataset, units_cfg: Config) -> np.ndarray:
    """The separations [m] of the scene (``homogenization.separations``; in ``sigma``, the
    standard deviation of the prepared heights, as the reference's)."""
    units = scene.Units.from_section(units_cfg)
    return scene_separations(scene.Homogenization.from_section(homogenization_cfg, units), surface_ds)


def contact_modulus_and_hardness(material_cfg: Config, units_cfg: Config) -> tuple[float, float]:
    """E* = E / (1 - nu^2) [Pa] of the body against a rigid flat, and its hardness [Pa]
    (`asperity.homogenize.validity.hardness_of`: given, or Tabor's 2.8 Y; NaN if unknown)."""
    body = scene.Material.from_scene(material_cfg, scene.Units.from_section(units_cfg))
    modulus = float(plane_strain_modulus(body.youngs_modulus, body.poisson))
    return modulus, validity.hardness_of(body)[0]


def _hardness_for(route_cfg: Config, hardness: float) -> float | None:
    """The cap of a route limited by the hardness (None: elastic)."""
    if route_cfg["limit"] != "hardness":
        return None
    if not math.isfinite(hardness):
        raise ValueError("route.limit: hardness needs material.hardness or material.yield_stress "
                         "in the scene")
    return hardness


def _boundary_elements(z, dx, dy, h, modulus, hardness, route_cfg) -> xr.Dataset:
    from asperity.references.boundary_element import solve_map

    cap = _hardness_for(route_cfg, hardness)
    ds = solve_map(z, dx, dy, h, modulus, hardness=cap, boundary="periodic",
                   yield_pressure=hardness if cap is None and math.isfinite(hardness) else None,
                   tolerance=float(route_cfg["tolerance"]), max_iterations=int(route_cfg["max_iterations"]))
    ds.attrs["route_cpu_time"] = ds.attrs.pop("cpu_time", math.nan)
    return ds


def _persson(z, dx, dy, h, modulus, hardness, route_cfg) -> xr.Dataset:
    from asperity.references import persson

    q, C = persson.isotropic_spectrum(z, dx, dy)
    return persson.persson_interface(q, C, modulus, h, hardness=_hardness_for(route_cfg, hardness),
                                     gamma=float(route_cfg["gamma"]))


#: the force laws of the interacting route's asperities (``route.law``); ``fe``: the
#: finite element asperities the scene plans (asperities.nc)
LAWS = ("shape", "elliptic", "hertz", "fe")
#: the interacting route's Newton tolerance: the largest residual of its equations over
#: the largest interference
INTERACTING_TOLERANCE = 1e-8
#: where Newton stalls (the equations are semismooth: a neighbour's summit at the edge of
#: a spot's field), the residual it accepts, over the largest interference; each
#: separation's residual is in the file, and a warning names those above the tolerance
INTERACTING_ACCEPT = 1e-2


def principal_curvatures(surface_ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """kappa_1 >= kappa_2 of the peaks of surface.nc, from their second derivatives
    (positive at a summit; kappa_2 <= 0 where the peak is a ridge or saddle at this scale)."""
    zxx, zyy, zxy = (surface_ds[k].values for k in ("z_xx", "z_yy", "z_xy"))
    mean, half = -(zxx + zyy) / 2.0, np.sqrt(((zxx - zyy) / 2.0) ** 2 + zxy ** 2)
    return mean + half, mean - half


def _sphere_laws(asperities: xr.Dataset, heights, tip, modulus: float):
    """The finite element spheres of asperities.nc (on height, curvature, interference) and
    Hertz's at the points (`heights`, `tip` curvature), as ``law(w, index)``, and how far
    each was computed (m; the table's ``extrapolated`` points lie beyond). The force and
    area are interpolated on the table's interference grid (linear, as the homogenization
    does: `asperity.homogenize.table`); a tip sharper or blunter than the table's spheres
    takes its nearest sphere at equal w/R (the self-similarity of a sphere of a material
    without a length of its own, as the population's plan uses)."""
    from asperity.homogenize.asperity_laws import hertz_law, tabulated_law
    from asperity.homogenize.table import interpolate_points, response_table

    geometry = scene_config(asperities).get("asperity", {}).get("geometry")
    if geometry not in (None, "sphere"):
        raise ValueError(f"route.law fe: the finite element asperities must be spheres (asperity.geometry: "
                         f"sphere), whose departure from Hertz the summits' own shapes take; got {geometry!r}")
    names = ["force", "contact_area"] + (["extrapolated"] if "extrapolated" in asperities else [])
    table = response_table(asperities[names].astype(float))
    grid = table.interference
    if grid[0] < 0:
        raise ValueError("route.law fe: asperities with attraction before contact (adhesion) "
                         "have no departure from Hertz's sphere to carry")
    tip = np.asarray(tip, dtype=float)
    z = np.asarray(heights, dtype=float)[:, None]
    k = np.clip(tip, table.curvatures[0], table.curvatures[-1])[:, None]
    values = interpolate_points(table, z, k, grid[None, :])  # (points, levels, [force, area, ...])
    computed = values[..., 2] < 0.5 if len(names) == 3 else np.ones(values.shape[:2], dtype=bool)
    reach = grid[np.where(computed.any(axis=1), grid.size - 1 - np.argmax(computed[:, ::-1], axis=1), 0)]
    stretch = tip / k[:, 0]
    table_sphere, table_hertz = tabulated_law(grid, values[..., 0], values[..., 1]), hertz_law(modulus, k[:, 0])

    def at_equal_depth(law):
        def scaled(w, index):
            f, a, df, da = law(np.asarray(w) * stretch[index], index)
            return f, a, df * stretch[index], da * stretch[index]
        return scaled

    return at_equal_depth(table_sphere), at_equal_depth(table_hertz), reach / stretch


def fe_law(asperities: xr.Dataset, heights, shape, tip, modulus: float):
    """The law of each summit (of height `heights`) with the scene's finite element
    asperities (asperities.nc; spheres): the summit's own `shape` law, with the departure
    of the finite element sphere of its tip curvature `tip` from Hertz's sphere (force
    and area ratios, `asperity.homogenize.asperity_laws.departure_law`; the spheres as
    `_sphere_laws` reads them), so that plasticity (or rate, or an elastic mesh's error)
    is the sphere's and the shape is the summit's. Past the interference the sphere was
    computed to, the ratios keep their last computed values."""
    from asperity.homogenize.asperity_laws import departure_law

    return departure_law(shape, *_sphere_laws(asperities, heights, tip, modulus))


def sphere_departure(asperities: xr.Dataset, modulus: float):
    """``departure(s)``: the force and area ratios of the scene's finite element sphere to
    Hertz's, and their slopes, against s = w kappa (w/R), for
    `asperity.homogenize.anisotropic.with_departure`: the table's sphere computed farthest
    in w/R (at the table's middle height), its ratios held past that. A function of w/R
    alone for a material without a length of its own (elastic, J2), as the population's
    plan derives its spheres."""
    from asperity.homogenize.asperity_laws import departure_law

    curvatures = asperities["curvature"].values.astype(float)
    middle = float(asperities["height"].values[asperities.sizes["height"] // 2])
    model, sphere, reach = _sphere_laws(asperities, np.full(curvatures.size, middle), curvatures, modulus)
    best = int(np.argmax(reach * curvatures))
    k = curvatures[best]

    def unit(w, index):
        one = np.ones(np.shape(w))
        return one, one, 0.0 * one, 0.0 * one

    law = departure_law(unit, model, sphere, reach)
    top = float(reach[best]) * k

    def departure(s, t):
        s = np.asarray(s, dtype=float)
        rf, ra, drf, _ = law(s / k, np.full(s.shape, best))
        return rf, ra, drf / k, s > top

    return departure


def _log_interp(s, nodes, values):
    """Values at `s` > 0 of the piecewise linear function of ln s through (`nodes`,
    `values`) (nodes increasing), held past the ends, and its slope d/ds there."""
    x, lx = np.log(np.maximum(s, nodes[0])), np.log(nodes)
    i = np.clip(np.searchsorted(lx, x) - 1, 0, lx.size - 2)
    slope = (values[i + 1] - values[i]) / (lx[i + 1] - lx[i])
    inside = (s > nodes[0]) & (s < nodes[-1])
    value = np.where(s >= nodes[-1], values[-1], values[i] + slope * (x - lx[i]))
    return value, np.where(inside, slope / np.maximum(s, nodes[0]), 0.0)


def elliptic_departure(asperities: xr.Dataset):
    """``departure(s, t)``: the force and area ratios of the J2 elliptic summit of ratio t
    to the elastic one (`asperity.population.kinds.elliptic`: asperities.nc on (ratio,
    level)), the force ratio's slope in s, and whether s lies past the jobs' reach, for
    `asperity.homogenize.anisotropic.with_departure`. s = w kappa, kappa the curvature of
    the sphere of equal Hertz peak pressure (the jobs' ``scaled_interference``): each job's
    ratios are piecewise linear in ln s, held below its first level (elastic there) and
    past its last; between two jobs' ratios linear in ln t; a ratio outside the jobs'
    takes the nearest job's at equal s, that is at equal peak pressure, the equivalence
    `sphere_departure` rests on (within 2 % for the J2 ellipse of t = 1/4:
    tests/fe/test_elliptic_3d.py)."""
    ratios = asperities["ratio"].values.astype(float)
    scaled = asperities["scaled_interference"].values
    force, area = (asperities[k].values for k in ("force_departure", "area_departure"))
    reach = scaled[:, -1]
    lt = np.log(ratios)

    def departure(s, t):
        s, t = np.broadcast_arrays(np.asarray(s, dtype=float), np.asarray(t, dtype=float))
        per_job = [[_log_interp(s, scaled[j], v[j]) for v in (force, area)] for j in range(ratios.size)]
        rf, drf = (np.stack([job[0][m] for job in per_job]) for m in (0, 1))  # (job, ...)
        ra = np.stack([job[1][0] for job in per_job])
        if ratios.size == 1:
            return rf[0], ra[0], drf[0], s > reach[0]
        x = np.clip(np.log(np.maximum(t, 1e-300)), lt[0], lt[-1])
        j = np.clip(np.searchsorted(lt, x) - 1, 0, lt.size - 2)
        u = (x - lt[j]) / (lt[j + 1] - lt[j])

        def mix(a):
            return ((1.0 - u) * np.take_along_axis(a, j[None], axis=0)[0]
                    + u * np.take_along_axis(a, j[None] + 1, axis=0)[0])

        return mix(rf), mix(ra), mix(drf), s > np.minimum(reach[j], reach[j + 1])

    return departure


def asperity_law(kind: str, z, dx: float, dy: float, surface_ds: xr.Dataset, modulus: float,
                 asperities: xr.Dataset | None = None):
    """The force law ``law(w, index)`` of the map's asperities for
    `asperity.homogenize.interacting` (`LAWS`):

    * ``shape``: each summit's own shape below its tip, as the axisymmetric profile of its
      watershed basin's bearing area (`asperity.surface.summits.summit_profiles`), pressed
      by Sneddon's solution (`asperity.references.sneddon`); its tip the paraboloid of the
      Gaussian curvature sqrt(kappa_1 kappa_2), which has the same bearing area as the
      elliptic tip;
    * ``elliptic``: Hertz's elliptic contact of the two principal curvatures (a ridge's
      smaller curvature taken as 1/100 of the larger);
    * ``hertz``: the sphere of the mean curvature, Hertz;
    * ``fe``: the ``shape`` law with the departure from Hertz of the scene's finite element
      sphere of the summit's tip curvature (`fe_law`; elastic, J2 or Bodner-Partom as the
      scene's effects and material say).
    """
    from asperity.homogenize.asperity_laws import hertz_law
    from asperity.references.hertz import elliptic_hertz
    from asperity.references.sneddon import profile_law
    from asperity.surface.summits import summit_profiles

    if kind not in LAWS:
        raise ValueError(f"route.law must be one of {', '.join(LAWS)}; got {kind!r}")
    mean = surface_ds["curvature"].values
    k1, k2 = principal_curvatures(surface_ds)
    if kind == "hertz":
        return hertz_law(modulus, mean)
    if kind == "fe" and asperities is None:
        raise ValueError("route.law fe needs the scene's finite element asperities "
                         "(asperity: {model: fe, geometry: sphere} and a population)")
    if kind == "elliptic":
        k2 = np.maximum(k2, k1 / 100.0)

        def law(w, index):
            out = elliptic_hertz(w, k1[index], k2[index], modulus)
            with np.errstate(divide="ignore", invalid="ignore"):  # A grows in proportion to w
                darea = np.where(w > 0, out["contact_area"] / np.where(w > 0, w, 1.0), 0.0)
            return out["force"], out["contact_area"], out["stiffness"], darea

        return law
    tip = np.where(k2 > 0, np.sqrt(np.abs(k1 * k2)), mean)
    radii, slopes = summit_profiles(z, dx, dy, surface_ds["row"].values, surface_ds["column"].values,
                                    tip)
    shape = profile_law(radii, slopes, modulus)
    return shape if kind == "shape" else fe_law(asperities, surface_ds["height"].values, shape, tip,
                                                   modulus)


def _anisotropic(h, surface_ds: xr.Dataset, route_cfg: Config, material_cfg: Config, units_cfg: Config,
                 validity_cfg: Config, effects, asperities: xr.Dataset | None = None) -> xr.Dataset:
    """The summits of the Gaussian anisotropic surface of the map's spectral moments (its
    derivative covariances at the scene's lateral scale, surface.nc), each an elliptic
    Hertz contact (``law: elliptic``), the sphere of its mean curvature (``hertz``) or the
    elliptic contact with the departure from Hertz of the scene's finite element asperities
    (``fe``): its 3-D elliptic summits over the curvature ratio (`elliptic_departure`), or
    its sphere at equal peak pressure (`sphere_departure`); independent (report 2.4.2, 2.5.2:
    `asperity.homogenize.anisotropic`), with the validity of independent asperities
    (`asperity.homogenize.validity.assess`: yield, contact area, interaction, plasticity
    index, Gaussian heights)."""
    from asperity.homogenize import anisotropic
    from asperity.homogenize.validity import peak_statistics, plasticity_of
    from asperity.peaks.anisotropic import AnisotropicDensity

    kind = route_cfg["law"] or "elliptic"
    if kind not in anisotropic.LAWS:
        raise ValueError(f"route.law of the anisotropic route must be one of {', '.join(anisotropic.LAWS)}; "
                         f"got {kind!r}")
    density = AnisotropicDensity.from_surface(surface_ds)
    units = scene.Units.from_section(units_cfg)
    plastic = plasticity_of(scene.Material.from_scene(material_cfg, units), effects or ())
    modulus = plastic.plane_strain_modulus
    if kind == "hertz":
        law = anisotropic.mean_curvature_law(modulus)
    elif kind == "fe":
        if asperities is None:
            raise ValueError("route.law fe needs the scene's finite element asperities "
                             "(asperity: {model: fe, geometry: elliptic or sphere})")
        departure = (elliptic_departure(asperities) if "ratio" in asperities.dims
                     else sphere_departure(asperities, modulus))
        law = anisotropic.with_departure(anisotropic.elliptic_law(modulus), departure)
    else:
        law = anisotropic.elliptic_law(modulus)
    out = anisotropic.anisotropic_interface(density, law, h, plastic.yield_pressure)
    out.attrs.update({"law": kind, "scale": float(surface_ds.attrs.get("scale", math.nan))})
    heights = tuple(float(surface_ds[k]) for k in ("skewness", "kurtosis")) \
        if "skewness" in surface_ds and "kurtosis" in surface_ds else None
    return validity.assess(out, plastic, peak_statistics(density), validity.Limits(**validity_cfg), heights)


def _interacting(z, dx, dy, h, modulus, surface_ds: xr.Dataset, route_cfg: Config,
                 asperities: xr.Dataset | None = None) -> xr.Dataset:
    """The map's own asperities as the surface stage found them (surface.nc: the summits at
    the scene's lateral scale, or the pixel's peaks), each with its force law
    (`asperity_law`), coupled on the map's period."""
    from asperity.homogenize.interacting import interacting_interface

    if "peak" not in surface_ds.dims or surface_ds.sizes["peak"] == 0:
        raise ValueError("the interacting route needs the map's peaks (surface.nc has none)")
    flat = surface_ds["curvature"].values <= 0
    if flat.any():  # pixel-scale peaks whose differences say they are no summit
        log.warning("interacting route: %d of %d peaks without a positive mean curvature left out",
                    int(flat.sum()), flat.size)
        surface_ds = surface_ds.isel(peak=np.flatnonzero(~flat))
    ny, nx = np.shape(z)
    kind = route_cfg["law"] or "shape"
    law = asperity_law(kind, z, dx, dy, surface_ds, modulus, asperities)
    out = interacting_interface(surface_ds["x"].values, surface_ds["y"].values,
                                surface_ds["height"].values, surface_ds["curvature"].values, h,
                                modulus, (nx * dx, ny * dy), law=law, tolerance=INTERACTING_TOLERANCE,
                                accept=INTERACTING_ACCEPT)
    loose = out["residual"].values > INTERACTING_TOLERANCE * (float(surface_ds["height"].max())
                                                              - out["separation"].values)
    if loose.any():
        log.warning("interacting route: Newton stalled at %d of %d separations (largest residual "
                    "%.3g m of the interference equations; the file's `residual`)", int(loose.sum()),
                    loose.size, float(out["residual"].values[loose].max()))
    out.attrs["peaks"] = int(surface_ds.sizes["peak"])
    out.attrs["scale"] = float(surface_ds.attrs.get("scale", math.nan))
    out.attrs["law"] = kind
    return out


def route_interface(z: np.ndarray, dx: float, dy: float, surface_ds: xr.Dataset, route_cfg: Config,
                    material_cfg: Config, homogenization_cfg: Config, units_cfg: Config,
                    validity_cfg: Config, asperities: xr.Dataset | None = None,
                    effects=()) -> xr.Dataset:
    """The interface of the map `z` (m, ``z[i, j] = z(x = j dx, y = i dy)``, prepared as the
    surface stage prepares it) by the route of `route_cfg` (``kind``: one of `KINDS`), on
    the scene's separations, in the contract of ``interface.nc``, with ``valid`` and
    ``validity`` (`assess_route`).  The interacting route takes the map's asperities from
    `surface_ds` (the summits at the scene's lateral scale, or the pixel's peaks)."""
    kind = route_cfg["kind"]
    if kind not in KINDS:
        raise ValueError(f"route.kind must be one of {', '.join(KINDS)}; got {kind!r}")
    h = separations(homogenization_cfg, surface_ds, units_cfg)
    check_positive(h, homogenization_cfg["separations"], heights_at_ratios(surface_ds),
                   "homogenization.separations")
    modulus, hardness = contact_modulus_and_hardness(material_cfg, units_cfg)
    if kind == "boundary_elements":
        out = _boundary_elements(z, dx, dy, h, modulus, hardness, route_cfg)
    elif kind == "persson":
        out = _persson(z, dx, dy, h, modulus, hardness, route_cfg)
    elif kind == "anisotropic":
        out = _anisotropic(h, surface_ds, route_cfg, material_cfg, units_cfg, validity_cfg, effects, asperities)
    else:
        out = _interacting(z, dx, dy, h, modulus, surface_ds, route_cfg, asperities)
    for name, (units, long_name) in CONTRACT.items():
        if name not in out:
            out[name] = ("separation", np.full(h.size, np.nan))
        out[name].attrs = {**attrs(units, long_name), **{k: v for k, v in out[name].attrs.items()
                                                        if k not in ("units", "long_name")}}
    # what the route models: elastic, or plastic (limited by the hardness, or inelastic FE
    # asperities); the reference comparison holds each against the boundary elements alike
    plastic = (route_cfg["limit"] == "hardness"
               or (kind in ("interacting", "anisotropic") and route_cfg["law"] == "fe"
                   and "plasticity" in set(effects or ())))
    out.attrs.update({"route": kind, "limit": "hardness" if plastic else "elastic",
                      "contact_modulus": modulus, "separation_definition":
                      "height of the flat above the mean plane of the prepared map; periodic, "
                      "zero-mean displacement: the mean gap of an elastic contact"})
    log.info("route %s (%s): %d separations, largest A/A0 %.3g, largest p %.4g Pa", kind,
             out.attrs["limit"], h.size, float(np.nanmax(out["contact_area_ratio"].values)),
             float(np.nanmax(out["nominal_pressure"].values)))
    if kind == "anisotropic":  # independent summits, assessed as every statistical route (_anisotropic)
        return out
    return assess_route(out, kind, hardness, validity_cfg)


def assess_route(out: xr.Dataset, kind: str, hardness: float, validity_cfg: Config) -> xr.Dataset:
    """``valid`` and ``validity`` of a route's interface: the boundary elements where they
    resolve their contact patches (at least `MIN_CELLS_PER_PATCH` cells); the
    interacting route where the share of load carried through merged spots is within
    ``validity.merged_load_fraction`` (its own interaction indicator); every elastic
    route where its yield could be judged (a hardness), as in
    `asperity.homogenize.validity`.  Separations without contact are valid."""
    p = out["nominal_pressure"].values
    contact = np.isfinite(p) & (p > 0)
    valid = np.ones(p.shape, bool)
    why = np.full(p.shape, "", dtype=object)

    def fail(where, reason):
        nonlocal valid
        new = where & valid
        why[new] = np.asarray(reason, dtype=object)[new] if np.ndim(reason) else reason
        valid = valid & ~where

    if "cells_per_patch" in out:
        cells = out["cells_per_patch"].values
        with np.errstate(invalid="ignore"):
            fail(contact & (cells < MIN_CELLS_PER_PATCH), np.array(
                [f"unresolved_contacts {c:.3g} cells per patch < {MIN_CELLS_PER_PATCH:g}" for c in cells],
                dtype=object))
    limit = float(validity_cfg["merged_load_fraction"])
    if "merged_load_fraction" in out:
        merged = out["merged_load_fraction"].values
        with np.errstate(invalid="ignore"):
            fail(contact & (merged > limit), np.array(
                [f"merged_load_fraction {m:.3g} > {limit:.3g}" for m in merged], dtype=object))
    elastic = out.attrs.get("limit", "elastic") == "elastic"
    if elastic and not math.isfinite(hardness):
        fail(contact, "unchecked_yield: no hardness or yield stress in the scene's material")
    elif elastic and "yielded_fraction" in out:
        share = out["yielded_fraction"].values
        cap = float(validity_cfg["yielded_fraction"])
        with np.errstate(invalid="ignore"):
            fail(contact & (share > cap), np.array([f"yielded_fraction {v:.3g} > {cap:.3g}" for v in share],
                                                   dtype=object))
    out["valid"] = ("separation", valid, {
        **attrs("1", "the route's assumptions hold at this separation (asperity.stages.routes)"),
        "limit_merged_load_fraction": limit, "min_cells_per_patch": MIN_CELLS_PER_PATCH})
    out["validity"] = ("separation", why.astype(object), attrs(
        "1", "the first assumption that fails at this separation (empty where valid)"))
    warning = validity.warn_invalid(out, f"route {kind}")
    if warning:
        out.attrs["validity_warning"] = warning
    return out
