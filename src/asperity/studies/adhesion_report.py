"""An adhesive scene beside its elastic twin (report 7.3, 9.1): what adhesion changes, and
whether the adhesive asperities stay where their model holds.

:func:`adhesion_report` reads the adhesive scene's asperities, interface, friction and
surface, and its twin's (the same scene without ``adhesion``), and writes:

* per curvature sample: the tip radius R = 1 / kappa, the Tabor parameter
  mu_T = (R dgamma^2 / (E*^2 d^3))^(1/3) (report 7.3), the pull-off force over JKR's
  3/2 pi R W_c and over Derjaguin's (DMT, rigid sphere) 2 pi R W_c, the interferences of
  the jump into and out of contact, and the share of the grid points in contact where the
  asperity is still elastic (the finite element job's flag, Fig. 7.10): the adhesive body
  is elastic, so this share says how far its response can be trusted;
* the share of the summits above 1 and 2 sigma whose curvature lies outside the samples
  (Nayak's joint density, report 2.4.1, of the scene's surface statistics): the
  homogenization gives them the response of the nearest sample;
* the interface: the largest attraction on approach, the pull-off pressure on retraction,
  the approach pressure at a separation of 1 sigma with and without adhesion;
* friction (9.1): mu at 1 sigma and at the lightest positive load, the twin's range;
* per branch, the range of the elastic share of contacting asperities and the valid
  separations; the twin's elastic share.

Nothing is computed again but the density's shares: the table says what the scenes'
files say.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from scipy import integrate

from asperity import peaks
from asperity.population.density import height_scale, population_stat
from asperity.units import attrs

__all__ = ["adhesion_report", "outside_samples"]


def outside_samples(surface: xr.Dataset, curvatures: np.ndarray, levels=(1, 2)) -> dict:
    """Share of the summits above ``n`` sigma (n in `levels`) flatter than the flattest of
    `curvatures` [1/m] and steeper than the steepest, from Nayak's joint density of the
    surface's statistics: the density integrated by the trapezoid rule over height (n to
    8 sigma) and cumulatively over curvature (0 to 15 sigma_curvature), read at the two
    curvatures by linear interpolation."""
    stats = {v: population_stat(surface, v) for v in ("sigma", "sigma_slope", "sigma_curvature")}
    density = peaks.JointDensity(**stats)
    s = stats["sigma"]
    k = np.linspace(0.0, 15 * stats["sigma_curvature"], 3001)
    out = {}
    for n in levels:
        z = np.linspace(n * s, 8 * s, 701)
        Z, K = np.meshgrid(z, k, indexing="ij")
        mass = integrate.cumulative_trapezoid(integrate.trapezoid(density.pdf(Z, K), z, axis=0), k, initial=0.0)
        share = np.interp([curvatures.min(), curvatures.max()], k, mass / mass[-1])
        out[f"flatter_above_{n}_sigma"] = float(share[0])
        out[f"steeper_above_{n}_sigma"] = float(1.0 - share[1])
    return out


def _range(x: np.ndarray) -> tuple[float, float]:
    x = x[np.isfinite(x)]
    return (float(x.min()), float(x.max())) if x.size else (np.nan, np.nan)


def _per_tip(asperities: xr.Dataset) -> dict:
    touching = asperities["in_contact"] > 0
    elastic = (asperities["elastic"] > 0) & touching
    dims = [d for d in touching.dims if d != "curvature"]
    share = elastic.sum(dims) / touching.sum(dims).where(touching.sum(dims) > 0)
    pull = asperities["pull_off_force"]
    return {
        "tip_radius": (1.0 / asperities["curvature"]).values,
        "tabor_parameter": asperities["tabor_parameter"].values,
        "pull_off_over_jkr": (pull / asperities["pull_off_force_jkr"]).values,
        "pull_off_over_dmt": (pull / asperities["pull_off_force_dmt"]).values,
        "jump_in_interference": asperities["jump_in_interference"].values,
        "jump_off_interference": asperities["jump_off_interference"].values,
        "elastic_share_in_contact": share.values,
    }


def _per_branch(interface: xr.Dataset, sigma: float) -> dict:
    out: dict = {k: [] for k in ("elastic_fraction_low", "elastic_fraction_high", "valid_from", "valid_to")}
    for b in interface["branch"].values:
        ds = interface.sel(branch=b)
        touching = ds["contact_count"].values > 0
        lo, hi = _range(ds["elastic_fraction"].values[touching])
        valid = ds["valid"].values.astype(bool)
        h = ds["separation"].values[valid] / sigma
        out["elastic_fraction_low"].append(lo)
        out["elastic_fraction_high"].append(hi)
        out["valid_from"].append(float(h.min()) if h.size else np.nan)
        out["valid_to"].append(float(h.max()) if h.size else np.nan)
    return out


def _approach(interface: xr.Dataset) -> xr.Dataset:
    return interface.sel(branch="approach") if "branch" in interface.dims else interface


def adhesion_report(scene: tuple[xr.Dataset, ...], twin: tuple[xr.Dataset, ...]) -> xr.Dataset:
    """Module text.  `scene`: the adhesive scene's (asperities, interface, friction,
    surface); `twin`: its elastic twin's (interface, friction, surface)."""
    asperities, interface, friction, surface = scene
    twin_interface, twin_friction, twin_surface = twin
    sigma, twin_sigma = height_scale(surface), height_scale(twin_surface)
    p, sep, mu = (friction[v].values for v in ("nominal_pressure", "separation", "mu"))
    lightest = int(np.nanargmax(np.where(p > 0, sep, np.nan)))
    twin_elastic = _range(twin_interface["elastic_fraction"].where(twin_interface["contact_count"] > 0).values)
    scalars = {
        "sigma": (sigma, "m", "standard deviation of the heights that separations are measured in"),
        "fe_jobs": (int(asperities.attrs["fe_jobs"]), "1", "finite element jobs of the adhesive scene"),
        "fe_cpu_time": (float(asperities.attrs["fe_cpu_time"]), "s", "CPU time of those jobs"),
        **{k: (v, "1", f"share of the summits {k.split('_', 1)[1].replace('_', ' ')} "
                       f"{'flatter than the flattest' if k.startswith('flatter') else 'steeper than the steepest'}"
                       " curvature sample (Nayak's density)")
           for k, v in outside_samples(surface, asperities["curvature"].values).items()},
        "largest_attraction_approach": (float(interface.attrs["largest_attraction_approach"]), "Pa",
                                        "largest nominal attraction before contact on approach"),
        "pull_off_pressure": (float(interface.attrs["pull_off_pressure"]), "Pa",
                              "largest nominal tension on retraction (pull-off)"),
        "pressure_at_1_sigma": (float(_approach(interface)["nominal_pressure"].interp(separation=sigma)), "Pa",
                                "nominal pressure on approach at a separation of 1 sigma"),
        "twin_pressure_at_1_sigma": (float(_approach(twin_interface)["nominal_pressure"].interp(
            separation=twin_sigma)), "Pa", "the elastic twin's nominal pressure at 1 sigma"),
        "mu_at_1_sigma": (float(np.interp(sigma, sep, mu)), "1", "friction coefficient at 1 sigma"),
        "mu_at_lightest_load": (float(mu[lightest]), "1",
                                "friction coefficient at the largest separation with a positive load"),
        "lightest_load": (float(p[lightest]), "Pa", "that load, nominal pressure"),
        "twin_mu_low": (float(np.nanmin(twin_friction["mu"])), "1", "the twin's least friction coefficient"),
        "twin_mu_high": (float(np.nanmax(twin_friction["mu"])), "1", "the twin's largest friction coefficient"),
        "twin_elastic_fraction_low": (twin_elastic[0], "1", "the twin's least elastic share of contacts"),
        "twin_elastic_fraction_high": (twin_elastic[1], "1", "the twin's largest elastic share of contacts"),
    }
    tip_meta = {
        "tip_radius": ("m", "tip radius 1 / kappa"),
        "tabor_parameter": ("1", "Tabor parameter (R dgamma^2 / (E*^2 d^3))^(1/3)"),
        "pull_off_over_jkr": ("1", "pull-off force over JKR's 3/2 pi R W_c"),
        "pull_off_over_dmt": ("1", "pull-off force over DMT's 2 pi R W_c"),
        "jump_in_interference": ("m", "interference of the jump into contact (NaN: none)"),
        "jump_off_interference": ("m", "interference of the jump out of contact (NaN: none)"),
        "elastic_share_in_contact": ("1", "share of the grid points in contact where the asperity is elastic"),
    }
    branch_meta = {
        "elastic_fraction_low": ("1", "least share of contacting asperities still elastic"),
        "elastic_fraction_high": ("1", "largest share of contacting asperities still elastic"),
        "valid_from": ("1", "smallest valid separation over sigma"),
        "valid_to": ("1", "largest valid separation over sigma"),
    }
    tips, branches = _per_tip(asperities), _per_branch(interface, sigma)
    data = {k: ((), v, attrs(u, n)) for k, (v, u, n) in scalars.items()}
    data.update({k: ("curvature", tips[k], attrs(*m)) for k, m in tip_meta.items()})
    data.update({k: ("branch", branches[k], attrs(*m)) for k, m in branch_meta.items()})
    coords = {"curvature": ("curvature", asperities["curvature"].values, attrs("1/m", "tip curvature sample")),
              "branch": ("branch", [str(b) for b in interface["branch"].values], attrs("", "branch of the path"))}
    return xr.Dataset(data, coords=coords)
