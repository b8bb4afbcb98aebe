"""Stage `surface` (workflow/rules/surface.smk): surface.nc from a profile, profiles, a map,
or statistics given in the scene (report 2.3, 2.4.3, 2.6.1); synthetic surfaces.

A measured profile or map is prepared before any statistic is taken
(`asperity.surface.prepare`: undefined points, form removal, the ISO 16610 filter,
a map's lateral scale); then the statistics of what is left (the roughness): the
sampling, counting and spectral estimates of a profile (2.3.1) or the statistics and
peaks of a map (2.4.3), skewness, kurtosis and bearing-area curve, the power spectrum
and autocorrelation.

surface.nc records what was removed, the rms height before and after, the
share of undefined points, whether the heights are Gaussian, the axis
convention of maps, and a preview of the raw heights, the removed form and
the roughness for the figure.
"""

from __future__ import annotations

import logging
import math
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import surface
from asperity.scene import length_factor
from asperity.surface import summits
from asperity.surface.prepare import Prepared, prepare
from asperity.scene.surface import SurfaceScene
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]

#: the most points per axis kept in surface.nc's preview of the heights (for the figure)
PREVIEW_PROFILE = 20000
PREVIEW_MAP = 512


# --------------------------------------------------------------------------
# synthetic surfaces (scene `generate` sections)
# --------------------------------------------------------------------------


def synthetic_profile(generate: Config) -> tuple[np.ndarray, np.ndarray]:
    """Positions and heights of a synthetic profile of report 2.6.1, scene units."""
    if generate["kind"] == "cosine":
        return surface.synthetic_profile("cosine", generate["spacing"], generate["length"],
                                         amplitude=generate["amplitude"], wavenumber=generate["wavenumber"])
    return surface.synthetic_profile("series", generate["spacing"], generate["length"],
                                     components=generate["components"], seed=generate["seed"])


def synthetic_map(generate: Config) -> np.ndarray:
    """The Gaussian random height map of a scene (scene units), :func:`surface.gaussian_map`."""
    return surface.gaussian_map(generate["points"], generate["spacing"], generate["sigma"],
                                generate["correlation_length"], generate["seed"], generate["aspect"])


def profile_file_name(direction_deg: float) -> str:
    """File name of the synthetic profile along `direction_deg`."""
    return f"profile_{direction_deg:g}deg.txt"


def _anisotropic(generate: Config):
    return surface.anisotropic_series(generate["components"], generate["seed"], generate["aspect"])


def synthetic_directional_profiles(generate: Config) -> list[tuple[np.ndarray, np.ndarray]]:
    """Profiles of a synthetic anisotropic surface along the scene's directions (2.3.2)."""
    return surface.directional_profiles(generate["components"], generate["seed"], generate["aspect"],
                                        generate["spacing"], generate["length"], generate["directions"])


def _series_reference(generate: Config, length: float) -> dict[str, float] | None:
    """Exact statistics of a synthetic profile (eq. 2.4 for a series), SI."""
    if generate["kind"] == "cosine":
        c, k = generate["amplitude"], generate["wavenumber"]
        amplitudes, wavenumbers = np.array([c]), np.array([k])
    else:
        amplitudes, wavenumbers, _ = surface.quasirandom_series(
            n=generate["components"], seed=generate["seed"]
        )
    exact = surface.series_statistics(amplitudes, wavenumbers)
    return {
        "sigma": exact["sigma"] * length,
        "sigma_slope": exact["sigma_slope"],
        "sigma_curvature": exact["sigma_curvature"] / length,
        "beta": exact["beta"],
    }


