"""Where each scene's interface law holds: the validity of several scenes in one table.

:func:`validity_summary` reads the interface of each scene (its ``valid`` and
``validity`` per separation, `asperity.homogenize.validity`) on its first branch (loading; approach with adhesion), and
writes per scene:

* how many separations are valid, of how many, and the range of the valid ones in sigma
  of the scene's heights (`asperity.population.density.height_scale`);
* the limit that fails at most separations (the first word of ``validity``), at how many,
  and the range of its indicator where it fails;
* the hardness H and Greenwood and Williamson's plasticity index psi the scene's validity
  used (NaN where the scene has none);
* the share of the load carried by asperities pressed beyond their finite element job's
  range (``extrapolated_load_fraction``: a representative hill pressed past half its
  height), its range over the loaded separations.

Nothing is computed again: the table says what the scenes' files say.
"""

from __future__ import annotations

from collections import Counter
from typing import Mapping

import numpy as np
import xarray as xr

from asperity.population.density import height_scale
from asperity.units import attrs

__all__ = ["validity_summary"]


def _loading(ds: xr.Dataset) -> xr.Dataset:
    return ds.isel(branch=0) if "branch" in ds.dims else ds  # loading, or an adhesive approach


def _scalar(ds: xr.Dataset, name: str) -> float:
    return float(ds[name]) if name in ds and ds[name].ndim == 0 else float("nan")


def _one(interface: xr.Dataset, surface: xr.Dataset) -> dict:
    ds = _loading(interface)
    sigma = height_scale(surface)
    h = ds["separation"].values / sigma
    valid = ds["valid"].values.astype(bool)
    why = [str(v) for v in ds["validity"].values]
    kinds = Counter(w.split(" ")[0].rstrip(":") for w in why if w)
    limit, fails = kinds.most_common(1)[0] if kinds else ("", 0)
    where = np.array([w.split(" ")[0].rstrip(":") == limit for w in why]) if limit else np.zeros(h.size, bool)
    values = ds[limit].values[where] if limit in ds and ds[limit].dims == ds["valid"].dims else np.array([])
    loaded = np.isfinite(ds["nominal_pressure"].values) & (ds["nominal_pressure"].values > 0)
    share = (ds["extrapolated_load_fraction"].values[loaded] if "extrapolated_load_fraction" in ds
             else np.array([]))
    return {
        "accuracy": str(interface.attrs.get("accuracy", "")),
        "separations": h.size, "valid_separations": int(valid.sum()),
        "valid_from": float(h[valid].min()) if valid.any() else np.nan,
        "valid_to": float(h[valid].max()) if valid.any() else np.nan,
        "failing_limit": limit, "failing_separations": fails,
        "failing_low": float(np.nanmin(values)) if values.size else np.nan,
        "failing_high": float(np.nanmax(values)) if values.size else np.nan,
        "hardness": _scalar(ds, "hardness"), "plasticity_index": _scalar(ds, "plasticity_index"),
        "extrapolated_load_low": float(np.nanmin(share)) if share.size else np.nan,
        "extrapolated_load_high": float(np.nanmax(share)) if share.size else np.nan,
    }


def validity_summary(scenes: Mapping[str, tuple[xr.Dataset, xr.Dataset]]) -> xr.Dataset:
    """Where each scene holds (module text); `scenes`: name -> (interface.nc, surface.nc)."""
    rows = {name: _one(*parts) for name, parts in scenes.items()}
    meta = {
        "accuracy": ("", "accuracy preset of the scene's finite element jobs (none: no FE job)"),
        "separations": ("1", "separations of the loading branch"),
        "valid_separations": ("1", "separations where the interface is valid"),
        "valid_from": ("1", "smallest valid separation over sigma"),
        "valid_to": ("1", "largest valid separation over sigma"),
        "failing_limit": ("", "the limit that fails at most separations (none: empty)"),
        "failing_separations": ("1", "separations where that limit fails first"),
        "failing_low": ("1", "least value of that limit's indicator where it fails"),
        "failing_high": ("1", "largest value of that limit's indicator where it fails"),
        "hardness": ("Pa", "hardness H of the scene's validity (NaN: none)"),
        "plasticity_index": ("1", "Greenwood and Williamson's plasticity index (NaN: none)"),
        "extrapolated_load_low": ("1", "least share of the load beyond the FE jobs' range, loaded separations"),
        "extrapolated_load_high": ("1", "largest share of the load beyond the FE jobs' range, loaded separations"),
    }
    data = {k: ("scene", [rows[n][k] for n in scenes], attrs(*v)) for k, v in meta.items()}
    return xr.Dataset(data, coords={"scene": ("scene", list(scenes), attrs("", "scene"))})
