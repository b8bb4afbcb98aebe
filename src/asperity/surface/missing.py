"""Undefined points of a measured profile or map (the inputs of report 2.3 and 2.4.3).

Optical instruments do not measure every pixel (steep flanks, dark spots,
reflections); their files mark those points undefined.  The statistics never
invent heights there: a derivative or a peak is taken only where its whole
stencil is defined, and densities are per defined length or area.  Where a
complete record is needed (the periodogram of a map), or where the scene asks
for it, the undefined points are filled with the harmonic function that
takes the defined heights around them as boundary values
(:func:`harmonic_fill`, as SurfaceTopography's
``interpolate_undefined_data("harmonic")`` does).

Instruments also leave defined points where they are not to be trusted: specks
standing alone in an undefined area (a stray reflection) or a line of a fixed
value next to undefined ones (``frt-1.frt``'s first row: 500 zeros).  They
carry no slope or peak (no stencil about them is defined) but their heights
enter the form fit, the height distribution and the in-fill.  :func:`islands`
finds them: the edge-connected regions of defined points that hold no
interior point.

A ``defined`` mask is a boolean array of the heights' shape, True where the
height was measured.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "defined_heights",
    "undefined_share",
    "runs",
    "longest_run",
    "complete_neighbourhood",
    "islands",
    "harmonic_fill",
]


def defined_heights(z, defined, ndim: int, what: str) -> tuple[np.ndarray, np.ndarray]:
    """Heights as float64 with NaN at undefined points, and the defined mask.

    ``defined=None`` means every point is defined: then every height must be
    finite (an error names the first that is not).  Otherwise heights at
    defined points must be finite and the others are ignored.
    """
    try:
        a = np.array(z, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{what} must be numeric heights: {exc}") from None
    if a.ndim != ndim:
        need = "1-D array of heights" if ndim == 1 else "2-D array z[y, x] of heights"
        raise ValueError(f"{what} must be a {need}; got an array of shape {a.shape}")
    if defined is None:
        mask = np.ones(a.shape, dtype=bool)
    else:
        mask = np.asarray(defined, dtype=bool)
        if mask.shape != a.shape:
            raise ValueError(f"defined mask of shape {mask.shape} does not match the {what}'s {a.shape}")
    bad = mask & ~np.isfinite(a)
    if bad.any():
        idx = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), a.shape)
        where = f"index {idx[0]}" if ndim == 1 else f"(row {idx[0]}, column {idx[1]})"
        raise ValueError(
            f"{what} has a non-finite value ({a[idx]}) at {where}; "
            "all heights must be finite numbers (fill or crop the gaps first, or mark them undefined)"
        )
    if defined is not None and not mask.any():
        raise ValueError(f"every point of the {what} is undefined: there is nothing to measure")
    if defined is not None:
        a[~mask] = np.nan
    return a, mask


def undefined_share(defined: np.ndarray) -> float:
    """Share of undefined points, 0 ... 1."""
    return 1.0 - float(np.count_nonzero(defined)) / max(1, defined.size)


def runs(defined: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and stop (exclusive) indices of the runs of consecutive defined points of a profile."""
    d = np.concatenate(([False], np.asarray(defined, dtype=bool), [False])).astype(np.int8)
    edges = np.diff(d)
    return np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)


def longest_run(defined: np.ndarray) -> slice:
    """The longest run of consecutive defined points of a profile (the first if tied)."""
    start, stop = runs(defined)
    if start.size == 0:
        raise ValueError("the profile has no defined point")
    i = int(np.argmax(stop - start))
    return slice(int(start[i]), int(stop[i]))


def _erode(d: np.ndarray) -> np.ndarray:
    """True where the 3 x 3 square about a point is inside the map and all True (separable)."""
    rows = np.zeros(d.shape, dtype=bool)
    rows[:, 1:-1] = d[:, :-2] & d[:, 1:-1] & d[:, 2:]
    out = np.zeros(d.shape, dtype=bool)
    out[1:-1, :] = rows[:-2, :] & rows[1:-1, :] & rows[2:, :]
    return out


def complete_neighbourhood(defined: np.ndarray, half_width: int) -> np.ndarray:
    """True where the square of (2 half_width + 1)^2 points centred on a point is inside
    the map and wholly defined: the defined mask eroded half_width times by a 3 x 3 square
    (a (2q+1)-square is defined when the (2q-1)-squares about its 3 x 3 centre are)."""
    out = np.asarray(defined, dtype=bool)
    for _ in range(int(half_width)):  # a few erosions, each vectorized over the map
        out = _erode(out)
    return out