def series_convergence(generate: Config, units_cfg: Config) -> xr.Dataset:
    """Sampled statistics of a synthetic profile versus spacing, against exact (2.6.1).

    The report notes that the differences shrink with the spacing "but they
    do not vanish"; this dataset shows how fast they shrink here.
    """
    length = length_factor(units_cfg)
    exact = _series_reference(generate, length)
    names = ["sigma", "sigma_slope", "sigma_curvature", "beta"]
    spacings = np.asarray(generate["convergence_spacings"], float)
    rows = []
    for spacing in spacings:  # a handful of spacings; each call is vectorized
        x, z = synthetic_profile({**generate, "spacing": spacing})
        stats = surface.profile_statistics(z * length, spacing * length)
        rows.append(stats[names].sel(estimator=["sampling", "counting", "spectral"]))
    ds = xr.concat(rows, dim="spacing")
    ds = ds.assign_coords(
        spacing=("spacing", spacings * length, attrs("m", "sampling interval of the profile"))
    )
    for name in names:
        ds[name].attrs = rows[0][name].attrs
        err = np.abs(ds[name] / exact[name] - 1.0)
        ds[f"{name}_error"] = err.assign_attrs(
            attrs("1", f"relative error of {rows[0][name].attrs['long_name']} against the series")
        )
        ds[f"{name}_exact"] = xr.DataArray(exact[name], attrs={
            "units": rows[0][name].attrs["units"],
            "long_name": f"{rows[0][name].attrs['long_name']} of the series (eq. 2.4)"})
    return ds


def reading(surface_cfg: Config, units_cfg: Config) -> dict[str, Any]:
    """What the reader of the scene's profile or map file needs to know
    (`asperity.io.topography.read_measurement`): kind, the file's unit and spacing as the
    scene gives them (SI), the channel, and the scene key for its messages."""
    scene = SurfaceScene.from_config(surface_cfg, units_cfg)
    return {"kind": scene.source, "unit": scene.file_unit, "spacing": scene.spacing,
            "channel": scene.section.get("channel"), "key": f"surface.{scene.source}"}


def profile_readings(surface_cfg: Config, units_cfg: Config) -> list[dict[str, Any]]:
    """What the reader needs for each file of the scene's `profiles` (2.3.2), with its direction."""
    scene = SurfaceScene.from_config(surface_cfg, units_cfg)
    if scene.generated:
        return [{"file": profile_file_name(d), "direction": d, "unit": scene.scene_unit, "spacing": None,
                 "key": "surface.profiles.generate"} for d in scene.generated["directions"]]
    return [{"file": item["file"], "direction": item["direction"], "unit": item.get("unit"),
             "spacing": None if item.get("spacing") is None else item["spacing"] * scene.length,
             "key": f"surface.profiles.files.{i}"} for i, item in enumerate(scene.section["files"])]


# --------------------------------------------------------------------------
# preparing a measured profile or map (asperity.surface.prepare)
# --------------------------------------------------------------------------


def prepared_roughness(heights, spacing, surface_cfg: Config, units_cfg: Config, defined=None) -> np.ndarray:
    """The roughness the statistics of `surface_from_data` see (m): the heights after the
    scene's in-fill, form removal and filter, NaN where undefined or outside the evaluation
    region; for whatever else must work on the same surface (the boundary-element reference)."""
    scene = SurfaceScene.from_config(surface_cfg, units_cfg)
    return prepare(np.asarray(heights, dtype=np.float64), spacing, scene, defined).roughness


# --------------------------------------------------------------------------
# surface.nc
# --------------------------------------------------------------------------


def _scalar(value, units: str, long_name: str):
    return ((), value, attrs(units, long_name))


def _stride(n: int, most: int) -> int:
    return max(1, int(math.ceil(n / most)))


def _preview(prep: Prepared) -> dict:
    """The raw heights, the removed form and the roughness, every k-th point (for the figure)."""
    if prep.raw.ndim == 1:
        dx = float(prep.spacing)
        s = _stride(prep.raw.size, PREVIEW_PROFILE)
        x = dx * np.arange(0, prep.raw.size, s)
        dims = ("position",)
        coords = {"position": ("position", x, attrs("m", f"position along the profile (every {s}. point)"))}
        pick = (slice(None, None, s),)
    else:
        dx, dy = (float(v) for v in prep.spacing)
        ny, nx = prep.raw.shape
        s = max(_stride(nx, PREVIEW_MAP), _stride(ny, PREVIEW_MAP))
        dims = ("map_y", "map_x")
        coords = {"map_x": ("map_x", dx * np.arange(0, nx, s), attrs("m", f"x of the map (every {s}. column)")),
                  "map_y": ("map_y", dy * np.arange(0, ny, s), attrs("m", f"y of the map (every {s}. row)"))}
        pick = (slice(None, None, s), slice(None, None, s))
    data = {
        "raw_height": (dims, prep.raw[pick], attrs("m", "height as read from the file (NaN: undefined)")),
        "form_height": (dims, prep.form[pick],
                        attrs("m", "removed form: the least-squares polynomial plus the lambda_c mean line")),
        "roughness_height": (dims, prep.roughness[pick],
                             attrs("m", "roughness: what the statistics see (NaN: undefined, or dropped "
                                        "at the ends by the filter)")),
    }
    return {"data": data, "coords": coords}


