"""Statistics and asperity peaks of a 2-D height map (report 2.4.3, 2.3.1, 2.3.2).

* :func:`map_statistics` -- sampling of the heights, slopes and curvatures
  along x and y, the nine spectral moments as covariances of derivatives,
  their invariants (2.3.2), and the density of peaks;
* :func:`map_peaks` -- the asperity peaks by the eight-neighbour rule and
  their heights and curvatures (2.4.3).

Axis convention: ``z[i, j] = z(x = j dx, y = i dy)``: axis 1 (along a row)
is x, axis 0 (along a column) is y.

Undefined points (a ``defined`` mask, False where the instrument measured
nothing): a derivative is used only where its whole stencil is defined, a
peak only where its eight neighbours are defined, its curvature from the
largest stencil that is wholly defined around it, and the peak density is
per defined area (the points whose eight neighbours are defined, where a
peak could have been found).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from asperity.surface.directional import INVARIANT_TEXT, INVARIANT_UNITS, MOMENT_UNITS, moment_invariants
from asperity.surface.missing import complete_neighbourhood, defined_heights
from asperity.surface.statistics import (DEFAULT_ORDER, _check_order, _spacing, derivatives, mean_and_deviation,
                                         stencil)

__all__ = ["AXES", "map_statistics", "map_peaks"]

AXES = "z[i, j] = z(x = j dx, y = i dy): x along rows (axis 1), y along columns (axis 0)"


def _peak_mask(z: np.ndarray) -> np.ndarray:
    """Interior points strictly higher than their eight neighbours (2.4.3).

    A comparison with an undefined (NaN) height is false, so a point next
    to an undefined one, or undefined itself, is never a peak.
    """
    c = z[1:-1, 1:-1]
    ny, nx = z.shape
    mask = np.ones(c.shape, dtype=bool)
    for di in (-1, 0, 1):  # the eight neighbour offsets, not the points
        for dj in (-1, 0, 1):
            if di or dj:
                mask &= c > z[1 + di : ny - 1 + di, 1 + dj : nx - 1 + dj]
    return mask


def _check_map(z, dx, dy, defined):
    zz, mask = defined_heights(z, defined, 2, "map")
    if zz.shape[0] < 3 or zz.shape[1] < 3:
        raise ValueError(f"a map needs at least 3 x 3 points (one interior point); got shape {zz.shape}")
    return zz, mask, _spacing(dx, "dx"), _spacing(dy, "dy")


def map_peaks(z, dx: float, dy: float, order: int = DEFAULT_ORDER, *, defined=None) -> xr.Dataset:
    """Asperity peaks of a height map by the eight-neighbour rule (report 2.4.3).

    A peak is an interior point strictly higher than all eight nearest
    neighbours (boundary points, which lack neighbours, are never peaks).
    At each peak the second derivatives are central differences of order
    ``order`` (see :func:`stencil`; z_xy uses the tensor product of the
    first-derivative formulas), reduced to the largest even order that fits
    inside the map for peaks near the edge (2 for a peak next to the edge;
    the order used is returned in ``fd_order``), and likewise to the
    largest stencil that is wholly defined around a peak near undefined
    points.  For a component
    cos(k x) the relative error of z_xx is 2 (p!)^2/(2p+2)! (k dx)^{2p}
    (exactly 1 - 2 (1 - cos k dx)/(k dx)^2 for order 2).

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        Heights, ``z[i, j] = z(x = j dx, y = i dy)`` (m).
    dx, dy : float
        Grid spacings along x (axis 1) and y (axis 0) (m).

    Returns
    -------
    xarray.Dataset
        Dimension ``peak``; x, y (m, origin at ``z[0, 0]``), row, column,
        height (above the mean height of the map), curvature =
        -(z_xx + z_yy)/2 (mean curvature, positive at a peak, the kappa of
        2.4.1 / 2.5.1: C k^2 for the hill C cos kx cos ky), z_xx, z_yy, z_xy,
        fd_order.
    """
    zz, mask, hx, hy = _check_map(z, dx, dy, defined)
    order = _check_order(order)
    pmax = order // 2
    ny, nx = zz.shape
    ii, jj = np.nonzero(_peak_mask(zz))
    ii += 1
    jj += 1
    # largest half-width whose square fits in the map and is wholly defined around each peak
    p = np.ones(ii.shape, dtype=np.int64)
    for q in range(2, pmax + 1):  # loop over stencil sizes, not peaks
        p = np.where((p == q - 1) & complete_neighbourhood(mask, q)[ii, jj], q, p)
    zz = np.where(mask, zz, 0.0)  # weights beyond a peak's stencil are zero: 0, not NaN, there
    # coefficient tables, row q = weights of the order-2q formulas, zero padded
    A = np.zeros((pmax + 1, pmax))
    B = np.zeros((pmax + 1, pmax + 1))
    for q in range(1, pmax + 1):  # loop over orders, not peaks
        a, b = stencil(2 * q)
        A[q, :q] = a
        B[q, : q + 1] = b
    off = np.arange(1, pmax + 1)
    a = A[p]  # (npk, pmax)
    b = B[p]
    # gathered values; offsets beyond a peak's p have zero weight, so clip indices
    def at(di, dj):
        return zz[np.clip(ii[:, None] + di, 0, ny - 1), np.clip(jj[:, None] + dj, 0, nx - 1)]

    z0 = zz[ii, jj]
    zxx = (b[:, 0] * z0 + np.sum(b[:, 1:] * (at(0, off) + at(0, -off)), axis=1)) / (hx * hx)
    zyy = (b[:, 0] * z0 + np.sum(b[:, 1:] * (at(off, 0) + at(-off, 0)), axis=1)) / (hy * hy)
    # z_xy = sum_{r,s} a_r a_s (z(+r,+s) - z(+r,-s) - z(-r,+s) + z(-r,-s)) / (dx dy), r on y, s on x
    di = off[None, :, None]
    dj = off[None, None, :]

    def at3(si, sj):
        return zz[
            np.clip(ii[:, None, None] + si * di, 0, ny - 1),
            np.clip(jj[:, None, None] + sj * dj, 0, nx - 1),
        ]

    w = a[:, :, None] * a[:, None, :]
    zxy = np.sum(w * (at3(1, 1) - at3(1, -1) - at3(-1, 1) + at3(-1, -1)), axis=(1, 2)) / (hx * hy)
    npk = ii.size
    mean_z = float(zz[mask].mean())

    def var(values, units, long_name):
        return ("peak", values, {"units": units, "long_name": long_name})

    return xr.Dataset(
        {
            "x": var(jj * hx, "m", "x of the peak (column * dx)"),
            "y": var(ii * hy, "m", "y of the peak (row * dy)"),
            "row": var(ii.astype(np.int64), "1", "row index of the peak in the map (y)"),
            "column": var(jj.astype(np.int64), "1", "column index of the peak in the map (x)"),
            "height": var(z0 - mean_z, "m", "peak height above the mean height of the map"),
            "curvature": var(-0.5 * (zxx + zyy), "1/m", "mean peak curvature -(z_xx + z_yy)/2"),
            "z_xx": var(zxx, "1/m", "second derivative d2z/dx2 at the peak"),
            "z_yy": var(zyy, "1/m", "second derivative d2z/dy2 at the peak"),
            "z_xy": var(zxy, "1/m", "mixed second derivative d2z/dxdy at the peak"),
            "fd_order": var((2 * p).astype(np.int64), "1", "order of the central differences used"),
        },
        coords={"peak": ("peak", np.arange(npk), {"units": "1", "long_name": "peak number"})},
        attrs={
            "title": "asperity peaks of a height map, eight-neighbour rule (report 2.4.3)",
            "mean_height": mean_z,
            "finite_difference_order": order,
        },
    )


def map_statistics(z, dx: float, dy: float, order: int = DEFAULT_ORDER, *, defined=None) -> xr.Dataset:
    """Sampling statistics and peak density of a height map (report 2.4.3, 2.3.1, 2.3.2).

    Mean height and (n-1) standard deviation over all defined points
    (2.4.3); means and standard deviations of slopes and curvatures along x
    (within rows, axis 1) and along y (within columns, axis 0) from
    :func:`derivatives` (central differences of ``order``, the order/2
    points nearest the ends of each line dropped, and any whose stencil
    meets an undefined point); peak count by the eight-neighbour rule
    (:func:`map_peaks`) and peak density = count / tested area, the points
    whose eight neighbours are defined times dx dy ((nx - 2) dx (ny - 2) dy
    for a complete map).

    The map also gives its nine spectral moments as covariances of the
    derivatives (stationary field, eq. (2.2)): m00 = sigma^2,
    m20 = var z_x, m02 = var z_y, m40 = var z_xx, m04 = var z_yy (the same
    samples as sigma_slope_x, ... above), and, on the points where both are
    defined, m11 = cov(z_x, z_y), m31 = cov(z_xx, z_xy), m22 = var z_xy,
    m13 = cov(z_xy, z_yy) (z_xy = d/dy of z_x); with them the invariants of
    2.3.2.

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        ``z[i, j] = z(x = j dx, y = i dy)`` (m); at least order + 2 points
        along each axis.
    defined : boolean array of the shape of z, optional
        False at undefined points (default: all defined).
    """
    zz, mask, hx, hy = _check_map(z, dx, dy, defined)
    order = _check_order(order)
    ny, nx = zz.shape
    need = order + 2
    if nx < need or ny < need:
        raise ValueError(
            f"map_statistics with order-{order} differences needs at least {need} points "
            f"along each axis; got shape {zz.shape} (rows, columns)"
        )
    p = order // 2
    values = zz[mask]
    mean_z = float(values.mean())
    sigma = float(np.std(values, ddof=1)) if values.size > 1 else np.nan
    zx, zxx = derivatives(zz, hx, order, axis=1)  # (ny, nx - 2p); NaN where a stencil is incomplete
    zy, zyy = derivatives(zz, hy, order, axis=0)  # (ny - 2p, nx)
    zxy, _ = derivatives(zx, hy, order, axis=0, curvature=False)  # (ny - 2p, nx - 2p)
    # common interior
    zx_c = zx[p : ny - p, :]
    zy_c = zy[:, p : nx - p]
    zxx_c = zxx[p : ny - p, :]
    zyy_c = zyy[:, p : nx - p]

    def cov(u, v):
        both = np.isfinite(u) & np.isfinite(v)
        u, v = u[both], v[both]
        u = u - u.mean()
        v = v - v.mean()
        return float(u @ v / (u.size - 1)) if u.size > 1 else np.nan

    s = {}
    for name, a in (("x", zx), ("y", zy)):
        s[f"mean_slope_{name}"], s[f"sigma_slope_{name}"], n_slope = mean_and_deviation(a)
        if n_slope < 2:
            raise ValueError(
                f"map_statistics with order-{order} differences needs at least two points whose "
                f"whole stencil along {name} ({order + 1} points) is defined; the map has {n_slope}"
            )
    for name, a in (("x", zxx), ("y", zyy)):
        s[f"mean_curvature_{name}"], s[f"sigma_curvature_{name}"], _ = mean_and_deviation(a)
    mom = {
        "m00": sigma**2,
        "m20": s["sigma_slope_x"] ** 2,
        "m11": cov(zx_c, zy_c),
        "m02": s["sigma_slope_y"] ** 2,
        "m40": s["sigma_curvature_x"] ** 2,
        "m31": cov(zxx_c, zxy),
        "m22": cov(zxy, zxy),
        "m13": cov(zxy, zyy_c),
        "m04": s["sigma_curvature_y"] ** 2,
    }
    inv = moment_invariants(**mom)
    count = int(np.count_nonzero(_peak_mask(zz)))
    tested = (nx - 2) * (ny - 2) if mask.all() else int(np.count_nonzero(complete_neighbourhood(mask, 1)))
    area = tested * hx * hy

    def v(val, units, long_name):
        return ((), val, {"units": units, "long_name": long_name})

    data = {
        "mean_height": v(mean_z, "m", "mean height of the map"),
        "sigma": v(sigma, "m", "standard deviation of height"),
        "mean_slope_x": v(s["mean_slope_x"], "1", "mean slope along x"),
        "mean_slope_y": v(s["mean_slope_y"], "1", "mean slope along y"),
        "mean_curvature_x": v(s["mean_curvature_x"], "1/m", "mean second derivative along x"),
        "mean_curvature_y": v(s["mean_curvature_y"], "1/m", "mean second derivative along y"),
        "sigma_slope_x": v(s["sigma_slope_x"], "1", "standard deviation of slope along x"),
        "sigma_slope_y": v(s["sigma_slope_y"], "1", "standard deviation of slope along y"),
        "sigma_curvature_x": v(s["sigma_curvature_x"], "1/m", "standard deviation of second derivative along x"),
        "sigma_curvature_y": v(s["sigma_curvature_y"], "1/m", "standard deviation of second derivative along y"),
        # the profile moments of an isotropic surface with the same invariants (2.3.2):
        # m2 = (m20 + m02)/2, m4 = 3 (m40 + 2 m22 + m04)/8 (the averages over directions),
        # what the Nayak density of 2.4.1 takes
        "sigma_slope": v(float(np.sqrt(inv[2] / 2)), "1",
                         "standard deviation of slope of the isotropic equivalent, sqrt((m20 + m02)/2)"),
        "sigma_curvature": v(float(np.sqrt(3 * inv[4] / 8)), "1/m",
                             "standard deviation of curvature of the isotropic equivalent, "
                             "sqrt(3 (m40 + 2 m22 + m04)/8)"),
        "peak_count": v(np.int64(count), "1", "number of peaks (eight-neighbour rule)"),
        "peak_density": v(count / area if area > 0 else np.nan, "1/m^2",
                          "peaks per unit tested area (points with eight defined neighbours)"),
        "tested_area": v(area, "m^2", "area where a peak can be found: points with eight defined neighbours"),
        "points_x": v(np.int64(nx), "1", "number of points along x"),
        "points_y": v(np.int64(ny), "1", "number of points along y"),
        "points_defined": v(np.int64(values.size), "1", "number of defined points of the map"),
        "spacing_x": v(hx, "m", "grid spacing along x"),
        "spacing_y": v(hy, "m", "grid spacing along y"),
    }
    for name, val in mom.items():
        data[name] = v(val, MOMENT_UNITS[name], f"spectral moment m_{name[1]}{name[2]} from derivative covariances")
    for key, val in inv.items():
        data[f"invariant_{key}"] = v(val, INVARIANT_UNITS[key], f"moment invariant {key}: {INVARIANT_TEXT[key]}")
    return xr.Dataset(
        data,
        attrs={"title": "height map statistics (report 2.4.3)", "finite_difference_order": order, "axes": AXES},
    )
