"""Stage `surface` (workflow/rules/surface.smk): surface.nc from a profile, profiles, a map,
or statistics given in the scene (report 2.3, 2.4.3, 2.6.1); synthetic surfaces."""

from __future__ import annotations

import logging
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import surface
from asperity.scene import length_factor
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]


def synthetic_profile(generate: Config) -> tuple[np.ndarray, np.ndarray]:
    """Positions and heights of a synthetic profile of report 2.6.1, scene units."""
    x = np.arange(0.0, generate["length"] + 0.5 * generate["spacing"], generate["spacing"])
    if generate["kind"] == "cosine":
        return x, generate["amplitude"] * np.cos(generate["wavenumber"] * x)
    c, k, e = surface.quasirandom_series(n=generate["components"], seed=generate["seed"])
    return x, surface.evaluate_series(x, c, k, e)


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


def surface_from_profile(z: np.ndarray, dx: float, surface_cfg: Config) -> xr.Dataset:
    """Profile statistics by sampling, counting and spectrum (2.3.1), SI input.

    For a synthetic profile the exact statistics are added as method
    ``exact`` (cosine: closed form; series: eq. 2.4).
    """
    ds = surface.profile_statistics(z, dx)
    generate = surface_cfg["profile"].get("generate")
    if generate:
        # the synthetic profile was written in scene units and read back in SI;
        # its exact statistics scale with the same factor
        length = dx / generate["spacing"]
        exact = _series_reference(generate, length)
        extra = xr.full_like(ds.isel(method=0), np.nan).expand_dims(method=["exact"])
        for name, value in exact.items():
            extra[name] = extra[name].copy(data=np.array([value]))
        extra["m0"] = extra["sigma"] ** 2
        extra["m2"] = extra["sigma_slope"] ** 2
        extra["m4"] = extra["sigma_curvature"] ** 2
        extra["peak_density"] = extra["m4"] / (6 * np.pi * np.sqrt(3) * extra["m2"])
        merged = xr.concat([ds, extra], dim="method", data_vars="all", coords="minimal")
        for name in ds.variables:
            merged[name].attrs = ds[name].attrs
        ds = merged
    ds.attrs["population_method"] = surface_cfg.get("method", "sampling")
    return ds


def surface_from_map(z: np.ndarray, dx: float, dy: float, surface_cfg: Config) -> xr.Dataset:
    """Statistics and peaks of a 2-D height map (2.4.3), SI input."""
    ds = xr.merge([surface.map_statistics(z, dx, dy), surface.map_peaks(z, dx, dy)])
    ds.attrs["population_method"] = "map"
    return ds


def surface_from_statistics(surface_cfg: Config, units_cfg: Config) -> xr.Dataset:
    """Surface statistics given in the scene (report 2.6.2), as method ``given``."""
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
        ds.attrs["population_method"] = "gaussian_heights"
        return ds
    st = surface_cfg["statistics"]
    values = {
        "mean_height": (st.get("mean_height", 0.0) * length, "m", "mean height"),
        "sigma": (st["sigma"] * length, "m", "standard deviation of height"),
        "sigma_slope": (st["sigma_slope"], "1", "standard deviation of slope"),
        "sigma_curvature": (st["sigma_curvature"] / length, "1/m", "standard deviation of curvature"),
        "peak_density": (st["peak_density"] / length**2, "1/m^2", "peaks per unit nominal area"),
    }
    ds = xr.Dataset(
        {name: ("method", [v], attrs(u, ln)) for name, (v, u, ln) in values.items()},
        coords={"method": ("method", ["given"], attrs("1", "how the statistics were obtained"))},
    )
    ds["m0"] = (ds["sigma"] ** 2).assign_attrs(attrs("m^2", "spectral moment m0"))
    ds["m2"] = (ds["sigma_slope"] ** 2).assign_attrs(attrs("1", "spectral moment m2"))
    ds["m4"] = (ds["sigma_curvature"] ** 2).assign_attrs(attrs("1/m^2", "spectral moment m4"))
    ds["beta"] = (np.sqrt(1.5) * ds["m2"] / np.sqrt(ds["m0"] * ds["m4"])).assign_attrs(
        attrs("1", "wavelength spectrum parameter beta (2.4.1)")
    )
    ds.attrs["population_method"] = "given"
    return ds


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
        rows.append(stats[names].sel({"method": ["sampling", "counting", "spectral"]}))
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


