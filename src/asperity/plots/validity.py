"""Shading of the separations where an interface leaves the model's validity
(`asperity.homogenize.validity`), shared by the interface, adhesion and friction figures."""

from __future__ import annotations

import numpy as np
import xarray as xr

#: the style of the shaded (invalid) ranges
SHADE = dict(color="0.6", alpha=0.25, lw=0, zorder=0)


def invalid_spans(x: np.ndarray, valid: np.ndarray, log: bool = False) -> list[tuple[float, float]]:
    """The x-ranges covering the invalid points of a curve given in separation order:
    each run of invalid points, out to midway (geometric on a log axis) to its valid
    neighbours.  Points with a non-finite x (or x <= 0 on a log axis) are left out."""
    x = np.asarray(x, float)
    ok = np.isfinite(x) & (x > 0 if log else True)
    x, bad = x[ok], ~np.asarray(valid, bool)[ok]
    if not bad.any():
        return []
    t = np.log(x) if log else x
    mid = 0.5 * (t[1:] + t[:-1])
    edges = np.flatnonzero(np.diff(np.concatenate([[0], bad.astype(int), [0]])))
    spans = []
    for a, b in zip(edges[::2], edges[1::2]):  # runs [a, b) of invalid points (a few per curve)
        lo = t[a] if a == 0 else mid[a - 1]
        hi = t[b - 1] if b == t.size else mid[b - 1]
        lo, hi = sorted((lo, hi))
        spans.append((float(np.exp(lo)), float(np.exp(hi))) if log else (float(lo), float(hi)))
    return spans


def shade_invalid(axes, xs, ds: xr.Dataset) -> None:
    """Shade on each of `axes` the x-ranges (its values `xs`, one array per axis)
    where `ds` (one branch, with ``valid`` and ``validity``) is invalid; the first
    axis's legend names the first reason.  Nothing without ``valid``."""
    if "valid" not in ds:
        return
    valid = ds["valid"].values.astype(bool)
    if valid.all():
        return
    reason = str(ds["validity"].values[np.flatnonzero(~valid)[0]])
    for i, (ax, x) in enumerate(zip(axes, xs)):
        for j, (lo, hi) in enumerate(invalid_spans(x, valid, ax.get_xscale() == "log")):
            label = f"outside validity, e.g. {reason}" if i == 0 and j == 0 else None
            ax.axvspan(lo, hi, label=label, **SHADE)
