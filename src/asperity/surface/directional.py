"""Spectral moments of an anisotropic surface from profiles in several directions (report 2.3.2).

A profile along the direction theta of a surface whose heights are the series of
eq. (2.3) has, by eq. (2.4), the moments m0(theta) = m00, m2(theta) (a quadratic
form in cos theta, sin theta of m20, m11, m02) and m4(theta) (a quartic form of
m40, m31, m22, m13, m04).

* :func:`directional_moments` -- the nine spectral moments m_pq of eq. (2.2)
  from the profile moments m0, m2, m4 (e.g. of
  :func:`asperity.surface.statistics.profile_statistics`) in three or more
  distinct directions (five for the fourth-order moments), by least squares;
* :func:`moment_invariants` -- their seven rotation invariants;
* ``MOMENT_UNITS``, ``INVARIANT_UNITS``, ``INVARIANT_TEXT``, ``FOURTH_ORDER``
  -- the units and formulas the datasets of this module and of
  :mod:`asperity.surface.maps` attach to these numbers.

Conventions as in :mod:`asperity.surface.statistics`: SI metres, angular
wavenumbers (rad/m), directions in radians from the x axis.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from asperity.surface.missing import defined_heights

__all__ = [
    "directional_moments",
    "moment_invariants",
]


def _finite_array(z, ndim: int, what: str) -> np.ndarray:
    return defined_heights(z, None, ndim, what)[0]


MOMENT_UNITS = {
    "m00": "m^2",
    "m20": "1",
    "m11": "1",
    "m02": "1",
    "m40": "1/m^2",
    "m31": "1/m^2",
    "m22": "1/m^2",
    "m13": "1/m^2",
    "m04": "1/m^2",
}
INVARIANT_UNITS = {1: "m^2", 2: "1", 3: "1", 4: "1/m^2", 5: "1/m^4", 6: "1/m^4", 7: "1/m^6"}
INVARIANT_TEXT = {
    1: "m00",
    2: "m20 + m02",
    3: "m20 m02 - m11^2",
    4: "m40 + 2 m22 + m04",
    5: "m40 m04 - 4 m13 m31 + 3 m22^2",
    6: "(m40 + m22)(m22 + m04) - (m31 + m13)^2",
    7: "det [[m40, m31, m22], [m31, m22, m13], [m22, m13, m04]]",
}
FOURTH_ORDER = ("m40", "m31", "m22", "m13", "m04")


def moment_invariants(m00, m20, m11, m02, m40=None, m31=None, m22=None, m13=None, m04=None) -> dict[int, float]:
    """The seven rotation invariants of the spectral moments (report 2.3.2).

    1. m00;  2. m20 + m02;  3. m20 m02 - m11^2;  4. m40 + 2 m22 + m04;
    5. m40 m04 - 4 m13 m31 + 3 m22^2;  6. (m40 + m22)(m22 + m04) - (m31 + m13)^2;
    7. m40 (m22 m04 - m13^2) - m31 (m31 m04 - m13 m22) + m22 (m31 m13 - m22^2).

    Returns a dict {number: value}; 4-7 only when all fourth-order moments
    are given (``None`` means not determined).
    """
    inv = {1: m00, 2: m20 + m02, 3: m20 * m02 - m11 * m11}
    if None not in (m40, m31, m22, m13, m04):
        inv[4] = m40 + 2.0 * m22 + m04
        inv[5] = m40 * m04 - 4.0 * m13 * m31 + 3.0 * m22 * m22
        inv[6] = (m40 + m22) * (m22 + m04) - (m31 + m13) ** 2
        inv[7] = m40 * (m22 * m04 - m13 * m13) - m31 * (m31 * m04 - m13 * m22) + m22 * (m31 * m13 - m22 * m22)
    return {key: float(val) for key, val in inv.items()}


def _distinct_directions(theta: np.ndarray, tol: float = 1e-9) -> int:
    t = np.sort(np.mod(theta, np.pi))
    gaps = np.diff(np.append(t, t[0] + np.pi))
    gaps = np.minimum(gaps, np.pi - gaps)  # directions near 0 and near pi are close
    return max(1, int(np.count_nonzero(gaps > tol)))


def directional_moments(theta, m0, m2, m4) -> xr.Dataset:
    """Spectral moments m_pq of an anisotropic surface from profiles in several directions (2.3.2).

    A profile along the unit vector (c, s) = (cos theta, sin theta) of the
    surface (2.3) has wavenumbers k_x c + k_y s, so by eq. (2.4) its moments are

        m0(theta) = m00,
        m2(theta) = m20 c^2 + 2 m11 c s + m02 s^2,
        m4(theta) = m40 c^4 + 4 m31 c^3 s + 6 m22 c^2 s^2 + 4 m13 c s^3 + m04 s^4.

    These linear systems are solved for the moments, by least squares when
    there are more profiles than unknowns.  Directions differing by pi are
    the same direction.

    Parameters
    ----------
    theta : array_like
        Direction of each profile, radians from the x axis.
    m0, m2, m4 : array_like
        Each profile's moments (e.g. from :func:`profile_statistics`).

    Returns
    -------
    xarray.Dataset
        Scalars m00 (mean of m0), m20, m11, m02 (>= 3 distinct directions
        needed), m40, m31, m22, m13, m04 (only with >= 5 distinct directions;
        otherwise the attribute ``fourth_order_moments`` says so), and
        invariant_1 .. invariant_7 (:func:`moment_invariants`) as far as
        computable.  With fewer than five directions invariant_4 is still
        given when the profiles determine it (e.g. three equally spaced
        directions: it is then 8/3 of the mean of m4).  Attributes give the
        condition numbers of the systems and the rms residuals.
    """
    th = _finite_array(theta, 1, "theta")
    a0 = _finite_array(m0, 1, "m0")
    a2 = _finite_array(m2, 1, "m2")
    a4 = _finite_array(m4, 1, "m4")
    if not (th.size == a0.size == a2.size == a4.size):
        raise ValueError(
            "theta, m0, m2, m4 must have one value per profile; got lengths "
            f"{th.size}, {a0.size}, {a2.size}, {a4.size}"
        )
    if th.size == 0:
        raise ValueError("directional_moments needs profiles in at least 3 distinct directions; got none")
    nd = _distinct_directions(th)
    if nd < 3:
        raise ValueError(
            f"directional_moments needs profiles in at least 3 distinct directions "
            f"(directions differing by pi are the same); got {nd}"
        )
    c, s = np.cos(th), np.sin(th)
    A2 = np.column_stack([c * c, 2.0 * c * s, s * s])
    A4 = np.column_stack([c**4, 4.0 * c**3 * s, 6.0 * c * c * s * s, 4.0 * c * s**3, s**4])

    def rms(A, x, y):
        return float(np.sqrt(np.mean((A @ x - y) ** 2)))

    x2 = np.linalg.lstsq(A2, a2, rcond=None)[0]
    mom = {"m00": float(a0.mean()), "m20": float(x2[0]), "m11": float(x2[1]), "m02": float(x2[2])}
    attrs = {
        "title": "spectral moments of an anisotropic surface from directional profiles (report 2.3.2)",
        "directions": nd,
        "profiles": int(th.size),
        "m0_spread": float(a0.max() - a0.min()),
        "condition_number_m2": float(np.linalg.cond(A2)),
        "residual_rms_m2": rms(A2, x2, a2),
    }
    if nd >= 5:
        x4 = np.linalg.lstsq(A4, a4, rcond=None)[0]
        mom.update(zip(FOURTH_ORDER, map(float, x4)))
        attrs["fourth_order_moments"] = f"determined from {nd} directions"
        attrs["condition_number_m4"] = float(np.linalg.cond(A4))
        attrs["residual_rms_m4"] = rms(A4, x4, a4)
        inv = moment_invariants(**mom)
    else:
        attrs["fourth_order_moments"] = f"not determined: {nd} directions given, 5 needed"
        inv = moment_invariants(**mom)
        # invariant 4 is the linear functional v.(m40..m04), v = (1, 0, 2, 0, 1);
        # it is determined when v lies in the row space of A4: v = A4^T y.
        v = np.array([1.0, 0.0, 2.0, 0.0, 1.0])
        y = np.linalg.lstsq(A4.T, v, rcond=None)[0]
        if np.linalg.norm(A4.T @ y - v) <= 1e-10 * np.linalg.norm(v):
            inv[4] = float(y @ a4)
    data_vars = {}
    for name, val in mom.items():
        p, q = int(name[1]), int(name[2])
        data_vars[name] = (
            (),
            val,
            {"units": MOMENT_UNITS[name], "long_name": f"spectral moment m_{p}{q} of the surface, eq. (2.2)"},
        )
    for key, val in inv.items():
        data_vars[f"invariant_{key}"] = (
            (),
            val,
            {"units": INVARIANT_UNITS[key], "long_name": f"moment invariant {key}: {INVARIANT_TEXT[key]}"},
        )
    return xr.Dataset(data_vars, attrs=attrs)