def _removal(prep: Prepared, scene: SurfaceScene) -> dict:
    """What was removed, and the rms height before and after."""
    raw = prep.raw[np.isfinite(prep.raw)]
    ev = prep.evaluated
    rough = ev[np.isfinite(ev)]
    removed = (prep.raw - prep.roughness)[prep.region]
    removed = removed[np.isfinite(removed)]
    return {
        "rms_height_raw": _scalar(float(np.sqrt(np.mean((raw - raw.mean()) ** 2))), "m",
                                  "rms height of the heights as read, only their mean removed"),
        "rms_height": _scalar(float(np.sqrt(np.mean((rough - rough.mean()) ** 2))), "m",
                              "rms height of the roughness (Rq / Sq), after form removal and filter"),
        "rms_removed": _scalar(float(np.sqrt(np.mean((removed - removed.mean()) ** 2))) if removed.size else 0.0,
                               "m", "rms of what form removal and the filter took away"),
        "undefined_share": _scalar(prep.undefined_share, "1",
                                   "share of the points of the file that are undefined"),
        "filled_points": _scalar(np.int64(prep.filled), "1", "undefined points filled by harmonic in-fill"),
        "island_points": _scalar(np.int64(prep.islands), "1",
                                 "defined points dropped as islands: in regions (edge-connected) "
                                 "without a point whose neighbours are all defined"),
    }


def _removal_attrs(scene: SurfaceScene, prep: Prepared) -> dict:
    return {"form_removed": scene.form_text, "filter": scene.filter_text,
            "undefined_fill": scene.fill if prep.filled else "none",
            "undefined_islands": scene.islands,
            "evaluation_region": ", ".join(f"{sl.start}:{sl.stop}" for sl in prep.region)}


def _distribution(rough: np.ndarray, defined: np.ndarray, kind: str) -> tuple[dict, dict, dict]:
    """Skewness, kurtosis, bearing-area curve, and the Gaussian verdict (variables, coords, attrs)."""
    dist = surface.height_distribution(rough, defined)
    gaussian, why = surface.gaussianity(dist["skewness"], dist["kurtosis"])
    iso = ("Rsk", "Rku") if kind == "profile" else ("Ssk", "Sku")
    data = {
        "skewness": _scalar(dist["skewness"], "1", f"skewness of the heights ({iso[0]}; 0 for Gaussian heights)"),
        "kurtosis": _scalar(dist["kurtosis"], "1", f"kurtosis of the heights ({iso[1]}; 3 for Gaussian heights)"),
        "bearing_height": ("material_ratio", dist["bearing_height"],
                           attrs("m", "bearing-area (Abbott-Firestone) curve: height above which that "
                                      "share of the surface lies, about the mean")),
    }
    coords = {"material_ratio": ("material_ratio", dist["material_ratio"],
                                 attrs("1", "material ratio: share of the points at or above the height"))}
    lo, hi = surface.KURTOSIS_RANGE
    out = {"gaussian": "yes" if gaussian else f"no: {why}",
           "gaussian_limits": f"|skewness| <= {surface.SKEWNESS_LIMIT:g}, kurtosis {lo:g} ... {hi:g}"}
    return data, coords, out


