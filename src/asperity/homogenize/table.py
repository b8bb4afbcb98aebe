"""The asperity responses of a population as a table, interpolated (report 2.5, 8.3).

An asperities dataset (``force``, ``contact_area``, ... on height, curvature and
interference) becomes a `ResponseTable`: the variables stacked on a regular
(height, curvature, interference) grid, with X = 0 at w = 0 added below the first
interference.  The expectation (`asperity.homogenize.integrate`) and the interacting
route's finite element law (`asperity.stages.routes.fe_law`) read it by multilinear
interpolation, clamped at the grid's ends: on the quadrature's tensor nodes
(`interpolate_tensor`) or at scattered points (`interpolate_points`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import xarray as xr

__all__ = ["DEFAULT_UNITS", "ResponseTable", "response_table", "check_reach", "check_interference",
           "interpolate_tensor", "interpolate_points", "lerp", "axis_weights"]

#: the units of the asperity variables a dataset gives without
DEFAULT_UNITS = {"force": "N", "contact_area": "m^2", "stiffness": "N/m", "contact_radius": "m"}


def lerp(a, b, t, finite=False):
    """(1 - t) a + t b, exact at t = 0 and t = 1 even if the other end is infinite.

    With ``finite=True`` (no inf/nan in the table) the cheaper a + t (b - a).
    """
    if finite:
        return a + t * (b - a)
    with np.errstate(invalid="ignore", over="ignore"):
        mid = (1.0 - t) * a + t * b
    return np.where(t == 0.0, a, np.where(t == 1.0, b, mid))


def axis_weights(grid: np.ndarray, x):
    """Indices lo, hi and fraction t of linear interpolation on `grid`, clamped at the ends.

    A single-point grid means independence of that variable (lo = hi = 0).
    """
    x = np.asarray(x, dtype=float)
    if grid.size == 1:
        zero = np.zeros(x.shape, dtype=np.intp)
        return zero, zero, np.zeros(x.shape)
    xc = np.clip(x, grid[0], grid[-1])
    lo = np.clip(np.searchsorted(grid, xc, side="right") - 1, 0, grid.size - 2)
    t = (xc - grid[lo]) / (grid[lo + 1] - grid[lo])
    return lo, lo + 1, t


class ResponseTable(NamedTuple):
    names: list
    units: list
    heights: np.ndarray
    curvatures: np.ndarray
    interference: np.ndarray
    data: np.ndarray  # (Nh, Nk, Nw, V)
    finite: bool  # no inf/nan in data: plain linear interpolation


def response_table(asperities: xr.Dataset) -> ResponseTable:
    dims = ("height", "curvature", "interference")
    for d in dims:
        if d not in asperities.dims:
            raise ValueError(f"asperities dataset lacks dimension {d!r} (needs {dims})")
    names = [str(v) for v in asperities.data_vars]
    if not names:
        raise ValueError("asperities dataset has no data variables")
    ds = asperities.sortby(["height", "curvature"])
    arrays, units = [], []
    for name in names:
        da = ds[name]
        if set(da.dims) - set(dims):
            raise ValueError(f"variable {name!r} has dimensions {da.dims} beyond {dims}")
        units.append(str(da.attrs.get("units", DEFAULT_UNITS.get(name, ""))))
        missing = {d: ds.sizes[d] for d in dims if d not in da.dims}
        da = da.astype(float).expand_dims(missing).transpose(*dims)
        arrays.append(np.asarray(da.values))
    data = np.stack(arrays, axis=-1)
    zc = np.asarray(ds["height"].values, dtype=float)
    kc = np.asarray(ds["curvature"].values, dtype=float)
    wc = np.asarray(ds["interference"].values, dtype=float)
    for label, c in (("height", zc), ("curvature", kc)):
        if c.size > 1 and np.any(np.diff(c) <= 0.0):
            raise ValueError(f"{label} coordinate has repeated values")
    if wc.size == 0 or np.any(np.diff(wc) <= 0.0):
        raise ValueError("interference coordinate must be strictly increasing")
    if wc[0] > 0.0:  # X = 0 at w = 0, linear up to the first interference
        wc = np.concatenate([[0.0], wc])
        data = np.concatenate([np.zeros(data[:, :, :1].shape), data], axis=2)
    return ResponseTable(names, units, zc, kc, wc, data, bool(np.isfinite(data).all()))


def check_reach(reach: float, table: ResponseTable) -> float:
    """The attraction range (>= 0) against the table: it must start at w <= -reach."""
    reach = float(reach)
    if not (np.isfinite(reach) and reach >= 0.0):
        raise ValueError(f"reach must be a finite non-negative interference, got {reach!r}")
    if table.interference[0] < 0.0 and reach == 0.0:
        raise ValueError("negative interferences in the asperity table need reach > 0 "
                         "(the gap up to which asperities out of contact still act)")
    if table.interference[0] > -reach * (1.0 - 1e-9):
        raise ValueError(f"reach {reach:.6g} needs the interference grid to start at "
                         f"-{reach:.6g} or below; it starts at {table.interference[0]:.6g}")
    return reach


def check_interference(w_needed: float, table: ResponseTable):
    w_max = table.interference[-1]
    if w_needed > w_max * (1.0 + 1e-9):
        raise ValueError(
            f"the quadrature needs asperity responses up to interference {w_needed:.6g}, "
            f"but the interference grid ends at {w_max:.6g}; extend the grid to at least "
            "z_max - min(separation), or raise the smallest separation / lower z_max"
        )


def interpolate_tensor(table: ResponseTable, z, w, k_nodes):
    """X at (z, kappa, w) with z, w of shape (S, Pz) and kappa nodes (Pk,): (S, Pz, Pk, V)."""
    d = table.data
    fin = table.finite
    klo, khi, kt = axis_weights(table.curvatures, k_nodes)
    dk = lerp(d[:, klo], d[:, khi], kt[None, :, None, None], fin)  # (Nh, Pk, Nw, V)
    dk = np.moveaxis(dk, 2, 1)  # (Nh, Nw, Pk, V)
    hlo, hhi, ht = axis_weights(table.heights, z)
    wlo, whi, wt = axis_weights(table.interference, w)
    wt = wt[..., None, None]
    at_hlo = lerp(dk[hlo, wlo], dk[hlo, whi], wt, fin)
    if table.heights.size == 1:  # independent of height
        return at_hlo
    at_hhi = lerp(dk[hhi, wlo], dk[hhi, whi], wt, fin)
    return lerp(at_hlo, at_hhi, ht[..., None, None], fin)


def interpolate_points(table: ResponseTable, z, k, w):
    """X at scattered points (z, kappa, w), broadcast shape B: (*B, V)."""
    d = table.data
    fin = table.finite
    hlo, hhi, ht = axis_weights(table.heights, z)
    klo, khi, kt = axis_weights(table.curvatures, k)
    wlo, whi, wt = axis_weights(table.interference, w)
    ht, kt, wt = (t[..., None] for t in (ht, kt, wt))

    def at(hi_, ki_):
        return lerp(d[hi_, ki_, wlo], d[hi_, ki_, whi], wt, fin)

    def at_height(hi_):
        return lerp(at(hi_, klo), at(hi_, khi), kt, fin)

    if table.heights.size == 1:  # independent of height
        return at_height(hlo)
    return lerp(at_height(hlo), at_height(hhi), ht, fin)
