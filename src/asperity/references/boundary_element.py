"""Deterministic contact of a rough height map with a rigid flat (boundary elements).

The statistical route of the report (2.4 - 2.5, 7.1) replaces the surface by a
population of independent asperities.  This module solves the contact of the
same surface deterministically, with the elastic half-space discretized by
boundary elements on the map's own grid, so that the statistical route can be
measured against it (the `deterministic_reference` scene).

The elastic half-space is ContactMechanics' FFT boundary-element operator on
the grid (piecewise-constant pressure on each cell); the contact problem is
its dual, a quadratic program in the cell forces (Polonsky and Keer, Wear
231 (1999) 206), solved by the library's bound-constrained conjugate
gradients (Bugnicourt et al., Tribol. Lett. 66 (2018) 29), or with a
hardness by L-BFGS-B in the box 0 <= p <= H.

Problem solved
--------------
An elastic body with the map's heights z(x, y) (its mean plane at z = 0, the
undefined points left out) pressed by a rigid flat held at height
``separation`` h above that mean plane.  For small slopes this is the same
problem as a rigid rough surface against an elastic flat with the contact
(plane-strain) modulus E* = E / (1 - nu^2) (Johnson, *Contact Mechanics*,
1985, sec. 13.1), which is what is solved.  Per separation: the nominal
pressure p (total force over the nominal area), the real contact area ratio
A/A0 (grid cells carrying pressure, less the perimeter correction below,
over all defined cells), the number of
contact patches per unit area (connected sets of contacting cells, eight
neighbours), the mean gap and the largest pressure.

Separation and the mean plane
-----------------------------
The statistical route measures the separation h from the mean plane of the
rough surface and neglects the bulk deformation (GW 7.1, 2.5).  Here:

* ``periodic`` (default): the map is one period of an infinite surface, the
  kernel is the periodic half-space, and its uniform (q = 0) displacement is
  set to zero: the mean plane of the deformed surface stays where the
  undeformed one was, so the flat's height above the mean plane equals the
  mean gap exactly for an elastic body.  A map that is not periodic (a
  measurement) is treated as one tile of a periodic surface: the height jump
  at its edges is part of the geometry (the method needs no slopes) and the
  interface is infinite, as the statistical route's is.
* ``free``: the map is a finite patch on an otherwise unloaded half-space,
  fixed at infinity (Hockney's method: the map zero-padded to twice its size
  so that the FFT's periodic images do not interact).  The separation is
  then the flat's height above the map's undeformed mean plane measured from
  the far field, and includes the sink-in of the whole loaded patch, which
  an infinite interface does not have; ``mean_gap`` gives the separation
  from the deformed surface.

With a ``hardness`` H the surface is perfectly plastic: no cell carries more
than H, and where the flat penetrates a cell at H the material has flowed
away (its gap is zero) (Almqvist et al., Tribol. Int. 40 (2007) 574; Weber
et al., Nat. Commun. 9 (2018) 888).  Separations are solved in decreasing
order (increasing load), each from the forces of the last; each is the
bounded problem of the undeformed surface, which is the loading path's as
long as no flowed cell is unloaded by its neighbours.  At full plasticity
the contact area tends to F/H.

Resolution
----------
Against Hertz on its grid (free boundary, tests/references/test_boundary_element.py),
the force of a paraboloid is within 0.15 (dx/a)^2 of Hertz (second order in
the grid step, as piecewise-constant pressure elements are) and the radius of
the counted contact area within a quarter of a grid step, for contact radii
a from 4 to 16 grid steps: about 50 cells per contact give the force to
1 % and the radius to 6 %.  Counted, the area is too large: the discrete
pressure reaches past the edge of the contact, where the exact one vanishes
as the square root of the distance, so that cells along the edge carry load
outside it, and the smaller the patches the larger the share of such cells
(which is why the area-load slope of rough surfaces converges slowly with
the grid).  ``contact_area_ratio`` is therefore the counted area less the
perimeter correction of Yastrebov, Anciaux and Molinari (Tribol. Int. 114
(2017) 161): alpha = (pi - 1 + ln 2) / 24 of a cell for each cell edge
between a cell in elastic contact and one out of contact (an edge of a cell
at the hardness is a plastic edge, with no such bias),

    A = (n_contact - alpha n_edges) dx dy;

``counted_area_ratio`` keeps the count.  On Hertz's circular and elliptic
contacts (curvature ratios 1 to 1/16) of 100 and 300 cells the corrected
area is within 5 % and 3 %, where the count alone is not (tests/references).
``cells_per_patch`` (contacting cells over patches) is reported per
separation so that the resolution can be judged.

Undefined points (NaN) neither touch the flat nor count in the nominal area
(the solver masks them); their share is recorded.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from asperity.references.hertz import plane_strain_modulus
from asperity.units import attrs

__all__ = ["BOUNDARIES", "BoundaryElementError", "solve_map", "contact_patches", "contact_edges",
           "plane_strain_modulus", "EDGE_CORRECTION"]

#: how the map's edges are treated (see the module docstring)
BOUNDARIES = ("periodic", "free")
#: how far (in standard deviations) below the lowest defined point undefined points are put
UNDEFINED_DEPTH = 1.0e3
#: area (in cells) a contact edge adds to the counted area (Yastrebov, Anciaux and Molinari
#: 2017): subtracted per edge between a cell in elastic contact and one out of contact
EDGE_CORRECTION = (np.pi - 1.0 + np.log(2.0)) / 24.0


class BoundaryElementError(RuntimeError):
    """The boundary-element solver did not converge at a separation."""


def contact_patches(mask: np.ndarray, periodic: bool) -> int:
    """Number of connected patches of True cells (eight neighbours); with
    `periodic`, patches that meet across the map's edges are one."""
    from scipy import ndimage
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    labels, count = ndimage.label(mask, structure=np.ones((3, 3), dtype=bool))
    if not periodic or count == 0:
        return int(count)
    ny, nx = labels.shape
    pairs = []
    for shift in (-1, 0, 1):  # the edge cells' eight neighbours across the wrap
        pairs.append((labels[-1, :], np.roll(labels[0, :], shift)))
        pairs.append((labels[:, -1], np.roll(labels[:, 0], shift)))
    a = np.concatenate([p[0] for p in pairs])
    b = np.concatenate([p[1] for p in pairs])
    keep = (a > 0) & (b > 0)
    graph = coo_matrix((np.ones(keep.sum()), (a[keep] - 1, b[keep] - 1)), shape=(count, count))
    return int(connected_components(graph, directed=False)[0])


