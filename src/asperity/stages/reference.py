"""The deterministic reference stage: the boundary-element contact of a scene's height
map, and the statistical routes' error against it (scene `deterministic_reference`).

The statistical routes (the Nayak density of 2.4.1 with Hertz or finite element
asperities, and the peaks sampled from the map, 2.4.3 and 2.5.3) run as scenes of
their own, one per route, derived from the reference scene by :func:`route_scene`:
the same map, material and separations, with the route's population, asperity and
homogenization.  Their `interface.nc` files are compared here with the
boundary-element solution (:mod:`asperity.references.boundary_element`) at the same
separations of the flat above the surface's mean plane, the separation of the
statistical route (2.5, 7.1).
"""

from __future__ import annotations

import copy
import dataclasses
import logging
import math
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity.references import boundary_element
from asperity.homogenize import validity
from asperity.population.density import height_scale, heights_at_ratios
from asperity.references.hertz import plane_strain_modulus
from asperity import scene
from asperity.scene import length_factor
from asperity.scene.interface import check_positive, separation_values
# the map as the surface stage reads and prepares it (in-fill, form, filter): the script of
# the reference rule calls this module only
from asperity.stages.surface import prepared_roughness, reading  # noqa: F401
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]
# the figure functions import their plots (matplotlib) themselves: the data jobs start without

#: `<scene>+<route>`: the scene of one statistical route of a reference scene
ROUTE_SEPARATOR = "+"
#: fewest contacting cells per contact patch (mean, elastic solve) at which the boundary
#: elements count as resolving the contact: a patch of 10 cells has a radius of 1.8 grid
#: steps, where the Hertz force error on the grid, 0.15 (dx / a)^2 (asperity.references.
#: boundary_element, measured for a = 4 to 16 steps), would be 5 %; below it the reference
#: is no reference, and no route is said to hold there
MIN_CELLS_PER_PATCH = 10.0
#: what a route's scene takes from the route; the rest is the reference scene's
ROUTE_PARTS = ("population", "asperity", "homogenization", "effects", "route", "friction")


def route_scene(name: str, definition: Config, route: str, results: str) -> dict:
    """The scene of statistical route `route` of reference scene `name`.

    The reference scene's units, material and surface, its reference
    separations as the route's, and the route's population, asperity,
    homogenization, effects, route and friction.  A generated map is read from the reference scene's
    own file (``<results>/<name>/input/map.npy``), so every route and the
    boundary-element solve see the same heights.
    """
    routes = definition.get("routes") or {}
    if route not in routes:
        raise KeyError(f"scene {name!r} has no route {route!r} (routes: {', '.join(routes) or 'none'})")
    derived = {k: copy.deepcopy(v) for k, v in definition.items()
               if k not in ("routes", "reference", "compare_with", *ROUTE_PARTS)}
    for part in ROUTE_PARTS:
        if part in routes[route]:
            derived[part] = copy.deepcopy(routes[route][part])
    derived["title"] = f"{definition.get('title', name)}: route {route}"
    source = definition["surface"]["map"]
    if "generate" in source:
        derived["surface"] = {**{k: v for k, v in definition["surface"].items() if k != "map"},
                              "map": {"file": f"{results}/{name}/input/map.npy",
                                      "spacing": source["generate"]["spacing"],
                                      "unit": definition["units"]["length"]}}
    homogenization = derived.setdefault("homogenization", {})
    homogenization["separations"] = copy.deepcopy(definition["reference"]["separations"])
    return derived


def reference_hardness(material: Config, reference: Config, units_cfg: Config) -> float | None:
    """The hardness of the perfectly plastic solve (Pa): the reference's `hardness`, else the
    material's by the rule of `asperity.homogenize.validity.hardness_of` (given, or Tabor's
    2.8 times the yield or flow stress), else None (elastic only)."""
    units = scene.Units.from_section(units_cfg)
    body = scene.Material.from_scene(material, units)
    if reference.get("hardness") is not None:
        body = dataclasses.replace(body, hardness=float(reference["hardness"]) * units.pressure_factor)
    h, _ = validity.hardness_of(body)
    return h if math.isfinite(h) else None


