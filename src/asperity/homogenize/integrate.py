"""Expectation integrals over the asperity population (report 2.5, 2.6.2).

The expected value per asperity of a single-asperity quantity X (report
eq. (2.5))::

    E(X) = int_{-inf}^{inf} int_0^{inf} X(z, kappa) f_{z kappa}(z, kappa) dkappa dz

is evaluated, as in the report, on a truncated rectangle
[z_min, z_max] x [kappa_min, kappa_max] divided into cells, with a
quadrature rule in each cell (eq. (2.6))::

    E(X) = sum_cells sum_alpha X(z_alpha, kappa_alpha) f(z_alpha, kappa_alpha) w_alpha dz dkappa

and corrected by the numerical integral I of the density itself (eq. (2.7))::

    I = sum_cells sum_alpha f(z_alpha, kappa_alpha) w_alpha dz dkappa,   E^(X) = E(X) / I

so that a constant X is reproduced exactly.  The macroscopic value is
N_p E^(X) with N_p = n A_0 peaks in the nominal area A_0 (report 2.5.1).

Cell rules: ``"trapezoid"`` (nodes at the cell corners, 2 x 2 per cell) and
``"gauss"`` (2 Gauss points per direction, the report's four-point Gauss
rule).  For a :class:`~asperity.peaks.SampledDensity` the rule ``"peaks"``
averages X over the sampled peak list itself, which is the exact expectation
for the sampled surface (report 2.4.3, 2.5.3).

Everything is vectorized: quadrature nodes are tensor products broadcast
against a leading separation axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, NamedTuple

import numpy as np
import xarray as xr

from asperity.homogenize.table import (ResponseTable, check_interference, check_reach,
                                       interpolate_points, interpolate_tensor, response_table)
from asperity.peaks import FixedCurvatureDensity, JointDensity, SampledDensity

__all__ = [
    "RULES",
    "Quadrature",
    "Expectation",
    "quadrature_1d",
    "quadrature_nodes",
    "expectation",
    "interface_response",
]

RULES = ("trapezoid", "gauss")
_GAUSS = 0.5 / math.sqrt(3.0)  # Gauss points at cell centre +- h/(2 sqrt 3)

# Asperity variables with a named macroscopic counterpart: name, units, long_name
_MACRO = {
    "force": ("nominal_pressure", "Pa", "nominal contact pressure n E^(force) (eq. 2.7)"),
    "contact_area": ("contact_area_ratio", "1", "real contact area per unit nominal area n E^(contact_area)"),
    "stiffness": ("normal_stiffness", "Pa/m", "normal contact stiffness per unit nominal area n E^(stiffness)"),
}


def _reference_rule(cells: int, rule: str):
    """Composite rule on [0, 1]: nodes u and weights summing to one."""
    cells = int(cells)
    if cells < 1:
        raise ValueError(f"need at least one cell, got {cells}")
    if rule == "trapezoid":
        u = np.linspace(0.0, 1.0, cells + 1)
        w = np.full(cells + 1, 1.0 / cells)
        w[[0, -1]] *= 0.5
        return u, w
    if rule == "gauss":
        centres = (np.arange(cells) + 0.5) / cells
        u = (centres[:, None] + np.array([-_GAUSS, _GAUSS]) / cells).ravel()
        return u, np.full(2 * cells, 0.5 / cells)
    raise ValueError(f"unknown quadrature rule {rule!r}; known: {RULES}")


def quadrature_1d(lo, hi, cells: int, rule: str = "gauss"):
    """Composite cell rule on [lo, hi] (lo, hi may be arrays: a leading batch shape).

    Returns nodes x and weights w (weights include the cell lengths), both of
    shape ``broadcast(lo, hi).shape + (points,)``; points = cells + 1 for the
    trapezoid rule (shared corners merged), 2 cells for Gauss.
    """
    u, wu = _reference_rule(cells, rule)
    lo = np.asarray(lo, dtype=float)[..., None]
    length = np.asarray(hi, dtype=float)[..., None] - lo
    return lo + length * u, length * wu


class Quadrature(NamedTuple):
    """Tensor-product nodes of a rectangle: z (Pz, 1), kappa (1, Pk), weights (Pz, Pk)."""

    z: np.ndarray
    kappa: np.ndarray
    weights: np.ndarray


def quadrature_nodes(bounds, cells=(20, 20), rule: str = "trapezoid") -> Quadrature:
    """Nodes and weights of the cell rule (2.6) on [z_min, z_max] x [kappa_min, kappa_max].

    Parameters
    ----------
    bounds : (z_min, z_max, kappa_min, kappa_max)
    cells : (nz, nk)
        Cells per direction.
    rule : "trapezoid" or "gauss"
        Trapezoid: the 2 x 2 cell corners; Gauss: 2 x 2 Gauss points per cell
        (the report's four-point rule).

    Returns
    -------
    Quadrature(z, kappa, weights) with z of shape (Pz, 1), kappa (1, Pk) and
    weights (Pz, Pk) = w_alpha dz dkappa, summing to the rectangle's area.
    """
    z0, z1, k0, k1 = _check_bounds(bounds, 4)
    nz, nk = _cells2(cells)
    z, wz = quadrature_1d(z0, z1, nz, rule)
    k, wk = quadrature_1d(k0, k1, nk, rule)
    return Quadrature(z[:, None], k[None, :], wz[:, None] * wk[None, :])


def _check_bounds(bounds, n):
    b = tuple(float(v) for v in bounds)
    if n == 2 and len(b) == 4:  # fixed curvature: the curvature entries are not used
        b = b[:2]
    if len(b) != n:
        raise ValueError(f"bounds must have {n} numbers, got {bounds!r}")
    for lo, hi in zip(b[::2], b[1::2]):
        if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
            raise ValueError(f"bounds must be finite with max > min, got {bounds!r}")
    return b


def _cells2(cells):
    if np.ndim(cells) == 0:
        return int(cells), int(cells)
    c = tuple(int(v) for v in cells)
    if len(c) != 2:
        raise ValueError(f"cells must be (nz, nk), got {cells!r}")
    return c


def _cells1(cells):
    return int(cells) if np.ndim(cells) == 0 else int(tuple(cells)[0])


def _default_bounds(density):
    return density.support()


def _is_fixed(density) -> bool:
    return isinstance(density, FixedCurvatureDensity)


def _population(density, bounds, cells, rule):
    """Nodes (z, kappa), weights and density values of the population rule.

    Returns z, kappa broadcastable to a 2-D population shape P, weights and
    f of shape P.  Fixed curvature: P = (Pz, 1); peaks rule: P = (N, 1).
    """
    if rule == "peaks":
        if not isinstance(density, SampledDensity):
            raise ValueError('rule "peaks" needs a SampledDensity (a list of peaks)')
        n = density.count
        z = density.heights[:, None]
        k = density.curvatures[:, None]
        return z, k, np.full((n, 1), 1.0 / n), np.ones((n, 1))
    if bounds is None:
        bounds = _default_bounds(density)
    if _is_fixed(density):
        z0, z1 = _check_bounds(bounds, 2)
        z, wz = quadrature_1d(z0, z1, _cells1(cells), rule)
        return z[:, None], np.array([[density.curvature]]), wz[:, None], density.pdf(z)[:, None]
    q = quadrature_nodes(bounds, cells, rule)
    return q.z, q.kappa, q.weights, density.pdf(q.z, q.kappa)


@dataclass(frozen=True)
class Expectation:
    """Result of :func:`expectation` (report 2.5, Fig. 2.13).

    integral      raw E(X) of eq. (2.6) (truncated domain, numerical rule)
    normalization I of eq. (2.7), the same rule applied to the density alone
    expectation   corrected E^(X) = E(X) / I, eq. (2.7)
    macroscopic   N_p E^(X) with N_p = peak_density * area (None without peak_density)
    per_unit_area macroscopic / area
    """

    integral: Any
    normalization: float
    expectation: Any
    macroscopic: Any = None
    per_unit_area: Any = None


def expectation(
    x: Callable | float,
    density,
    bounds=None,
    cells=(20, 20),
    rule: str = "trapezoid",
    peak_density: float | None = None,
    area: float = 1.0,
) -> Expectation:
    """Expected value of X over the peak population, eqs. (2.5)-(2.7).

    Parameters
    ----------
    x : callable or float
        X(z, kappa), vectorized: called once with z and kappa arrays that
        broadcast to the 2-D population shape P (z of shape (Pz, 1), kappa of
        shape (1, Pk)); it returns an array broadcastable to P, optionally
        with extra trailing dimensions (each integrated separately).  A
        scalar means a constant X.  Where f = 0 the product X f is taken as
        0 even if X is infinite or nan (e.g. Hertz at curvature 0).
    density : JointDensity, FixedCurvatureDensity or SampledDensity
        For fixed curvature X is called with kappa = density.curvature and
        the rule is 1-D in z (bounds (z_min, z_max), or a 4-tuple whose
        curvature entries are ignored; only the first entry of cells is used).
    bounds : (z_min, z_max, kappa_min, kappa_max), optional
        Truncated domain; defaults to ``density.support()``.
    cells : (nz, nk)
        Cells per direction.
    rule : "trapezoid", "gauss" or "peaks"
        "peaks" (SampledDensity only): E(X) = mean of X over the peak list, I = 1.
    peak_density : float, optional
        Areal peak density n; N_p = n * area.
    area : float
        Nominal contact area A_0.
    """
    z, k, w, f = _population(density, bounds, cells, rule)
    fw = f * w
    norm = 1.0 if rule == "peaks" else float(fw.sum())  # peaks: I = 1 exactly
    if not norm > 0.0:
        raise ValueError("the density integrates to zero over the bounds: wrong bounds?")
    if callable(x):
        vals = np.asarray(x(z, k), dtype=float)
        pshape = fw.shape
        if vals.ndim < 2:
            vals = np.broadcast_to(vals, pshape)
        extra = vals.shape[2:]
        vals = np.broadcast_to(vals, pshape + extra)
        fwx = fw.reshape(pshape + (1,) * len(extra))
        with np.errstate(invalid="ignore", over="ignore"):
            prod = np.where(fwx != 0.0, vals * fwx, 0.0)
        integral = prod.sum(axis=(0, 1))
        if integral.ndim == 0:
            integral = float(integral)
    else:
        c = np.asarray(x, dtype=float)
        integral = c * norm
        if integral.ndim == 0:
            integral = float(integral)
    expect = integral / norm
    macro = per_area = None
    if peak_density is not None:
        n_peaks = float(peak_density) * float(area)
        macro = n_peaks * expect
        per_area = macro / float(area)
    return Expectation(integral, norm, expect, macro, per_area)


# ----------------------------------------------------------------------------
# interface response: homogenization of an asperities dataset over separations


_CHUNK = 2_000_000  # elements of (separation, z-node, kappa-node, variable) held at once


def interface_response(
    asperities: xr.Dataset,
    density,
    separations,
    bounds=None,
    cells=(20, 20),
    rule: str = "gauss",
    peak_density: float | None = None,
    reach: float = 0.0,
    contact: str | None = None,
) -> xr.Dataset:
    """Homogenized interface laws versus separation (report 2.5, eqs. (2.5)-(2.7)).

    For a rigid flat at separation h, the asperity of peak height z is pressed
    by the interference w = z - h (in contact when w > 0), and every data
    variable X of `asperities` is averaged over the peak population::

        E(X)(h) = int int_{z > h} X(z, kappa, z - h) f(z, kappa) dkappa dz,   E^ = E / I

    Quadrature: for each h the z-cells span [max(h, z_min), z_max] with the
    given number of cells, so the contact onset lies on a cell boundary and
    the w^(3/2)-type kink at w = 0 does not spoil the rule (nodes at w = 0
    carry the limit w -> 0+).  The normalization I of eq. (2.7) is the rule
    applied to f over the whole rectangle.  X is interpolated from the
    asperity grid: linearly in height and curvature (clamped at the grid
    edges; a dimension of length one means independence of it) and linearly
    in interference, X = 0 at w = 0 when the grid starts above 0.

    Asperities that act out of contact (adhesion, report 3.3.3 and 7.3: the
    attraction starts before contact): with ``reach`` > 0 every asperity
    with z > h - reach contributes X(z, kappa, z - h), w < 0 being a gap.
    The z-range of each separation is then two segments, [h - reach, h]
    (out of contact) and [h, z_max], each with the given number of cells,
    so the onset of contact stays on a cell boundary; the table must start
    at w <= -reach.  ``contact``: the variable that is 1 where an asperity
    is in contact (an adhesive contact can hold at w < 0 on retraction, and
    an asperity at w > 0 is not in contact before it has jumped in); the
    contact count is then n E^(contact) instead of n E^(1 where w > 0).

    Parameters
    ----------
    asperities : xarray.Dataset
        Dims (height, curvature, interference); interference increasing from
        0 or a positive value; data variables e.g. force [N], contact_area
        [m^2], stiffness [N/m] - every variable present is homogenized.
    density : JointDensity, FixedCurvatureDensity or SampledDensity
        Fixed curvature: 1-D rule in z, X interpolated at density.curvature.
    separations : array_like, shape (S,)
        Separations h [m] (same origin as the peak heights).
    bounds : tuple, optional
        (z_min, z_max, kappa_min, kappa_max); for fixed curvature
        (z_min, z_max) or the 4-tuple of its support (curvature entries
        ignored); defaults to ``density.support()``.
    cells : (nz, nk)
        Cells per direction (only nz for fixed curvature).
    rule : "gauss", "trapezoid" or "peaks"
        "peaks" (SampledDensity): E(X) = mean over the sampled peaks of
        X(z_i, kappa_i, z_i - h) (0 where z_i <= h), I = 1; exact for the
        sampled surface.
    peak_density : float
        Areal peak density n [1/m^2] (required).
    reach : float
        Gap [m] up to which asperities out of contact still act (0: none).
    contact : str, optional
        Variable of `asperities` (1 in contact, else 0) that counts contacts;
        it is not returned as ``<contact>_per_unit_area``.

    Returns
    -------
    xarray.Dataset on dim ``separation``: nominal_pressure = n E^(force) [Pa],
    contact_area_ratio = n E^(contact_area) [1], normal_stiffness =
    n E^(stiffness) [Pa/m] (each only if its variable is present),
    ``<var>_per_unit_area`` = n E^(var) for other variables, contact_count =
    n E^(1 where w > 0) [1/m^2], density_integral I, and the raw integrals
    ``raw_<var>`` and ``raw_contact`` of eq. (2.6).

    Raises
    ------
    ValueError
        If the quadrature needs interferences beyond the grid's largest by
        more than 1e-9 relative, or on malformed input.
    """
    if peak_density is None:
        raise ValueError("peak_density [1/m^2] is required to scale expectations per unit area")
    n = float(peak_density)
    h = np.atleast_1d(np.asarray(separations, dtype=float))
    if h.ndim != 1 or not np.isfinite(h).all():
        raise ValueError("separations must be a 1-D array of finite numbers")
    table = response_table(asperities)
    reach = check_reach(reach, table)
    if contact is not None and contact not in table.names:
        raise ValueError(f"contact variable {contact!r} is not in the asperities dataset")

    if rule == "peaks":
        raw, raw_count, norm = _peaks_response(table, density, h, reach)
    else:
        raw, raw_count, norm = _cell_response(table, density, h, bounds, cells, rule, reach)
        if bounds is None:
            bounds = _default_bounds(density)
    counted = "1 where w > 0"
    if contact is not None:  # the count is the expectation of the contact indicator
        j = table.names.index(contact)
        raw_count = raw[:, j]
        keep = [i for i in range(len(table.names)) if i != j]
        raw = raw[:, keep]
        table = table._replace(names=[table.names[i] for i in keep],
                               units=[table.units[i] for i in keep])
        counted = contact

    exp = raw / norm  # (S, V)
    count = n * raw_count / norm
    sep_dims = ("separation",)
    data_vars = {}
    for j, (name, units) in enumerate(zip(table.names, table.units)):
        if name in _MACRO:
            out, out_units, long_name = _MACRO[name]
        else:
            out = f"{name}_per_unit_area"
            out_units = f"({units})/m^2" if units not in ("", "1") else "1/m^2"
            long_name = f"{name} per unit nominal area, n E^({name}) (eq. 2.7)"
        data_vars[out] = (sep_dims, n * exp[:, j], {"units": out_units, "long_name": long_name})
    data_vars["contact_count"] = (sep_dims, count, {"units": "1/m^2", "long_name": f"asperities in contact per unit nominal area, n E^({counted})"})
    data_vars["density_integral"] = ((), norm, {"units": "1", "long_name": "numerical integral I of the peak density over the truncated domain (eq. 2.7)"})
    for j, (name, units) in enumerate(zip(table.names, table.units)):
        data_vars[f"raw_{name}"] = (sep_dims, raw[:, j], {"units": units or "1", "long_name": f"uncorrected expectation integral E({name}) per asperity (eq. 2.6)"})
    data_vars["raw_contact"] = (sep_dims, raw_count, {"units": "1", "long_name": f"uncorrected integral E({counted}) per asperity (eq. 2.6)"})
    attrs = {
        "title": "interface response homogenized over the asperity population (report 2.5)",
        "rule": rule,
        "peak_density": n,
    }
    if reach > 0.0:
        attrs["reach"] = reach
    if rule != "peaks":
        attrs["cells"] = list(np.atleast_1d(cells).astype(int).tolist())
        attrs["bounds"] = [float(b) for b in bounds]
    return xr.Dataset(
        data_vars,
        coords={"separation": (sep_dims, h, {"units": "m", "long_name": "separation of the rigid flat from the height datum"})},
        attrs=attrs,
    )


def _peaks_response(table: ResponseTable, density, h, reach: float = 0.0):
    if not isinstance(density, SampledDensity):
        raise ValueError('rule "peaks" needs a SampledDensity (a list of peaks)')
    z = density.heights[None, :]
    k = density.curvatures[None, :]
    w = z - h[:, None]  # (S, N)
    acting = w > -reach if reach > 0.0 else w > 0.0
    if acting.any():
        check_interference(float(w[acting].max()), table)
    nv = table.data.shape[-1]
    n_peaks = z.shape[1]
    step = max(1, _CHUNK // max(1, n_peaks * nv))
    raw = np.empty((h.size, nv))
    for s in range(0, h.size, step):  # memory guard only: chunks of separations
        sl = slice(s, s + step)
        x = interpolate_points(table, z, k, np.maximum(w[sl], -reach))
        with np.errstate(invalid="ignore"):
            x = np.where(acting[sl, :, None], x, 0.0)
        raw[sl] = x.mean(axis=1)
    return raw, (w > 0.0).mean(axis=1), 1.0


def _cell_response(table: ResponseTable, density, h, bounds, cells, rule, reach: float = 0.0):
    if bounds is None:
        bounds = _default_bounds(density)
    if _is_fixed(density):
        z0, z1 = _check_bounds(bounds, 2)
        nz = _cells1(cells)
        k_nodes = np.array([density.curvature])
        wk = np.array([1.0])

        def pdf(z, k):
            return density.pdf(z)[..., None] * np.ones(k.shape[-1])
    elif isinstance(density, (JointDensity, SampledDensity)) or hasattr(density, "pdf"):
        z0, z1, k0, k1 = _check_bounds(bounds, 4)
        nz, nk = _cells2(cells)
        k_nodes, wk = quadrature_1d(k0, k1, nk, rule)

        def pdf(z, k):
            return density.pdf(z[..., None], k)
    else:  # pragma: no cover - defensive
        raise TypeError(f"unsupported density {type(density).__name__}")

    # normalization I over the whole rectangle, eq. (2.7)
    zf, wzf = quadrature_1d(z0, z1, nz, rule)
    norm = float((pdf(zf, k_nodes) * wzf[:, None] * wk[None, :]).sum())
    if norm <= 0.0:
        raise ValueError("the density integrates to zero over the bounds: wrong bounds?")

    # contact region [max(h, z_min), z_max] for each separation, same number of cells
    lo = np.clip(h, z0, z1)
    z, wz = quadrature_1d(lo, z1, nz, rule)  # (S, Pz)
    touching = np.ones(z.shape[1], bool)  # nodes at w >= 0
    if reach > 0.0:  # and the asperities acting out of contact, [h - reach, h], own cells
        zg, wg = quadrature_1d(np.clip(h - reach, z0, z1), lo, nz, rule)
        z, wz = np.concatenate([zg, z], axis=1), np.concatenate([wg, wz], axis=1)
        touching = np.concatenate([np.zeros(zg.shape[1], bool), touching])
    w = z - h[:, None]
    active = wz > 0.0
    if active.any():
        check_interference(float(w[active].max()), table)
    w = np.maximum(w, -reach)

    nv = table.data.shape[-1]
    pz, pk = z.shape[1], k_nodes.size
    raw = np.empty((h.size, nv))
    raw_count = np.empty(h.size)
    step = max(1, _CHUNK // max(1, pz * pk * nv))
    for s in range(0, h.size, step):  # memory guard only: chunks of separations
        sl = slice(s, s + step)
        g = pdf(z[sl], k_nodes) * wz[sl, :, None] * wk  # (s, Pz, Pk): f w dz dkappa
        raw_count[sl] = g[:, touching].sum(axis=(1, 2))
        x = interpolate_tensor(table, z[sl], w[sl], k_nodes)
        with np.errstate(invalid="ignore", over="ignore"):
            x = np.where(g[..., None] != 0.0, x, 0.0)
        raw[sl] = np.einsum("spk,spkv->sv", g, x)
    return raw, raw_count, norm