def contact_edges(inner: np.ndarray, outside: np.ndarray, periodic: bool) -> int:
    """Cell edges between a cell of `inner` and a cell of `outside` (boolean maps), the
    four neighbours of each cell, across the map's edges where it is `periodic`."""
    count = 0
    for axis in (0, 1):
        a, b = np.moveaxis(inner, axis, 0), np.moveaxis(outside, axis, 0)
        if periodic:  # each cell and the next, the last and the first
            a_next, b_next = np.roll(a, -1, 0), np.roll(b, -1, 0)
        else:
            a, b, a_next, b_next = a[:-1], b[:-1], a[1:], b[1:]
        count += int(np.count_nonzero(a & b_next) + np.count_nonzero(b & a_next))
    return count


def _compliance(system, shape):
    """The displacement of cell forces (normalized units), signed so that a force pressing
    into the body moves its own cell in the direction of the flat's approach."""
    probe = np.zeros(shape)
    probe[0, 0] = 1.0
    sign = float(np.sign(system.substrate.evaluate_disp(probe)[0, 0]))
    return lambda forces: sign * system.substrate.evaluate_disp(forces)


def _incremental_force(compliance, active: np.ndarray, tolerance: float) -> float:
    """The total force increment (normalized units) when the flat approaches by one unit
    with the contact set `active` held: the forces on those cells whose displacement there
    is uniform, G_aa f = 1 (conjugate gradients; G the half-space's compliance, positive
    definite on a set smaller than the whole map)."""
    from scipy.sparse.linalg import LinearOperator, cg

    n = int(active.sum())
    if n == 0:
        return 0.0
    full = np.zeros(active.shape)

    def matvec(fa):
        full[...] = 0.0
        full[active] = np.ravel(fa)
        return compliance(full)[active]

    f, info = cg(LinearOperator((n, n), matvec=matvec, dtype=float), np.ones(n), rtol=tolerance,
                 maxiter=20 * n + 100)
    if info != 0:
        raise BoundaryElementError(f"the incremental contact problem (stiffness) did not converge "
                                   f"on {n} cells ({info} iterations)")
    return float(f.sum())