def _spectra(rough: np.ndarray, defined: np.ndarray, spacing, scene: SurfaceScene) -> tuple[dict, dict, dict]:
    """Power spectrum (profile: windowed periodogram; map: radially averaged) and the autocorrelation."""
    extra = {}
    if rough.ndim == 1:
        dx = float(spacing)
        run = surface.longest_run(defined)
        k, P = surface.power_spectrum(rough[run], dx, scene.window)
        k, P = k[1:], P[1:]
        psd_attrs = attrs("m^3", f"power spectral density of the profile ({scene.window} window), one-sided")
    else:
        dx, dy = (float(v) for v in spacing)
        record = rough
        if not defined.all():
            record = surface.harmonic_fill(np.where(defined, rough, 0.0), defined)
            extra["psd_note"] = (f"the periodogram needs a complete map: {int((~defined).sum())} undefined "
                                 "points were filled harmonically for the spectrum only")
        k, P = surface.radial_power_spectrum(record, dx, dy, scene.window)
        psd_attrs = attrs("m^4", f"radially averaged two-dimensional power spectral density ({scene.window} "
                                 "window)")
    r, R, A = surface.autocorrelation(rough, spacing, defined)
    data = {
        "psd": ("wavenumber", P, psd_attrs),
        "autocorrelation": ("lag", R, attrs("1", "autocorrelation of the heights over defined pairs, "
                                                 "normalized (radially averaged on a map)")),
        "height_difference_autocorrelation": (
            "lag", A, attrs("m^2", "height-difference autocorrelation 1/2 <(z(x + r) - z(x))^2>")),
    }
    coords = {"wavenumber": ("wavenumber", k, attrs("rad/m", "angular wavenumber (2 pi / wavelength)")),
              "lag": ("lag", r, attrs("m", "distance between the two points of a pair"))}
    extra["correlation_length"] = surface.correlation_length(r, R)
    extra["correlation_length_note"] = ("first lag where the autocorrelation falls to "
                                        f"{surface.CORRELATION_THRESHOLD:g}")
    return data, coords, extra


def _warn_gaussian(ds: xr.Dataset, kind: str):
    if ds.attrs["gaussian"] == "yes":
        return
    if kind == "profile":
        consequence = ("the Nayak/Francis peak density of a profile (2.4.1) assumes Gaussian heights; "
                       "measure a map and use population.density: sampled (2.4.3) for this surface")
    else:
        consequence = ("population.density sampled (the default for a map) takes the map's own peaks "
                       "(2.4.3); a Nayak or Greenwood-Williamson density would assume Gaussian heights")
    message = f"the heights are not Gaussian ({ds.attrs['gaussian'][4:]}): {consequence}"
    log.warning(message)
    ds.attrs["warnings"] = message


def _profile_dataset(prep: Prepared, scene: SurfaceScene) -> xr.Dataset:
    dx = float(prep.spacing)
    rough, defined = prep.evaluated, prep.evaluated_defined
    ds = surface.profile_statistics(rough, dx, defined=None if defined.all() else defined,
                                    window=scene.window)
    ds.attrs["title"] = "profile statistics (report 2.3.1)"
    return ds


def _map_dataset(prep: Prepared) -> xr.Dataset:
    dx, dy = (float(v) for v in prep.spacing)
    rough, defined = prep.evaluated, prep.evaluated_defined
    mask = None if defined.all() else defined
    stats = surface.map_statistics(rough, dx, dy, defined=mask)
    if prep.scale is None:
        peaks = surface.map_peaks(rough, dx, dy, defined=mask)
    else:  # summits at the scale: found and fitted on the map before its low pass, which
        # map_summits applies itself (its fit completes the filter at the scale)
        found = summits.map_summits(prep.unsmoothed[prep.region], dx, dy, prep.scale, defined=mask,
                                    periodic=True)
        peaks = found[["x", "y", "row", "column", "height", "curvature", "z_xx", "z_yy", "z_xy",
                       "principal_curvature_1", "principal_curvature_2"]].rename(summit="peak")
        stats["peak_density"] = stats["peak_density"].copy(
            data=np.full(stats["peak_density"].shape, found.attrs["summit_density"]))
        stats.attrs["scale"] = prep.scale
        stats.attrs["scale_rule"] = prep.scale_rule
        stats.attrs["peaks"] = found.attrs["method"]
    i0, j0 = prep.region[0].start, prep.region[1].start
    # peaks in the coordinates of the whole map (the evaluation region is inset by the filter)
    for name, shift in (("row", i0), ("column", j0), ("x", j0 * dx), ("y", i0 * dy)):
        peaks[name] = peaks[name].copy(data=peaks[name].values + shift)
    ds = xr.merge([stats, peaks], combine_attrs="override")
    ds.attrs["title"] = "height map statistics and peaks (report 2.4.3)"
    ds.attrs["axes"] = surface.AXES
    return ds


