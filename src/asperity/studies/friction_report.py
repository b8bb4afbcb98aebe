"""The shear part of the friction coefficient against the report's (9.1, Fig. 9.2).

mu_shear = tau_s A_c / p = tau_s / p_r (report 9.41): the junctions' shear strength tau_s
over the mean real contact pressure p_r = p / A_c.  :func:`friction_against_report`
writes, per scene, over the separations where its friction is valid: the range of
mu_shear and of p_r, the report's coefficient and the p_r it would need at the scene's
tau_s, and mu_shear at the shear flow stress tau_s = Y / sqrt 3 of the body (von Mises)
with Y its initial and its saturated flow stress: how much of the difference the
handbook shear strength explains, and how much must be real contact area per load.
"""

from __future__ import annotations

import math
from typing import Mapping

import xarray as xr

from asperity.units import attrs

__all__ = ["friction_against_report"]


def _one(friction: xr.Dataset, interface: xr.Dataset, flow: tuple[float, float]) -> dict:
    if "branch" in interface.dims:
        interface = interface.isel(branch=0)
    p = interface["nominal_pressure"].sel(separation=friction["separation"]).values
    a = interface["contact_area_ratio"].sel(separation=friction["separation"]).values
    keep = friction["valid"].values.astype(bool) & (p > 0) & (a > 0)
    tau = float(friction["junction_shear_strength"])
    mu = friction["mu_shear"].values[keep]
    pr = p[keep] / a[keep]
    report = float(friction["report_mu_shear"]) if "report_mu_shear" in friction else math.nan
    nan = (math.nan, math.nan)
    lo_hi = (lambda v: (float(v.min()), float(v.max())) if v.size else nan)  # noqa: E731
    out = {"shear_strength": tau, "report_mu_shear": report,
           "report_real_pressure": tau / report if report > 0 else math.nan, "valid_separations": int(keep.sum())}
    out["mu_shear_low"], out["mu_shear_high"] = lo_hi(mu)
    out["real_pressure_low"], out["real_pressure_high"] = lo_hi(pr)
    for name, y in zip(("initial", "saturated"), flow):
        out[f"mu_at_{name}_flow_low"], out[f"mu_at_{name}_flow_high"] = lo_hi(y / math.sqrt(3.0) / pr)
    return out


def friction_against_report(scenes: Mapping[str, tuple[xr.Dataset, xr.Dataset, tuple[float, float]]]) -> xr.Dataset:
    """Per scene (name -> (friction.nc, interface.nc, (initial, saturated) uniaxial flow
    stress of its body, Pa; NaN for an elastic body)): module text."""
    rows = {name: _one(*parts) for name, parts in scenes.items()}
    meta = {
        "shear_strength": ("Pa", "junction shear strength tau_s of the scene"),
        "report_mu_shear": ("1", "the report's shear part of the friction coefficient"),
        "report_real_pressure": ("Pa", "mean real contact pressure the report's coefficient needs, tau_s / mu"),
        "valid_separations": ("1", "separations where the friction is valid"),
        "mu_shear_low": ("1", "least mu_shear where valid"), "mu_shear_high": ("1", "largest mu_shear where valid"),
        "real_pressure_low": ("Pa", "least mean real contact pressure p / A_c where valid"),
        "real_pressure_high": ("Pa", "largest mean real contact pressure p / A_c where valid"),
        "mu_at_initial_flow_low": ("1", "least mu_shear with tau_s = Y0 / sqrt 3, Y0 the initial flow stress"),
        "mu_at_initial_flow_high": ("1", "largest mu_shear with tau_s = Y0 / sqrt 3"),
        "mu_at_saturated_flow_low": ("1", "least mu_shear with tau_s = Ys / sqrt 3, Ys the saturated flow stress"),
        "mu_at_saturated_flow_high": ("1", "largest mu_shear with tau_s = Ys / sqrt 3"),
    }
    data = {k: ("scene", [rows[n][k] for n in scenes], attrs(*v)) for k, v in meta.items()}
    return xr.Dataset(data, coords={"scene": ("scene", list(scenes), attrs("", "scene"))})