def _set(values: np.ndarray, k: int, value: float) -> np.ndarray:
    values[k] = value
    return values


def _system(heights: np.ndarray, sizes: tuple[float, float], modulus: float, boundary: str):
    from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
    from ContactMechanics.Factory import make_system
    from SurfaceTopography import Topography

    shape = heights.shape
    periodic = boundary == "periodic"
    if periodic:  # q = 0 stiffness zero: the mean plane of the deformed surface stays put
        substrate = PeriodicFFTElasticHalfSpace(shape, modulus, sizes, stiffness_q0=0.0, fft="serial")
    else:
        substrate = FreeFFTElasticHalfSpace(shape, modulus, sizes, fft="serial")
    return make_system(substrate=substrate, surface=Topography(heights, sizes, periodic=periodic))


def _solve(system, offset: float, start: np.ndarray, upper: float | None, tolerance: float,
           max_iterations: int):
    """Cell forces and gaps at `offset`: the dual (pressure) problem of the library,
    min 1/2 f K^-1 f - f (z + offset) over 0 <= f (<= `upper`): bounded below by the
    library's constrained conjugate gradients (Bugnicourt et al., Tribol. Lett. 66 (2018) 29),
    in a box by L-BFGS-B; `tolerance` bounds the gap's projected gradient."""
    if upper is None:
        result = system.dual_minimize_proxy(offset, init_force=start, gtol=tolerance,
                                            maxiter=max_iterations)
    else:
        from scipy.optimize import minimize

        bounds = np.zeros((start.size, 2))
        bounds[:, 1] = np.broadcast_to(upper, start.shape).ravel()
        result = minimize(system.dual_objective(offset, gradient=True), start.ravel(),
                          method="L-BFGS-B", jac=True, bounds=bounds,
                          options={"gtol": tolerance, "ftol": 0.0, "maxiter": max_iterations,
                                   "maxfun": 2 * max_iterations, "maxcor": 20})
    force = np.asarray(result.x).reshape(start.shape)
    # the gap is the dual objective's gradient (the solvers return it projected)
    gap = system.dual_objective(offset, gradient=True)(force.ravel())[1].reshape(start.shape)
    return result, force, gap


#: the variables of `solve_map`'s dataset: units, long name
_VARIABLES = {
    "nominal_pressure": ("Pa", "nominal pressure: total force over the nominal (defined) area"),
    "contact_area_ratio": ("1", "real contact area ratio A/A0: contacting cells, less the perimeter "
                                "correction of their elastic edges, over defined cells"),
    "counted_area_ratio": ("1", "contacting cells over defined cells (no perimeter correction)"),
    "contact_count": ("1/m^2", "contact patches (connected contacting cells, eight neighbours) per unit area"),
    "mean_gap": ("m", "mean gap between the flat and the deformed surface over the defined cells"),
    "normal_stiffness": ("Pa/m", "normal stiffness -dp/dh: the force increment of an approach with "
                                 "the contacting cells held (flowing cells at the hardness excluded)"),
    "max_pressure": ("Pa", "largest pressure of a cell"),
    "cells_per_patch": ("1", "contacting cells per contact patch (resolution of the contacts)"),
    "flowing_area_ratio": ("1", "share of the nominal area at the hardness (flowing)"),
    "yielded_fraction": ("1", "share of the real contact area pressed beyond the yield pressure "
                              "(elastic solution)"),
    "iterations": ("1", "conjugate-gradient iterations of the solve"),
}