def islands(defined: np.ndarray) -> np.ndarray:
    """True at the defined points of the regions of defined points that hold no
    interior point: no point whose neighbours (on a map the 3 x 3 square about it,
    on a profile the points either side) are all defined and inside the record.

    Regions are edge-connected on a map (four neighbours; points that touch only
    at a corner are apart) and runs of consecutive points on a profile.  A region
    without an interior point is a speck, a pair of points or a line one point
    wide: nothing in it has a defined stencil (a slope, a curvature, a peak), and
    on an optical map it is what the instrument left inside an area it could not
    measure.  A region with one interior point is kept whole (its edge points
    too), so the measured surface loses nothing but such islands.
    """
    from scipy import ndimage

    d = np.asarray(defined, dtype=bool)
    if d.ndim == 1:
        interior = np.zeros(d.shape, dtype=bool)
        interior[1:-1] = d[:-2] & d[1:-1] & d[2:]
    elif d.ndim == 2:
        interior = _erode(d)
    else:
        raise ValueError(f"a defined mask of a profile or map is 1-D or 2-D; got shape {d.shape}")
    labels, _ = ndimage.label(d)  # the default structure: edge-connected
    kept = np.unique(labels[interior])
    return d & ~np.isin(labels, kept)


def harmonic_fill(z, defined, periodic: bool = False) -> np.ndarray:
    """Heights with every undefined point replaced by a harmonic interpolant.

    The undefined heights solve the discrete Laplace equation
    sum_{n in N(p)} (h_n - h_p) = 0 at every undefined point p, N(p) its
    nearest neighbours (two along a profile, four on a map); defined points
    are Dirichlet values.  Off a non-periodic record's edge the neighbour is
    dropped (zero normal derivative).  This is the in-fill of
    SurfaceTopography's ``interpolate_undefined_data("harmonic")``; along a
    profile it is linear interpolation across each gap (constant beyond the
    first and last defined points).  One sparse system for all undefined
    points, solved directly.
    """
    import scipy.sparse
    import scipy.sparse.linalg

    h = np.array(z, dtype=np.float64)
    mask = ~np.asarray(defined, dtype=bool)
    if mask.shape != h.shape:
        raise ValueError(f"defined mask of shape {mask.shape} does not match the heights' {h.shape}")
    unknowns = int(mask.sum())
    if unknowns == 0:
        return h
    if unknowns == h.size:
        raise ValueError("every point is undefined: there is nothing to fill from")
    index = np.full(h.shape, -1, dtype=np.int64)
    index[mask] = np.arange(unknowns)
    values = np.where(mask, 0.0, h)
    diagonal = np.zeros(unknowns)
    rhs = np.zeros(unknowns)
    rows, cols = [], []
    for axis in range(h.ndim):  # the 2 (profile) or 4 (map) neighbour directions, not the points
        for shift in (1, -1):
            neighbour_index = np.roll(index, shift, axis)
            neighbour_undefined = np.roll(mask, shift, axis)
            neighbour_value = np.roll(values, shift, axis)
            leg = mask.copy()
            if not periodic:  # np.roll wraps: drop the legs that leave the record
                edge = [slice(None)] * h.ndim
                edge[axis] = 0 if shift == 1 else -1
                leg[tuple(edge)] = False
            np.subtract.at(diagonal, index[leg], 1.0)
            couple = leg & neighbour_undefined
            rows.append(index[couple])
            cols.append(neighbour_index[couple])
            known = leg & ~neighbour_undefined
            np.subtract.at(rhs, index[known], neighbour_value[known])
    rows.append(np.arange(unknowns))
    cols.append(np.arange(unknowns))
    data = np.concatenate([np.ones(sum(r.size for r in rows[:-1])), diagonal])
    laplace = scipy.sparse.csr_matrix((data, (np.concatenate(rows), np.concatenate(cols))),
                                      shape=(unknowns, unknowns))
    h[mask] = scipy.sparse.linalg.spsolve(laplace, rhs)
    if not np.all(np.isfinite(h[mask])):
        raise ValueError("harmonic in-fill failed: a region of undefined points touches no defined point")
    return h