def synthetic_map(generate: Config) -> np.ndarray:
    """A Gaussian random height map (scene units) with a Gaussian autocorrelation.

    White noise filtered in Fourier space by exp(-k^2 l^2 / 8), which gives
    the autocorrelation exp(-r^2 / l^2) (l: correlation length), scaled to
    the standard deviation `sigma`.  Periodic, so the eight-neighbour peak
    rule of 2.4.3 sees no edge effects.
    """
    n, h = generate["points"], generate["spacing"]
    rng = np.random.default_rng(generate["seed"])
    noise = rng.standard_normal((n, n))
    k = 2 * np.pi * np.fft.fftfreq(n, d=h)
    k2 = k[:, None] ** 2 + k[None, :] ** 2
    z = np.fft.ifft2(np.fft.fft2(noise) * np.exp(-k2 * generate["correlation_length"] ** 2 / 8)).real
    z -= z.mean()
    return z * (generate["sigma"] / z.std())


def profile_file_name(direction_deg: float) -> str:
    """File name of the synthetic profile along `direction_deg`."""
    return f"profile_{direction_deg:g}deg.txt"


def anisotropic_series(generate: Config):
    """Amplitudes, wave vectors and phases of a synthetic anisotropic surface (eq. 2.3).

    The 1-D quasi-random series of 2.6.1 with each wave vector turned to a
    random direction and its x component stretched by `aspect`.
    """
    c, k, e = surface.quasirandom_series(n=generate["components"], seed=generate["seed"])
    phi = np.random.default_rng(generate["seed"] + 1).uniform(0.0, np.pi, c.size)
    return c, generate["aspect"] * k * np.cos(phi), k * np.sin(phi), e


def synthetic_directional_profiles(generate: Config) -> list[tuple[np.ndarray, np.ndarray]]:
    """Profiles z(s) = sum C cos((kx cos t + ky sin t) s + e) along each direction t."""
    c, kx, ky, e = anisotropic_series(generate)
    s = np.arange(0.0, generate["length"] + 0.5 * generate["spacing"], generate["spacing"])
    out = []
    for deg in generate["directions"]:  # a handful of directions
        t = np.radians(deg)
        out.append((s, surface.evaluate_series(s, c, kx * np.cos(t) + ky * np.sin(t), e)))
    return out


def surface_from_profiles(
    profiles: list[tuple[np.ndarray, float]], directions_deg: list[float], surface_cfg: Config,
) -> xr.Dataset:
    """Statistics of profiles along several directions and the surface moments (2.3.2).

    Each profile gets the statistics of `profile_statistics` (dim
    ``direction``); the moments m20, m11, m02 (3 directions or more) and the
    fourth-order moments (5 or more) follow by least squares from the
    chosen method's m0, m2, m4, with the invariants of 2.3.2.  For a
    synthetic surface the exact moments of eq. (2.4) are added as
    ``<moment>_exact``.
    """
    method = surface_cfg.get("method", "sampling")
    stats = xr.concat([surface.profile_statistics(z, dx) for z, dx in profiles], dim="direction",
                      data_vars="all", coords="minimal", compat="override")
    theta = np.radians(np.asarray(directions_deg, float))
    stats = stats.assign_coords(direction=("direction", theta, attrs("rad", "profile direction from the x axis")))
    chosen = stats.sel({"method": method})
    moments = surface.directional_moments(theta, chosen["m0"].values, chosen["m2"].values, chosen["m4"].values)
    ds = xr.merge([stats, moments], combine_attrs="drop_conflicts")
    ds.attrs.update(moments.attrs)
    generate = surface_cfg["profiles"].get("generate")
    if generate:
        length = profiles[0][1] / generate["spacing"]
        c, kx, ky, _ = anisotropic_series(generate)
        exact = surface.series_moments_2d(c, kx, ky)
        for name, value in exact.items():
            if name not in ds:
                continue
            order = int(name[1]) + int(name[2])
            ds[f"{name}_exact"] = xr.DataArray(
                value * length ** (2 - order),
                attrs=attrs(ds[name].attrs["units"], f"{ds[name].attrs['long_name']}, exact (eq. 2.4)"))
    ds.attrs["population_method"] = method
    return ds
