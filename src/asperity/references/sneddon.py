"""An elastic body of any axisymmetric profile pressed by a rigid flat (Sneddon 1965).

A measured summit is not a paraboloid: below its tip it widens as its own map
says.  Its profile f(r) (the depth below the tip at radius r, f(0) = 0,
non-decreasing) gives the frictionless contact of radius a exactly (Sneddon,
Int. J. Eng. Sci. 3 (1965) 47; Johnson, *Contact Mechanics*, 1985, 5.6)::

    w(a) = a   int_0^{pi/2} f'(a sin t) dt,
    F(a) = 2 E* a^2 int_0^{pi/2} f'(a sin t) sin^2 t dt,
    dF/dw = 2 E* a,

with E* = E / (1 - nu^2) and the flat rigid.  For the paraboloid f = r^2 / (2R)
this is Hertz: w = a^2 / R, F = 4 E* a^3 / (3 R).  Beyond the largest radius of
the profile's table the contact stops growing: the summit is a flat punch of that
radius, F grows by 2 E* a_max per unit of w.

:func:`profile_law` tabulates w, F and a against a on a common radial grid for
many profiles at once (Gauss-Legendre in t), and returns the law
``law(w, index) -> (F, A, dF/dw, dA/dw)`` that
`asperity.homogenize.interacting` takes.
"""

from __future__ import annotations

import numpy as np

__all__ = ["profile_tables", "profile_law"]

#: Gauss-Legendre nodes of the integrals over t in (0, pi/2)
NODES = 48


def profile_tables(radii: np.ndarray, slopes: np.ndarray, contact_modulus: float
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """w, F (both (n, m)) and a (m,) at the contact radii a = `radii` (m, increasing from
    0, uniform) of the n profiles whose slopes f'(r) (>= 0) are `slopes` (n, m) on that
    grid, linear between its points (module text)."""
    r = np.asarray(radii, dtype=float)
    fp = np.maximum(np.asarray(slopes, dtype=float), 0.0)
    t, weight = np.polynomial.legendre.leggauss(NODES)
    t = (t + 1.0) * np.pi / 4.0
    weight = weight * np.pi / 4.0
    step = r[1] - r[0]
    x = r[:, None] * np.sin(t)[None, :] / step  # (m, nodes), in grid steps
    i = np.minimum(np.floor(x).astype(int), r.size - 2)
    frac = x - i
    slope = fp[:, i] * (1.0 - frac) + fp[:, i + 1] * frac  # (n, m, nodes)
    w = r[None, :] * (slope @ weight)
    force = 2.0 * contact_modulus * r[None, :] ** 2 * (slope @ (weight * np.sin(t) ** 2))
    return w, force, r


def profile_law(radii: np.ndarray, slopes: np.ndarray, contact_modulus: float):
    """``law(w, index) -> (F, A, dF/dw, dA/dw)`` of the profiles (rows of `slopes` on the
    grid `radii`, as `profile_tables`), for `asperity.homogenize.interacting`.

    a(w) is each profile's table w(a) inverted, linear between its points; the force is
    the integral of dF/dw = 2 E* a(w), so that F is continuously differentiable (Newton's
    iterations see no kink) and equals Sneddon's to the table's resolution.  Within the
    first radius of the table the tip is its paraboloid (a ~ w^1/2, F ~ w^3/2: no kink at
    w = 0); past the table a flat punch (a constant).  A = pi a^2; all zero at w <= 0."""
    w_tab, _, a_tab = profile_tables(radii, slopes, contact_modulus)
    w_tab = np.maximum.accumulate(w_tab, axis=1)
    n, m = w_tab.shape
    estar = float(contact_modulus)
    # F at the nodes: the tip's 4/3 E* a1 w1 at the first, then the integral of 2 E* a(w)
    # with a linear between nodes (the trapezoid is exact for it)
    pieces = estar * (a_tab[None, 1:-1] + a_tab[None, 2:]) * np.diff(w_tab[:, 1:], axis=1)
    f_nodes = np.zeros((n, m))
    f_nodes[:, 1] = 4.0 / 3.0 * estar * a_tab[1] * w_tab[:, 1]
    f_nodes[:, 2:] = f_nodes[:, [1]] + np.cumsum(pieces, axis=1)
    span = float(w_tab[:, -1].max()) * 2.0 + 1.0
    keys = (w_tab + span * np.arange(n)[:, None]).ravel()  # rows side by side, sorted

    def law(w, index):
        w = np.asarray(w, dtype=float)
        index = np.asarray(index, dtype=int)
        wp = np.maximum(w, 0.0)
        last = w_tab[index, -1]
        k = np.searchsorted(keys, np.minimum(wp, last) + span * index, side="right") - 1
        j = np.clip(k - index * m, 1, m - 2)
        w0, w1 = w_tab[index, j], w_tab[index, j + 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.where(w1 > w0, (a_tab[j + 1] - a_tab[j]) / (w1 - w0), 0.0)
        dw = np.minimum(wp, last) - w0
        a = a_tab[j] + slope * dw
        force = f_nodes[index, j] + 2.0 * estar * (a_tab[j] * dw + 0.5 * slope * dw * dw)
        beyond = wp > last  # a flat punch of the table's largest radius
        force = np.where(beyond, f_nodes[index, -1] + 2.0 * estar * a_tab[-1] * (wp - last), force)
        a = np.where(beyond, a_tab[-1], a)
        da_dw = np.where(beyond, 0.0, slope)
        w_first = w_tab[index, 1]
        tip = wp < w_first
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(tip, wp / w_first, 1.0)
            a = np.where(tip, a_tab[1] * np.sqrt(s), a)
            da_dw = np.where(tip, 0.5 * a_tab[1] / np.sqrt(np.where(tip, wp * w_first, 1.0)), da_dw)
        force = np.where(tip, f_nodes[index, 1] * s ** 1.5, force)
        touching = w > 0
        a = np.where(touching, a, 0.0)
        with np.errstate(invalid="ignore"):
            darea = np.where(touching, 2.0 * np.pi * a * da_dw, 0.0)
        return (np.where(touching, force, 0.0), np.pi * a * a, 2.0 * estar * a, darea)

    return law
