"""Force laws of single asperities as the interacting route couples them.

A law is ``law(w, index)`` -> (force, contact area, dF/dw, dA/dw) of the asperities
`index` at interferences `w` (arrays, broadcast; all zero at w <= 0): the Hertz sphere
of each peak's curvature (report 6.1; `hertz_law`), or responses tabulated on one
interference grid, e.g. the scene's finite element asperities (`tabulated_law`), or a
shape's law with a finite element sphere's departure from Hertz (`departure_law`).
`asperity.homogenize.interacting` solves their equilibrium on the map's period;
`asperity.stages.routes.asperity_law` picks the law a scene names.
"""

from __future__ import annotations

import numpy as np

__all__ = ["hertz_law", "tabulated_law", "departure_law"]


def hertz_law(contact_modulus: float, curvatures):
    """The Hertz force law of the peaks of curvatures kappa_i = 1/R_i (report 6.1) as
    ``law(w, index)`` -> (force F = 4/3 E* R^1/2 w^3/2, area A = pi R w,
    dF/dw = 2 E* (R w)^1/2, dA/dw = pi R) of the peaks `index`, all zero at w <= 0."""
    estar = float(contact_modulus)
    kappa = np.asarray(curvatures, dtype=float)

    def law(w, index):
        w = np.asarray(w, dtype=float)
        radius = 1.0 / kappa[index]
        wp = np.maximum(w, 0.0)
        a = np.sqrt(radius * wp)
        return (4.0 / 3.0 * estar * a * wp, np.pi * a * a, 2.0 * estar * a,
                np.where(w > 0, np.pi * radius, 0.0))

    return law


def tabulated_law(interference: np.ndarray, force: np.ndarray, area: np.ndarray):
    """``law(w, index)`` -> (F, A, dF/dw, dA/dw) of asperities whose responses are tabulated
    on one interference grid (m, increasing, from 0; rows of `force` (N) and `area` (m^2)
    per asperity), e.g. finite element asperities: linear between the grid's points (the
    slopes those of the segments), as w^3/2 and w below its first positive point (a
    contact that starts smoothly, as Hertz's), and continued in a straight line past its
    last."""
    grid = np.asarray(interference, dtype=float)
    force, area = np.asarray(force, dtype=float), np.asarray(area, dtype=float)
    if grid[0] != 0.0 or np.any(np.diff(grid) <= 0):
        raise ValueError("the interference grid must increase from 0")
    first = grid[1]
    slope_f = np.diff(force, axis=1) / np.diff(grid)
    slope_a = np.diff(area, axis=1) / np.diff(grid)

    def law(w, index):
        w = np.asarray(w, dtype=float)
        index = np.asarray(index, dtype=int)
        wp = np.maximum(w, 0.0)
        j = np.clip(np.searchsorted(grid, wp, side="right") - 1, 1, grid.size - 2)
        dw = wp - grid[j]
        f = force[index, j] + slope_f[index, j] * dw
        a = area[index, j] + slope_a[index, j] * dw
        df, da = slope_f[index, j], slope_a[index, j]
        tip = wp < first
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(tip, wp / first, 1.0)
            f = np.where(tip, force[index, 1] * s ** 1.5, f)
            df = np.where(tip, 1.5 * force[index, 1] * np.sqrt(s) / first, df)
            a = np.where(tip, area[index, 1] * s, a)
            da = np.where(tip, area[index, 1] / first, da)
        touching = w > 0
        return tuple(np.where(touching, v, 0.0) for v in (f, a, df, da))

    return law


def departure_law(base, model, sphere, reach):
    """``law(w, index)`` of asperities whose shape `base` describes, with the departure of
    `model` from `sphere` (two laws of the same spherical tip, e.g. finite element and
    Hertz): force F = F_base F_model / F_sphere and area A = A_base A_model / A_sphere,
    their slopes by the product and quotient rules. Past each asperity's `reach` (m;
    the largest interference `model` was computed to) the two ratios keep their values
    there. A `model` equal to `sphere` gives `base` itself."""
    reach = np.asarray(reach, dtype=float)

    def ratio(value, slope, ref, ref_slope, held):
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(ref > 0, value / np.where(ref > 0, ref, 1.0), 1.0)
            dr = np.where((ref > 0) & ~held, (slope * ref - value * ref_slope)
                          / np.where(ref > 0, ref, 1.0) ** 2, 0.0)
        return r, dr

    def law(w, index):
        w = np.asarray(w, dtype=float)
        index = np.asarray(index, dtype=int)
        held = w > reach[index]
        wm = np.minimum(w, reach[index])
        fb, ab, dfb, dab = base(w, index)
        fm, am, dfm, dam = model(wm, index)
        fs, as_, dfs, das = sphere(wm, index)
        rf, drf = ratio(fm, dfm, fs, dfs, held)
        ra, dra = ratio(am, dam, as_, das, held)
        return fb * rf, ab * ra, dfb * rf + fb * drf, dab * ra + ab * dra

    return law