def reference_separations(reference: Config, surface_ds: xr.Dataset, units_cfg: Config) -> np.ndarray:
    """The separations [m] of the reference section (in sigma of the map, the length unit, or
    material ratios of the map: `asperity.scene.interface.separation_values`)."""
    curve = heights_at_ratios(surface_ds)
    h = separation_values(reference["separations"], height_scale(surface_ds), length_factor(units_cfg),
                          curve, "reference.separations")
    if reference["boundary"] == "periodic":
        check_positive(h, reference["separations"], curve, "reference.separations")
    return h


def reference_dataset(z: np.ndarray, dx: float, dy: float, surface_ds: xr.Dataset,
                      material: Config, reference: Config, units_cfg: Config) -> xr.Dataset:
    """The boundary-element solution of the map (SI input) on dims (limit, separation):
    limit ``elastic``, and ``hardness`` where the scene gives one (`reference_hardness`)."""
    body = scene.Material.from_scene(material, scene.Units.from_section(units_cfg))
    modulus = float(plane_strain_modulus(body.youngs_modulus, body.poisson))
    h = reference_separations(reference, surface_ds, units_cfg)
    hardness = reference_hardness(material, reference, units_cfg)
    options = {"boundary": reference["boundary"], "tolerance": reference["tolerance"],
               "max_iterations": reference["max_iterations"]}
    limits = {"elastic": None} | ({"hardness": hardness} if hardness is not None else {})
    parts = []
    for limit, cap in limits.items():  # two solves at most
        ds = boundary_element.solve_map(z, dx, dy, h, modulus, hardness=cap, **options)
        log.info("boundary elements, %s: %d separations, %.3g s CPU, largest A/A0 %.3g",
                 limit, h.size, ds.attrs["cpu_time"], float(ds["contact_area_ratio"].max()))
        parts.append(ds.expand_dims(limit=[limit]).assign_coords(
            cpu_time=("limit", [ds.attrs.pop("cpu_time")], {"units": "s", "long_name": "CPU time of the solve"})))
    out = xr.concat(parts, dim="limit", data_vars="all", combine_attrs="drop_conflicts")
    for name in parts[0].data_vars:
        out[name].attrs = parts[0][name].attrs
    if "flowing_area_ratio" in out:
        out["flowing_area_ratio"].attrs = parts[-1]["flowing_area_ratio"].attrs
    out["limit"].attrs = {"units": "1", "long_name": "elastic, or perfectly plastic at the hardness"}
    out["separation"].attrs = parts[0]["separation"].attrs
    out.attrs.update({
        "hardness": np.nan if hardness is None else hardness,
        "contact_modulus": modulus,
        "gradient_rms": gradient_rms(z, dx, dy),
    })
    undefined = float(out.attrs.get("undefined_fraction", 0.0))
    if undefined > 0:
        log.warning("%.3g %% of the map is undefined: those points neither touch nor count in A0",
                    100 * undefined)
    return out


def gradient_rms(z: np.ndarray, dx: float, dy: float) -> float:
    """h'_rms, the rms gradient of the defined heights (spectral, undefined points at the mean)."""
    zz = np.where(np.isfinite(z), z - np.nanmean(z), 0.0)
    qy = 2 * np.pi * np.fft.fftfreq(zz.shape[0], d=dy)
    qx = 2 * np.pi * np.fft.fftfreq(zz.shape[1], d=dx)
    power = np.abs(np.fft.fft2(zz)) ** 2
    return float(np.sqrt(np.sum((qy[:, None] ** 2 + qx[None, :] ** 2) * power)) / zz.size)


