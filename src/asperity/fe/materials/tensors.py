"""Tensor components of the material laws: the Mandel form, and helpers that are safe
under complex-step differentiation.

Strains and stresses are ``(4, *shape)`` with components (11, 22, 33, 12) (the
axisymmetric and plane-strain bodies), or ``(6, *shape)`` with (11, 22, 33, 12,
13, 23) (three-dimensional bodies), tensor shear components; tangents are
``(n, n, *shape)`` (`asperity.fe.materials.elastic`).  In Mandel form the shear
components are multiplied by sqrt 2,

    x_M = W x,   W = diag(1, 1, 1, sqrt 2[, sqrt 2, sqrt 2]),

so that the contraction x : y is the dot product x_M . y_M and the tensor norm
the Euclidean one; a tangent d sigma / d eps is D = W^-1 D_M W in tensor
components (`to_mandel`, `from_mandel`, `tangent_from_mandel`).

The helpers used inside the complex-step derivatives of the Bodner-Partom update
(`mandel_dot`, `largest_principal6`, `signed_power`, `where_positive`) are
analytic in their argument: no complex conjugation, branches chosen on real
parts, so that Im f(x + i h) / h is f'(x) to rounding (W. Squire and G. Trapp,
Using complex variables to estimate derivatives of real functions, SIAM Rev. 40
(1998) 110).  The largest principal stress is the trigonometric solution of the
characteristic cubic (O. K. Smith, Eigenvalues of a symmetric 3 x 3 matrix,
Commun. ACM 4 (1961) 168).
"""

from __future__ import annotations

import math

import numpy as np

SQRT2 = math.sqrt(2.0)
SQRT3 = math.sqrt(3.0)
#: tensor components -> Mandel components
MANDEL = np.array([1.0, 1.0, 1.0, SQRT2])
#: the identity in 4 components
IDENTITY = np.array([1.0, 1.0, 1.0, 0.0])
#: the same for the 6 components (11, 22, 33, 12, 13, 23) of a 3-D body
MANDEL6 = np.array([1.0, 1.0, 1.0, SQRT2, SQRT2, SQRT2])
IDENTITY6 = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
_I = IDENTITY[:, None]
_I6 = IDENTITY6[:, None]
#: the supported numbers of components
COMPONENTS = (4, 6)


def component_count(x) -> int:
    """The number of tensor components (4 or 6) on the first axis of x; ValueError
    if it is neither."""
    n = int(np.shape(x)[0])
    if n not in COMPONENTS:
        raise ValueError("strain/stress arrays have 4 or 6 components on their first axis, "
                         f"got {n}")
    return n


def _mandel_of(n: int) -> np.ndarray:
    return MANDEL if n == 4 else MANDEL6


def identity_of(n: int) -> np.ndarray:
    """The identity tensor in `n` (4 or 6) components."""
    return IDENTITY if n == 4 else IDENTITY6


def identity_like(x) -> np.ndarray:
    """The identity (n, 1) matching the component count of x (n, N)."""
    return _I if np.shape(x)[0] == 4 else _I6


def to_mandel(x: np.ndarray) -> np.ndarray:
    """Tensor components (4 or 6, ...) -> Mandel components (shear times sqrt 2)."""
    x = np.asarray(x)
    n = component_count(x)
    return x * _mandel_of(n).reshape((n,) + (1,) * (x.ndim - 1))


def from_mandel(x: np.ndarray) -> np.ndarray:
    """Mandel components (4 or 6, ...) -> tensor components (shear over sqrt 2)."""
    x = np.asarray(x)
    n = component_count(x)
    return x / _mandel_of(n).reshape((n,) + (1,) * (x.ndim - 1))


def tangent_from_mandel(D: np.ndarray) -> np.ndarray:
    """Mandel d sigma / d eps (n, n, ...) -> tensor-component tangent (n = 4 or 6)."""
    n = component_count(D)
    m = _mandel_of(n)
    s = (1.0 / m)[:, None] * m[None, :]
    return D * s.reshape((n, n) + (1,) * (D.ndim - 2))


def mandel_dot(a, b):
    """Contraction of Mandel vectors (n, N) without conjugation (complex-step safe)."""
    if len(a) == 4:
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]


def largest_principal6(sig):
    """Largest principal value of Mandel stresses (6, N), complex-step safe.

    The trigonometric solution of the characteristic cubic: with
    m = tr/3, p = sqrt(|dev|^2 / 6), r = det(dev / p) / 2 (clipped to
    [-1, 1]), sigma_1 = m + 2 p cos(arccos(r) / 3); sigma_1 = m where the
    deviator vanishes.
    """
    a, b, c = sig[0], sig[1], sig[2]
    t12, t13, t23 = sig[3] / SQRT2, sig[4] / SQRT2, sig[5] / SQRT2
    m = (a + b + c) / 3.0
    da, db, dc = a - m, b - m, c - m
    p2 = (da * da + db * db + dc * dc + 2.0 * (t12 * t12 + t13 * t13 + t23 * t23)) / 6.0
    ok = np.real(p2) > 1e-30 * (np.real(m) ** 2 + 1e-300)
    p = np.sqrt(np.where(ok, p2, 1.0))
    det = (da * (db * dc - t23 * t23) - t12 * (t12 * dc - t23 * t13)
           + t13 * (t12 * t23 - db * t13))
    r = det / (2.0 * p**3)
    r = np.where(np.real(r) >= 1.0, 1.0 - 1e-15, np.where(np.real(r) <= -1.0, -1.0 + 1e-15, r))
    phi = np.arccos(r) / 3.0
    return np.where(ok, m + 2.0 * p * np.cos(phi), m)


def signed_power(x, r):
    """sign(x) |x|^r, analytic for complex-step on either side of 0."""
    s = np.sign(np.real(x))
    return s * (s * x) ** r


def where_positive(x, fn, default=0.0):
    """fn(x) where Re x > 0 else default, without evaluating fn at Re x <= 0."""
    pos = np.real(x) > 0
    safe = np.where(pos, x, 1.0)
    return np.where(pos, fn(safe), default)