def surface_from_data(heights, spacing, surface_cfg: Config, units_cfg: Config, defined=None,
                      notes: list[str] | None = None) -> xr.Dataset:
    """surface.nc of a measured or generated profile (1-D) or map (2-D), heights and spacing in SI.

    The scene's surface section (``surface_cfg``) says how to prepare it
    (`asperity.surface.prepare.prepare`); ``defined`` is False at undefined points; ``notes``
    (where the unit and spacing came from) go to the log and the dataset.
    """
    scene = SurfaceScene.from_config(surface_cfg, units_cfg)
    z = np.asarray(heights, dtype=np.float64)
    kind = "profile" if z.ndim == 1 else "map"
    for note in notes or []:
        log.info("%s", note)
    prep = prepare(z, spacing, scene, defined)
    log.info("%s: %d points, %.2f %% undefined; form removed: %s; filter: %s", kind, z.size,
             100 * prep.undefined_share, scene.form_text, scene.filter_text)
    ds = _profile_dataset(prep, scene) if kind == "profile" else _map_dataset(prep)
    rough, defined_ev = prep.evaluated, prep.evaluated_defined
    more = _removal(prep, scene)
    dist, dist_coords, dist_attrs = _distribution(rough, defined_ev, kind)
    spec, spec_coords, spec_attrs = _spectra(rough, defined_ev, prep.spacing, scene)
    preview = _preview(prep)
    ds = ds.assign_coords({**dist_coords, **spec_coords, **preview["coords"]})
    for name, value in {**more, **dist, **spec, **preview["data"]}.items():
        ds[name] = value
    ds.attrs.update(_removal_attrs(scene, prep))
    ds.attrs.update(dist_attrs)
    ds.attrs.update(spec_attrs)
    ds.attrs["axes"] = surface.AXES if kind == "map" else "profile heights z(x) at x = i dx"
    if notes:
        ds.attrs["input"] = "; ".join(notes)
    log.info("rms height %.6g m as read (mean removed), %.6g m after form removal and filter",
             float(ds["rms_height_raw"]), float(ds["rms_height"]))
    _warn_gaussian(ds, kind)
    if kind == "profile":
        ds = _with_exact(ds, scene, float(prep.spacing))
        ds.attrs["population_estimator"] = scene.estimator
    else:
        ds.attrs["population_estimator"] = "map"
    return ds


def _with_exact(ds: xr.Dataset, scene: SurfaceScene, dx: float) -> xr.Dataset:
    """For a synthetic profile, its exact statistics as estimator ``exact`` (cosine: closed
    form; series: eq. 2.4)."""
    generate = scene.generated
    if not generate:
        return ds
    # the synthetic profile was written in scene units and read back in SI;
    # its exact statistics scale with the same factor
    length = dx / generate["spacing"]
    exact = _series_reference(generate, length)
    per_estimator = [name for name in ds.data_vars if ds[name].dims == ("estimator",)]
    extra = xr.full_like(ds[per_estimator].isel(estimator=0), np.nan).expand_dims(estimator=["exact"])
    for name, value in exact.items():
        extra[name] = extra[name].copy(data=np.array([value]))
    extra["m0"] = extra["sigma"] ** 2
    extra["m2"] = extra["sigma_slope"] ** 2
    extra["m4"] = extra["sigma_curvature"] ** 2
    extra["peak_density"] = extra["m4"] / (6 * np.pi * np.sqrt(3) * extra["m2"])
    merged = xr.concat([ds[per_estimator], extra], dim="estimator", data_vars="all", coords="minimal")
    out = ds.drop_vars(per_estimator).drop_dims("estimator")
    out = out.assign_coords(estimator=merged["estimator"])
    for name in per_estimator:
        out[name] = merged[name].assign_attrs(ds[name].attrs)
    out["estimator"].attrs = ds["estimator"].attrs
    return out


