"""Form removal: the least-squares polynomial a measured surface is tilted and bent by.

A measurement carries the tilt of the specimen on the stage and the form of
the part (a cylinder, a ball, a bent sheet); on real files these dwarf the
roughness, and statistics of heights that still carry them describe the
mounting, not the surface (report 2.3.1 assumes a stationary random profile
about its mean line).  The F-operator of ISO 16610 removes the least-squares
polynomial in position before any filter:

* ``none``: nothing (a synthetic or already levelled record);
* ``mean``: the mean height (degree 0);
* ``tilt``: the least-squares line (profile) or plane (map), degree 1;
* ``polynomial``: all terms x^a y^b with a + b <= degree.

The fit uses defined points only.  The basis is Legendre polynomials of the
positions scaled to [-1, 1] (well conditioned at any degree used here); the
normal equations of a map are assembled from products of the one-dimensional
bases with the defined mask (two matrix products, no loop over points).
"""

from __future__ import annotations

import numpy as np

__all__ = ["FORMS", "form_degree", "fit_form", "remove_form"]

FORMS = ("none", "mean", "tilt", "polynomial")


def form_degree(kind: str, degree: int | None = None) -> int | None:
    """The polynomial degree of a form kind (None for ``none``)."""
    if kind not in FORMS:
        raise ValueError(f"form must be one of {FORMS}; got {kind!r}")
    if kind == "none":
        return None
    if kind == "polynomial":
        if degree is None or isinstance(degree, bool) or int(degree) != degree or degree < 0:
            raise ValueError(f"form polynomial needs a degree (an integer >= 0); got {degree!r}")
        return int(degree)
    return {"mean": 0, "tilt": 1}[kind]


def _basis(n: int, degree: int) -> np.ndarray:
    u = np.linspace(-1.0, 1.0, n) if n > 1 else np.zeros(1)
    return np.polynomial.legendre.legvander(u, degree)


def fit_form(z, degree: int, defined=None) -> np.ndarray:
    """The least-squares polynomial of total ``degree`` through the defined heights.

    ``z`` is a profile (1-D) or a map (2-D, ``z[i, j] = z(x = j dx, y = i
    dy)``; the fit does not depend on the spacings).  Returns the form at
    every point, defined or not.
    """
    zz = np.asarray(z, dtype=np.float64)
    if zz.ndim not in (1, 2):
        raise ValueError(f"form removal needs a profile or a map; got shape {zz.shape}")
    grid = zz.reshape(1, -1) if zz.ndim == 1 else zz
    mask = np.ones(grid.shape, dtype=bool) if defined is None else np.asarray(defined, bool).reshape(grid.shape)
    ny, nx = grid.shape
    dx_degree = degree if nx > 1 else 0
    dy_degree = degree if ny > 1 else 0
    px, py = _basis(nx, dx_degree), _basis(ny, dy_degree)
    kx, ky = px.shape[1], py.shape[1]
    terms = [(a, b) for b in range(ky) for a in range(kx) if a + b <= degree]
    w = mask.astype(np.float64)
    values = np.where(mask, grid, 0.0)
    # G[(a,b),(c,e)] = sum_ij w_ij Px_a(j) Px_c(j) Py_b(i) Py_e(i), assembled as two products
    pxx = (px[:, :, None] * px[:, None, :]).reshape(nx, kx * kx)
    pyy = (py[:, :, None] * py[:, None, :]).reshape(ny, ky * ky)
    g4 = (pyy.T @ (w @ pxx)).reshape(ky, ky, kx, kx)
    rhs4 = py.T @ values @ px  # (ky, kx): sum_ij w z Py_b(i) Px_a(j)
    a_idx = np.array([a for a, _ in terms])
    b_idx = np.array([b for _, b in terms])
    gram = g4[b_idx[:, None], b_idx[None, :], a_idx[:, None], a_idx[None, :]]
    rhs = rhs4[b_idx, a_idx]
    coef = np.linalg.lstsq(gram, rhs, rcond=None)[0]
    c = np.zeros((ky, kx))
    c[b_idx, a_idx] = coef
    return (py @ c @ px.T).reshape(zz.shape)


def remove_form(z, kind: str = "tilt", degree: int | None = None, defined=None
                ) -> tuple[np.ndarray, np.ndarray]:
    """Heights less their form, and the form (see the module text for the kinds).

    Returns ``(residual, form)``, both of the shape of ``z``; undefined
    points keep whatever ``z`` holds there (NaN) in ``residual``.
    """
    zz = np.asarray(z, dtype=np.float64)
    d = form_degree(kind, degree)
    if d is None:
        return zz.copy(), np.zeros_like(zz)
    form = fit_form(zz, d, defined)
    return zz - form, form