def _checked(heights, dx, dy, separations, contact_modulus, hardness, boundary):
    """The map and the separations of `solve_map` as arrays, its inputs checked (ValueError)."""
    z = np.array(heights, dtype=float)
    if z.ndim != 2 or min(z.shape) < 2:
        raise ValueError(f"heights must be a 2-D map of at least 2 x 2 points; got shape {z.shape}")
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}; got {boundary!r}")
    if not (dx > 0 and dy > 0):
        raise ValueError(f"grid spacings must be positive; got dx = {dx!r}, dy = {dy!r}")
    if not contact_modulus > 0:
        raise ValueError(f"contact modulus must be positive; got {contact_modulus!r}")
    if hardness is not None and not hardness > 0:
        raise ValueError(f"hardness must be positive; got {hardness!r}")
    h = np.asarray(separations, dtype=float)
    if h.ndim != 1 or h.size == 0 or not np.all(np.isfinite(h)):
        raise ValueError("separations must be a non-empty 1-D array of finite numbers")
    return z, h


def solve_map(
    heights,
    dx: float,
    dy: float,
    separations,
    contact_modulus: float,
    *,
    hardness: float | None = None,
    boundary: str = "periodic",
    tolerance: float = 1e-6,
    max_iterations: int = 5000,
    yield_pressure: float | None = None,
) -> xr.Dataset:
    """Contact of the map `heights` with a rigid flat at each of `separations`.

    Parameters
    ----------
    heights : array_like, shape (ny, nx)
        ``z[i, j] = z(x = j dx, y = i dy)`` (m); NaN where undefined.
    dx, dy : float
        Grid spacings along x (axis 1) and y (axis 0) (m).
    separations : array_like
        Heights of the flat above the mean plane of the defined heights (m).
    contact_modulus : float
        E* = E / (1 - nu^2) of the body (the flat is rigid) (Pa).
    hardness : float, optional
        Largest pressure a cell carries (Pa): a perfectly plastic surface.
    boundary : {"periodic", "free"}
        How the edges are treated (module docstring).
    tolerance : float
        Largest violation of the contact conditions at convergence (a gap
        where there is pressure, a penetration where there is none), relative
        to the standard deviation of the heights.
    max_iterations : int
        Iterations of the solver per separation before it gives up.
    yield_pressure : float, optional
        A pressure (Pa, typically the hardness) whose excess the elastic solution
        reports: ``yielded_fraction``, the share of the real contact area (cells)
        pressed beyond it, where an elastic answer describes a surface that flows.

    Returns
    -------
    xarray.Dataset
        On dim ``separation`` (as given, increasing): nominal_pressure,
        contact_area_ratio (perimeter-corrected), counted_area_ratio,
        contact_count, mean_gap, normal_stiffness (the
        incremental problem on the contact set: G_aa f = 1), max_pressure,
        cells_per_patch, flowing_area_ratio (hardness only), yielded_fraction
        (yield_pressure only), iterations;
        attributes: boundary, contact_modulus, hardness, undefined_fraction,
        cpu_time, grid.

    Raises
    ------
    BoundaryElementError
        The solver did not converge at a separation (named in the message).
    """
    z, h = _checked(heights, dx, dy, separations, contact_modulus, hardness, boundary)
    defined = np.isfinite(z)
    n_defined = int(defined.sum())
    if n_defined == 0:
        raise ValueError("the map has no defined height")
    z = z - z[defined].mean()
    sigma = float(z[defined].std())
    if not sigma > 0:
        raise ValueError("the map is flat (zero standard deviation of height)")
    # solved in units of sigma (lengths) and E* (pressures): the solvers' tolerances are
    # absolute.  Undefined points sit far below the lowest point: they never touch.
    zs = np.where(defined, z / sigma, np.nanmin(z) / sigma - UNDEFINED_DEPTH)
    ny, nx = z.shape
    dxs, dys = dx / sigma, dy / sigma
    sizes = (ny * dys, nx * dxs)  # ContactMechanics' physical sizes follow the array's axes
    cell = dxs * dys
    area = n_defined * cell
    upper = None if hardness is None else np.where(defined, hardness / contact_modulus * cell, 0.0)
    system = _system(zs, sizes, 1.0, boundary)
    order = np.argsort(h)[::-1]  # largest separation first: increasing load
    names = ("nominal_pressure", "contact_area_ratio", "counted_area_ratio", "contact_count", "mean_gap",
             "normal_stiffness",
             "max_pressure", "cells_per_patch", "flowing_area_ratio", "yielded_fraction", "iterations")
    compliance = _compliance(system, z.shape)
    out = {name: np.full(h.size, np.nan) for name in names}
    force = np.zeros(z.shape)
    start = time.process_time()
    top = float(zs[defined].max())
    for k in order:  # each from the last solution: a loading path
        if float(h[k]) / sigma >= top:  # the flat touches nothing: no force, the gap is h - z
            force = np.zeros(z.shape)
            out.update({name: _set(out[name], k, value) for name, value in (
                ("nominal_pressure", 0.0), ("contact_area_ratio", 0.0), ("counted_area_ratio", 0.0),
                ("contact_count", 0.0),
                ("mean_gap", float(np.mean(float(h[k]) - z[defined]))), ("max_pressure", 0.0),
                ("normal_stiffness", 0.0),
                ("flowing_area_ratio", 0.0 if upper is not None else np.nan),
                ("yielded_fraction", 0.0 if yield_pressure is not None else np.nan),
                ("iterations", 0.0))})
            continue
        result, force, gap = _solve(system, -float(h[k]) / sigma, force, upper, tolerance,
                                    max_iterations)
        if not result.success:
            raise BoundaryElementError(
                f"boundary-element solve ({boundary}, "
                f"{'elastic' if hardness is None else 'hardness %g Pa' % hardness}) did not converge "
                f"at separation {h[k]:.6g} m after {result.nit} iterations: {result.message}")
        force = np.where(defined, force, 0.0)
        touching = force > 0.0
        patches = contact_patches(touching, boundary == "periodic")
        cells = int(touching.sum())
        flowing = np.zeros(z.shape, bool)
        if upper is not None:
            flowing = force >= upper * (1 - 1e-6)
            out["flowing_area_ratio"][k] = np.count_nonzero(flowing & defined) / n_defined
        edges = contact_edges(touching & ~flowing, ~touching, boundary == "periodic")
        out["nominal_pressure"][k] = force.sum() / area * contact_modulus
        out["contact_area_ratio"][k] = (cells - EDGE_CORRECTION * edges) / n_defined
        out["counted_area_ratio"][k] = cells / n_defined
        out["contact_count"][k] = patches / (n_defined * dx * dy)
        # a flowing cell's penetration is material pushed away: its gap is zero
        out["mean_gap"][k] = float(np.mean(np.maximum(gap[defined], 0.0))) * sigma
        out["max_pressure"][k] = force.max() / cell * contact_modulus
        out["cells_per_patch"][k] = cells / patches if patches else np.nan
        # -dp/dh: the cells in elastic contact held, the flat approaching (flowing cells keep H)
        out["normal_stiffness"][k] = (_incremental_force(compliance, touching & ~flowing, 1e-8)
                                      / area * contact_modulus / sigma)
        if yield_pressure is not None and cells:
            above = force > yield_pressure / contact_modulus * cell
            out["yielded_fraction"][k] = np.count_nonzero(above & defined) / cells
        elif yield_pressure is not None:
            out["yielded_fraction"][k] = 0.0
        out["iterations"][k] = result.nit
    cpu = time.process_time() - start
    ds = xr.Dataset(
        {name: ("separation", out[name], attrs(*_VARIABLES[name])) for name in names
         if (hardness is not None or name != "flowing_area_ratio")
         and (yield_pressure is not None or name != "yielded_fraction")},
        coords={"separation": ("separation", h, attrs(
            "m", "height of the rigid flat above the mean plane of the surface"))},
    ).sortby("separation")
    ds.attrs.update({
        "method": "boundary elements, FFT half-space (ContactMechanics): dual problem by "
                  "bound-constrained conjugate gradients, or L-BFGS-B under a hardness",
        "boundary": boundary,
        "contact_modulus": float(contact_modulus),
        "hardness": float(hardness) if hardness is not None else np.nan,
        "undefined_fraction": 1.0 - n_defined / z.size,
        "sigma": sigma,
        "grid": f"{ny} x {nx} points, dx = {dx:.6g} m, dy = {dy:.6g} m",
        "tolerance": tolerance,
        "cpu_time": cpu,
    })
    return ds