def surface_from_statistics(surface_cfg: Config, units_cfg: Config) -> xr.Dataset:
    """Surface statistics given in the scene (report 2.6.2), as estimator ``given``."""
    length = length_factor(units_cfg)
    if "gaussian_heights" in surface_cfg:
        gh = surface_cfg["gaussian_heights"]
        ds = xr.Dataset(
            {
                "sigma_peak_height": ((), gh["sigma_peak_height"] * length,
                                      attrs("m", "standard deviation of peak heights")),
                "tip_curvature": ((), 1.0 / (gh["radius"] * length),
                                  attrs("1/m", "curvature of every asperity tip (1/R)")),
                "peak_density": ((), gh["peak_density"] / length**2,
                                 attrs("1/m^2", "peaks per unit nominal area")),
            }
        )
        ds.attrs["population_estimator"] = "gaussian_heights"
        return ds
    st = surface_cfg["statistics"]
    values = {
        "mean_height": (st["mean_height"] * length, "m", "mean height"),  # the schema fills it in
        "sigma": (st["sigma"] * length, "m", "standard deviation of height"),
        "sigma_slope": (st["sigma_slope"], "1", "standard deviation of slope"),
        "sigma_curvature": (st["sigma_curvature"] / length, "1/m", "standard deviation of curvature"),
        "peak_density": (st["peak_density"] / length**2, "1/m^2", "peaks per unit nominal area"),
    }
    ds = xr.Dataset(
        {name: ("estimator", [v], attrs(u, ln)) for name, (v, u, ln) in values.items()},
        coords={"estimator": ("estimator", ["given"], attrs("1", "how the statistics were obtained"))},
    )
    ds["m0"] = (ds["sigma"] ** 2).assign_attrs(attrs("m^2", "spectral moment m0"))
    ds["m2"] = (ds["sigma_slope"] ** 2).assign_attrs(attrs("1", "spectral moment m2"))
    ds["m4"] = (ds["sigma_curvature"] ** 2).assign_attrs(attrs("1/m^2", "spectral moment m4"))
    ds["beta"] = (np.sqrt(1.5) * ds["m2"] / np.sqrt(ds["m0"] * ds["m4"])).assign_attrs(
        attrs("1", "wavelength spectrum parameter beta (2.4.1)")
    )
    ds.attrs["population_estimator"] = "given"
    return ds


def surface_from_profiles(
    profiles: list[tuple[np.ndarray, float]], directions_deg: list[float], surface_cfg: Config,
    units_cfg: Config,
) -> xr.Dataset:
    """Statistics of profiles along several directions and the surface moments (2.3.2).

    Each profile is prepared as a single profile is (`asperity.surface.prepare.prepare`: form
    removal and filter of the scene) and gets the statistics of
    `profile_statistics` (dim ``direction``); the moments m20, m11, m02 (3
    directions or more) and the fourth-order moments (5 or more) follow by
    least squares from the chosen estimator's m0, m2, m4, with the
    invariants of 2.3.2.  For a synthetic surface the exact moments of eq.
    (2.4) are added as ``<moment>_exact``.
    """
    scene = SurfaceScene.from_config(surface_cfg, units_cfg)
    estimator = scene.estimator
    rows = []
    for z, dx in profiles:  # a handful of profiles, each vectorized
        prep = prepare(z, dx, scene)
        rough, defined = prep.evaluated, prep.evaluated_defined
        rows.append(surface.profile_statistics(rough, dx, defined=None if defined.all() else defined,
                                               window=scene.window))
    stats = xr.concat(rows, dim="direction", data_vars="all", coords="minimal", compat="override")
    theta = np.radians(np.asarray(directions_deg, float))
    stats = stats.assign_coords(direction=("direction", theta, attrs("rad", "profile direction from the x axis")))
    chosen = stats.sel(estimator=estimator)
    moments = surface.directional_moments(theta, chosen["m0"].values, chosen["m2"].values, chosen["m4"].values)
    ds = xr.merge([stats, moments], combine_attrs="drop_conflicts")
    ds.attrs.update(moments.attrs)
    ds.attrs.update(form_removed=scene.form_text, filter=scene.filter_text)
    generate = scene.generated
    if generate:
        length = profiles[0][1] / generate["spacing"]
        c, kx, ky, _ = _anisotropic(generate)
        exact = surface.series_moments_2d(c, kx, ky)
        for name, value in exact.items():
            if name not in ds:
                continue
            order = int(name[1]) + int(name[2])
            ds[f"{name}_exact"] = xr.DataArray(
                value * length ** (2 - order),
                attrs=attrs(ds[name].attrs["units"], f"{ds[name].attrs['long_name']}, exact (eq. 2.4)"))
    ds.attrs["population_estimator"] = estimator
    return ds