def _interp_log(x_new: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """y(x_new), linear in log-log over the positive points (x increasing), NaN outside."""
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 2:
        return np.full(np.shape(x_new), np.nan)
    order = np.argsort(x[ok])
    lx, ly = np.log(x[ok][order]), np.log(y[ok][order])
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.exp(np.interp(np.log(x_new), lx, ly, left=np.nan, right=np.nan))
    return np.where(np.asarray(x_new) > 0, out, np.nan)


def errors_against(p, route_p, route_a, p_ref, a_ref) -> tuple[np.ndarray, np.ndarray]:
    """A route's pressure error at equal separation, p / p_ref - 1 (`p` the route's pressure at
    the reference's separations), and its area error at equal pressure, A(p_ref) / a_ref - 1
    (the route's curve `route_p`, `route_a` interpolated in log-log); NaN where the
    reference has no pressure or area."""
    with np.errstate(divide="ignore", invalid="ignore"):
        pressure = np.where(p_ref > 0, np.asarray(p) / p_ref - 1, np.nan)
        area = np.where(a_ref > 0, _interp_log(p_ref, np.asarray(route_p), np.asarray(route_a)) / a_ref - 1,
                        np.nan)
    return pressure, area


def _interp_semilog(x_new: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """y(x_new) linear in log y (exact for the exponential tails of p(h)), NaN outside x;
    zeros stay (near) zero."""
    order = np.argsort(x)
    log_y = np.log(np.maximum(y[order], np.finfo(float).tiny))
    out = np.exp(np.interp(x_new, x[order], log_y, left=np.nan, right=np.nan))
    return np.where(np.isnan(out) | (out > 2 * np.finfo(float).tiny), out, 0.0)



def _longest_run(mask: np.ndarray) -> tuple[int, int] | None:
    """First and last index of the longest run of True, None if there is none."""
    best, start = None, None
    for i, v in enumerate(list(mask) + [False]):  # separations: a few dozen
        if v and start is None:
            start = i
        elif not v and start is not None:
            if best is None or i - start > best[1] - best[0] + 1:
                best = (start, i - 1)
            start = None
    return best


def recommended(names, pressure_error: np.ndarray, area_error: np.ndarray, resolved: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """Per separation, the route (of `names`, rows of the errors) whose larger absolute error,
    of pressure and of area, is smallest, and that error; '' and NaN where no route has
    both errors or the reference does not resolve its contact."""
    if len(names) == 0:
        return np.full(np.shape(resolved), "", dtype=object), np.full(np.shape(resolved), np.nan)
    worst = np.fmax(np.abs(pressure_error), np.abs(area_error))
    worst = np.where(np.isfinite(pressure_error) & np.isfinite(area_error), worst, np.nan)
    have = np.isfinite(worst).any(axis=0) & resolved
    pick = np.argmin(np.where(np.isfinite(worst), worst, np.inf), axis=0)
    best = np.where(have, np.asarray(names, dtype=object)[pick], "").astype(object)
    error = np.where(have, np.take_along_axis(worst, pick[None, :], axis=0)[0], np.nan)
    return best, error


def comparison_dataset(reference: xr.Dataset, interfaces: Mapping[str, xr.Dataset],
                       agreement: float) -> xr.Dataset:
    """Each route's error against the boundary-element solution: the elastic one, or the
    one limited by the hardness for a route that models plasticity (its interface's
    attribute ``limit``: ``hardness``; the ``reference_limit`` of each route).

    Per route and separation: the pressure error p_route / p_BEM - 1 at the same
    separation; the contact area error A_route / A_BEM - 1 at the same nominal
    pressure (the route's A(p) interpolated in log-log at the BEM's p); the ratio of
    contact counts (asperities in contact against contact patches).  A route holds
    where both errors are within `agreement` and the boundary elements resolve the
    contact (``reference_resolved``: at least `MIN_CELLS_PER_PATCH` cells per patch,
    elastic solve; a warning names the separations where they do not);
    ``holds_from``/``holds_to`` give the longest such range of separations, with the
    BEM's pressures there.  With a hardness, ``plastic_departure`` is
    p_hardness / p_elastic - 1: where it is large, an elastic route describes a
    surface that has yielded.
    """
    el = reference.sel(limit="elastic")
    h = reference["separation"].values
    p_ref = el["nominal_pressure"].values
    a_ref = el["contact_area_ratio"].values
    names = list(interfaces)
    shape = (len(names), h.size)
    vals = {k: np.full(shape, np.nan) for k in ("nominal_pressure", "contact_area_ratio",
                                                 "pressure_error", "area_error", "contact_count_ratio")}
    limits = [interfaces[n].attrs.get("limit", "elastic") if interfaces[n].attrs.get("limit")
              in reference["limit"].values else "elastic" for n in names]
    for i, name in enumerate(names):
        ds = interfaces[name]
        if "branch" in ds.dims:
            ds = ds.sel(branch=ds["branch"].values[0])
        against = reference.sel(limit=limits[i])
        p_ref = against["nominal_pressure"].values
        a_ref = against["contact_area_ratio"].values
        hs = ds["separation"].values
        p, a, n = (_interp_semilog(h, hs, ds[k].values)
                   for k in ("nominal_pressure", "contact_area_ratio", "contact_count"))
        vals["nominal_pressure"][i] = p
        vals["contact_area_ratio"][i] = a
        vals["pressure_error"][i], vals["area_error"][i] = errors_against(
            p, ds["nominal_pressure"].values, ds["contact_area_ratio"].values, p_ref, a_ref)
        with np.errstate(divide="ignore", invalid="ignore"):
            vals["contact_count_ratio"][i] = np.where(el["contact_count"].values > 0,
                                                      n / el["contact_count"].values, np.nan)
    p_ref = el["nominal_pressure"].values
    a_ref = el["contact_area_ratio"].values
    cells = el["cells_per_patch"].values
    with np.errstate(invalid="ignore"):
        resolved = ~(cells < MIN_CELLS_PER_PATCH)  # NaN (no contact) is not judged
    holds = ((np.abs(vals["pressure_error"]) <= agreement) & (np.abs(vals["area_error"]) <= agreement)
             & resolved[None, :])
    meta = {
        "nominal_pressure": ("Pa", "nominal pressure of the statistical route"),
        "contact_area_ratio": ("1", "real contact area ratio of the statistical route"),
        "pressure_error": ("1", "route's nominal pressure over the elastic boundary-element one, minus 1, "
                                "at the same separation"),
        "area_error": ("1", "route's real contact area over the elastic boundary-element one, minus 1, "
                            "at the same nominal pressure"),
        "contact_count_ratio": ("1", "route's asperities in contact over the boundary-element contact "
                                     "patches, at the same separation"),
    }
    out = xr.Dataset(
        {k: (("route", "separation"), v, attrs(*meta[k])) for k, v in vals.items()},
        coords={"route": ("route", names, attrs("1", "route (scene <reference>+<route>)")),
                "separation": ("separation", h, dict(reference["separation"].attrs))},
    )
    out["reference_limit"] = ("route", np.array(limits, dtype=object), attrs(
        "1", "the boundary elements each route is held against: elastic, or limited by the hardness"))
    out["reference_pressure"] = ("separation", p_ref, attrs("Pa", "nominal pressure, elastic boundary elements"))
    out["reference_area_ratio"] = ("separation", a_ref, attrs("1", "real contact area ratio, elastic boundary elements"))
    out["reference_resolved"] = ("separation", resolved, attrs(
        "1", f"the elastic boundary elements resolve the contact: at least {MIN_CELLS_PER_PATCH:g} "
             "contacting cells per contact patch"))
    out["holds"] = (("route", "separation"), holds, attrs(
        "1", f"pressure and area errors both within {agreement:g}, where the boundary elements "
             "resolve the contact"))
    ranges = {k: np.full(len(names), np.nan) for k in ("holds_from", "holds_to", "holds_pressure_low",
                                                        "holds_pressure_high")}
    for i in range(len(names)):
        run = _longest_run(holds[i])
        if run is not None:
            ranges["holds_from"][i], ranges["holds_to"][i] = h[run[0]], h[run[1]]
            ranges["holds_pressure_low"][i], ranges["holds_pressure_high"][i] = p_ref[run[1]], p_ref[run[0]]
    range_meta = {
        "holds_from": ("m", "smallest separation of the longest range where the route holds"),
        "holds_to": ("m", "largest separation of the longest range where the route holds"),
        "holds_pressure_low": ("Pa", "boundary-element pressure at holds_to"),
        "holds_pressure_high": ("Pa", "boundary-element pressure at holds_from"),
    }
    for k, v in ranges.items():
        out[k] = ("route", v, attrs(*range_meta[k]))
    # among the routes held against the elastic boundary elements: a plastic route's errors
    # are against another reference
    elastic = np.array([limit == "elastic" for limit in limits], dtype=bool)
    best, best_error = recommended(np.asarray(names, dtype=object)[elastic], vals["pressure_error"][elastic],
                                   vals["area_error"][elastic], resolved)
    out["recommended_route"] = ("separation", best, attrs(
        "1", "the elastic route closest to the elastic boundary elements at this separation (the "
             "smallest larger of its pressure and area errors; routes held against the boundary "
             "elements limited by the hardness are not candidates); empty where no route is "
             "defined or the boundary elements do not resolve the contact"))
    out["recommended_error"] = ("separation", best_error, attrs(
        "1", "the larger of the recommended route's pressure and area errors (absolute)"))
    if "hardness" in reference["limit"].values:
        pl = reference.sel(limit="hardness")["nominal_pressure"].values
        with np.errstate(divide="ignore", invalid="ignore"):
            out["plastic_departure"] = ("separation", np.where(p_ref > 0, pl / p_ref - 1, np.nan), attrs(
                "1", "boundary-element pressure with the hardness over the elastic one, minus 1"))
    out.attrs.update({"agreement": agreement, "sigma": reference.attrs.get("sigma", np.nan),
                      "hardness": reference.attrs.get("hardness", np.nan),
                      "boundary": reference.attrs.get("boundary", "")})
    warnings = []
    if reference.attrs.get("boundary") == "free":
        log.warning("free boundary: the map is a finite patch, whose sink-in the statistical routes "
                    "(an infinite interface) do not have; compare mean gaps with care")
        warnings.append("free boundary: finite patch against infinite-interface routes")
    if not resolved.all():
        low = h[~resolved]
        text = (f"the boundary elements do not resolve the contact at {low.size} of {h.size} separations "
                f"({low.min():.4g} .. {low.max():.4g} m): {np.nanmin(cells[~resolved]):.2g} to "
                f"{np.nanmax(cells[~resolved]):.2g} cells per contact patch, fewer than "
                f"{MIN_CELLS_PER_PATCH:g}; no route holds there. A finer map (smaller spacing) resolves them")
        log.warning("%s", text)
        warnings.append(text)
    if warnings:
        out.attrs["warning"] = "; ".join(warnings)
    for i, name in enumerate(names):
        log.info("route %s: holds (within %g) from separation %.4g to %.4g m", name, agreement,
                 ranges["holds_from"][i], ranges["holds_to"][i])
    for hk, route, error in zip(h, best, best_error):
        if route:
            log.info("separation %.4g m: recommended route %s (largest error %.3g)", hk, route, error)
    return out


def reference_figure(reference: xr.Dataset, comparison: xr.Dataset, units_cfg: Config):
    """Pressure against separation and contact area against pressure, every route beside
    the boundary-element solution."""
    from asperity.plots.reference import reference_figure as draw

    return draw(reference, comparison, length_unit=units_cfg["length"],
                pressure_unit=units_cfg["pressure"])  # the schema fills it in
