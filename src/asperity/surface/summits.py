"""Summits (asperities) of a height map at a stated lateral scale (report 2.4.3).

The eight-neighbour peaks of :func:`asperity.surface.maps.map_peaks` are the
peaks at the pixel: their number and curvatures follow the instrument's
sampling interval, not the surface (Greenwood and Wu, Wear 249 (2001) 766).
Report 2.4.3 lets "the mesh spacing h ... filter out high-frequency noise" and
takes the second derivatives at a peak by "a generalized minimization
procedure" (its Appendix A: the least-squares fit of a second-order
polynomial over a neighbourhood, as A.1 does for profiles).  Here the lateral
scale is the short-wavelength cut-off ``scale`` = lambda_s of the Gaussian
filter, stated and set by the user:

1. Low-pass (:func:`lowpass_map`): the areal Gaussian filter of ISO 16610-61
   with cut-off lambda_s; a wave of wavelength lambda (any direction) keeps
   the amplitude T(lambda) = exp(-pi (alpha lambda_s / lambda)^2),
   alpha = sqrt(ln 2 / pi) (50 % at lambda = lambda_s).
2. Summits: a point of the map low-passed at lambda_s' (below) strictly
   higher than every point within the neighbourhood radius
   r_n = max(lambda_s / 4, sqrt(dx^2 + dy^2)) (at least the eight
   neighbours: the eight-neighbour rule of 2.4.3 at the pixel scale).
3. Fit (the "generalized minimization" of 2.4.3, step 2): at each summit
   z = c0 + c1 u + c2 v + c3 u^2 + c4 u v + c5 v^2 (u, v the offsets from
   the summit's grid point along x, y) minimizing sum w (z - z_i)^2 over the
   grid points within r_fit = max(5 sigma_w, sqrt(dx^2 + dy^2)) (at least
   the 3 x 3 stencil), with Gaussian weights w = exp(-(u^2 + v^2) /
   (2 sigma_w^2)), sigma_w = max(sigma_s / 2, max(dx, dy) / 2), sigma_s =
   alpha lambda_s / sqrt(2 pi) the standard deviation of the filter's
   weighting function.  Every kept summit has its whole disc, so the
   normal equations are the same for all: their solution operator P (6 x m)
   is computed once and the coefficients of all summits are one product
   C = V P^T of the gathered disc heights V (summits x m).

Why Gaussian weights: for the continuous weight, c3 = <z (u^2 - sigma_w^2)>
/ (2 sigma_w^4) = (1/2) d2/du2 (G * z), G the normalized Gaussian of
sigma_w: the weighted fit returns exactly the second derivatives of the
map smoothed by G, and the Gaussian low-pass at lambda_s' followed by G is
the Gaussian low-pass at lambda_s (variances add) when
lambda_s' = lambda_s sqrt(1 - (sigma_w / sigma_s)^2).  So the low-pass is
done at lambda_s' and the fit completes it: z_xx = 2 c3, z_xy = c4,
z_yy = 2 c5 are the second derivatives of the map low-passed at lambda_s;
a wave a cos(k.x) contributes -a k_i k_j T(2 pi / |k|) to them, whatever
the sampling interval (the sampled Gaussian sums equal the integrals to
exp(-2 pi^2 sigma_w^2 / dx^2) < 2e-5 once sigma_w >= 0.75 dx, i.e.
lambda_s >= 8 dx; the truncation at 5 sigma_w costs 4e-4).  An unweighted
fit over a disc of radius r instead multiplies them by 1 - O((k r)^2), by
an amount that depends on how the disc is sampled.  Below
lambda_s = 5.34 max(dx, dy), sigma_w is held at half a sampling interval
(the fit needs the 3 x 3 stencil) and the curvatures are those of a
slightly larger scale; ``scale = 0``: no low-pass, the eight-neighbour
rule and the weighted 3 x 3 ... 5 x 5 fit: the pixel scale of map_peaks.

Then the mean curvature -(z_xx + z_yy)/2 (the kappa of 2.4.1), the
principal curvatures kappa_1,2 = -(z_xx + z_yy)/2 +- sqrt(((z_xx - z_yy)/2)^2
+ z_xy^2) (eigenvalues of minus the Hessian H; positive at a summit), the
summit's position the vertex v of the fitted quadratic (H v = -g, g =
(c1, c2); the grid point where H is not negative definite or the vertex
lies outside the fit disc: ``vertex`` False) and its height the weighted
mean sum w z / sum w (the height of the map low-passed at lambda_s, as for
the curvatures) plus the quadratic's rise to the vertex, g.v / 2.

Heights are measured from the mean plane of the original defined heights (as
:func:`~asperity.surface.maps.map_peaks` does: the mean height; remove the
form first, :func:`asperity.surface.form.remove_form`).  Axis convention:
``z[i, j] = z(x = j dx, y = i dy)``, x along axis 1.

Edges and undefined points
--------------------------
``periodic=True``: the map is one period of an infinite surface (as the
boundary-element reference treats it, :mod:`asperity.references.boundary_element`):
the low-pass is the FFT product with T, neighbourhoods wrap around, and the
summit density is per defined area.  ``periodic=False``: the low-pass is
:func:`asperity.surface.filters.mean_line` (kernel truncated at
+-lambda_s, normalized over the defined points: a zero-order end correction),
the run-in of lambda_s / 2 at each edge is dropped (ISO 16610-21's
evaluation length, :func:`~asperity.surface.filters.evaluation_margin`), and
so is every summit whose neighbourhood or fit disc leaves the map.  In both
cases a summit whose neighbourhood or fit disc meets an undefined point is
dropped, and the attr ``area`` is the area of the points where a summit
could have been found (their count times dx dy).  Undefined points are
filled, for the low-pass only, by the normalized convolution
sum w z / sum w over defined points (both implementations).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from asperity.surface.filters import ALPHA, evaluation_margin, mean_line
from asperity.surface.missing import defined_heights
from asperity.units import attrs

__all__ = ["summit_profiles", "neighbourhood_radius", "filter_sigma", "fit_parameters", "lowpass_map", "summit_fit_matrix",
           "map_summits", "default_scale", "DEFAULT_SCALE_PIXELS", "LEAST_SCALE_PIXELS", "DEFAULT_MIN_SUMMITS"]

#: lambda_s of the default rule, in sampling intervals (see :func:`default_scale`)
DEFAULT_SCALE_PIXELS = 8.0
#: the least lambda_s of the default rule, in sampling intervals (see :func:`default_scale`)
LEAST_SCALE_PIXELS = 5.0
#: summits the default rule keeps on a map at least (see :func:`default_scale`)
DEFAULT_MIN_SUMMITS = 200
#: r_n as a fraction of lambda_s
RADIUS_FRACTION = 0.25
#: sigma_w of the fit's Gaussian weights as a fraction of the filter's sigma_s
FIT_SIGMA_FRACTION = 0.5
#: the fit's disc: r_fit = FIT_TRUNCATION sigma_w (weight exp(-12.5) = 4e-6 at its edge)
FIT_TRUNCATION = 5.0


def _spacing(h, name):
    h = float(h)
    if not (math.isfinite(h) and h > 0):
        raise ValueError(f"{name} must be a positive grid spacing (m); got {h!r}")
    return h


def _scale(scale):
    s = float(scale)
    if not (math.isfinite(s) and s >= 0):
        raise ValueError(f"scale (lambda_s, m) must be a finite number >= 0; got {scale!r}")
    return s


def neighbourhood_radius(scale: float, dx: float, dy: float) -> float:
    """r_n = max(scale / 4, sqrt(dx^2 + dy^2)): a summit is higher than every point within it."""
    return max(RADIUS_FRACTION * _scale(scale), math.hypot(dx, dy))


def filter_sigma(scale: float) -> float:
    """Standard deviation of the Gaussian weighting function of cut-off ``scale``:
    s(x) ~ exp(-pi (x / (alpha lambda_s))^2) = exp(-x^2 / (2 sigma^2)), sigma = alpha lambda_s / sqrt(2 pi)."""
    return ALPHA * _scale(scale) / math.sqrt(2.0 * math.pi)


def fit_parameters(scale: float, dx: float, dy: float) -> tuple[float, float, float]:
    """(sigma_w, r_fit, lambda_s') of the weighted fit at ``scale`` (module text, step 3).

    sigma_w = max(sigma_s / 2, max(dx, dy) / 2), r_fit = max(4 sigma_w, sqrt(dx^2 + dy^2)),
    lambda_s' = lambda_s sqrt(max(0, 1 - (sigma_w / sigma_s)^2)) (the low-pass before the fit).
    """
    sigma_s = filter_sigma(scale)
    sigma_w = max(FIT_SIGMA_FRACTION * sigma_s, 0.5 * max(dx, dy))
    r_fit = max(FIT_TRUNCATION * sigma_w, math.hypot(dx, dy))
    pre = _scale(scale) * math.sqrt(max(0.0, 1.0 - (sigma_w / sigma_s) ** 2)) if sigma_s > 0 else 0.0
    return sigma_w, r_fit, pre


def _disc(radius: float, dx: float, dy: float) -> tuple[np.ndarray, np.ndarray]:
    """Row and column offsets (di, dj) of the grid points with (dj dx)^2 + (di dy)^2 <= radius^2."""
    ni, nj = int(math.floor(radius / dy + 1e-9)), int(math.floor(radius / dx + 1e-9))
    di, dj = np.meshgrid(np.arange(-ni, ni + 1), np.arange(-nj, nj + 1), indexing="ij")
    inside = (dj * dx) ** 2 + (di * dy) ** 2 <= radius * radius * (1 + 1e-9)
    return di[inside], dj[inside]


def lowpass_map(z, dx: float, dy: float, scale: float, *, defined=None, periodic: bool = True) -> np.ndarray:
    """The map low-passed by the areal Gaussian filter with short-wavelength cut-off ``scale``.

    Transmission exp(-pi (alpha lambda_s / lambda)^2), alpha = sqrt(ln 2 / pi)
    (ISO 16610-61, the product of the profile filters of ISO 16610-21).

    ``periodic=True``: the map is one period; the filter is the product of
    the heights' discrete Fourier transform with exp(-pi alpha^2 lambda_s^2
    (f_x^2 + f_y^2)) (f the frequencies of the DFT, the transmission exactly
    for every wave of the period).  ``periodic=False``:
    :func:`asperity.surface.filters.mean_line` (the sampled weighting
    function, truncated at +-lambda_s and normalized; near an edge over the
    points inside the map).  Undefined points: the normalized convolution
    F[w z] / F[w] (w = 1 at defined points, 0 elsewhere) in both; the result
    is NaN at undefined points.  ``scale = 0`` returns the heights.
    """
    zz, mask = defined_heights(z, defined, 2, "map")
    hx, hy, s = _spacing(dx, "dx"), _spacing(dy, "dy"), _scale(scale)
    if s == 0:
        return zz
    if not periodic:
        out = mean_line(zz, s, (hx, hy), mask)
        return np.where(mask, out, np.nan)
    ny, nx = zz.shape
    fx = np.fft.rfftfreq(nx, d=hx)
    fy = np.fft.fftfreq(ny, d=hy)
    gain = np.exp(-np.pi * (ALPHA * s) ** 2 * (fy[:, None] ** 2 + fx[None, :] ** 2))
    num = np.fft.irfft2(np.fft.rfft2(np.where(mask, zz, 0.0)) * gain, s=zz.shape)
    if mask.all():
        return num
    den = np.fft.irfft2(np.fft.rfft2(mask.astype(np.float64)) * gain, s=zz.shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(mask, num / den, np.nan)


def summit_fit_matrix(di, dj, dx: float, dy: float, sigma_w: float | None = None) -> np.ndarray:
    """The weighted least-squares solution operator P (6 x m) of the quadratic fit.

    Rows of the design matrix A: (1, u, v, u^2, u v, v^2) at u = dj dx, v = di dy;
    weights w = exp(-(u^2 + v^2) / (2 sigma_w^2)) (1 without ``sigma_w``);
    c = P z = pinv(W^1/2 A) W^1/2 z minimizes sum w (A c - z)^2 for the heights
    z at the m offsets.  Built in units of the disc's radius (well
    conditioned) and scaled back.
    """
    u = np.asarray(dj, dtype=np.float64) * dx
    v = np.asarray(di, dtype=np.float64) * dy
    r = max(float(np.max(np.hypot(u, v))), min(dx, dy))
    us, vs = u / r, v / r
    design = np.stack([np.ones_like(us), us, vs, us * us, us * vs, vs * vs], axis=1)
    root = np.ones(u.size) if sigma_w is None else np.exp(-(u * u + v * v) / (4.0 * sigma_w**2))
    scale = np.array([1.0, r, r, r * r, r * r, r * r])
    return np.linalg.pinv(design * root[:, None]) * root[None, :] / scale[:, None]


def _valid_points(mask, rows, cols, margin_rows, margin_cols, periodic):
    """Points whose disc (the offsets ``rows``, ``cols``) is wholly defined and, unless
    periodic, inside the map and ``margin`` points or more from its edges."""
    from scipy import ndimage

    ny, nx = mask.shape
    if mask.all():
        valid = mask.copy()
    else:
        ri, rj = int(np.max(np.abs(rows))), int(np.max(np.abs(cols)))
        footprint = np.zeros((2 * ri + 1, 2 * rj + 1), dtype=bool)
        footprint[rows + ri, cols + rj] = True
        if periodic:  # binary_erosion does not wrap: erode a 3 x 3 tiling and keep its centre
            tiled = np.tile(mask, (3, 3))
            valid = ndimage.binary_erosion(tiled, structure=footprint, border_value=1)[ny:2 * ny, nx:2 * nx]
        else:
            valid = ndimage.binary_erosion(mask, structure=footprint, border_value=0)
    if not periodic:
        edge = np.zeros_like(valid)
        edge[margin_rows:ny - margin_rows, margin_cols:nx - margin_cols] = True
        valid &= edge
    return valid


def map_summits(z, dx: float, dy: float, scale: float, *, defined=None, periodic: bool = True) -> xr.Dataset:
    """Summits of a height map at the lateral scale ``scale`` = lambda_s (module text, 2.4.3).

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        Heights, ``z[i, j] = z(x = j dx, y = i dy)`` (m).
    dx, dy : float
        Grid spacings along x (axis 1) and y (axis 0) (m).
    scale : float
        Short-wavelength cut-off lambda_s of the Gaussian low-pass (m); 0: no
        low-pass, the eight-neighbour rule, the fit with sigma_w = max(dx, dy)/2
        (the pixel scale).
    defined : boolean array of the shape of z, optional
        False at undefined points.
    periodic : bool
        The map is one period (neighbourhoods wrap); else edges are cut.

    Returns
    -------
    xarray.Dataset
        Dimension ``summit``: x, y (the vertex, m, origin at ``z[0, 0]``),
        row, column (the grid point), height (above the mean of the defined
        heights: the weighted mean plus the rise to the vertex, module text),
        curvature = -(z_xx + z_yy)/2, z_xx, z_yy, z_xy,
        principal_curvature_1 >= principal_curvature_2, fit_residual
        (weighted rms of the fit's residuals, m), vertex (bool); attrs
        scale, fit_radius, fit_sigma, prefilter_scale (lambda_s'),
        neighbourhood_radius, fit_points, area (m^2, where summits could be
        found), summit_density (1/m^2), mean_height, periodic, method.
    """
    zz, mask = defined_heights(z, defined, 2, "map")
    hx, hy, s = _spacing(dx, "dx"), _spacing(dy, "dy"), _scale(scale)
    ny, nx = zz.shape
    r_n = neighbourhood_radius(s, hx, hy)
    sigma_w, r_fit, pre = fit_parameters(s, hx, hy)
    ni, nj = _disc(r_n, hx, hy)
    fi, fj = _disc(r_fit, hx, hy)
    reach_i = max(np.max(np.abs(ni)), np.max(np.abs(fi)))
    reach_j = max(np.max(np.abs(nj)), np.max(np.abs(fj)))
    if periodic and (2 * reach_i + 1 > ny or 2 * reach_j + 1 > nx):
        raise ValueError(f"the neighbourhood ({2 * reach_i + 1} x {2 * reach_j + 1} points) is larger "
                         f"than the map ({ny} x {nx}): use a smaller scale")
    zl = lowpass_map(zz, hx, hy, pre, defined=mask, periodic=periodic)
    margin_i = max(reach_i, evaluation_margin(pre, hy) if pre > 0 else 0)
    margin_j = max(reach_j, evaluation_margin(pre, hx) if pre > 0 else 0)
    both_i, both_j = np.concatenate([ni, fi]), np.concatenate([nj, fj])
    valid = _valid_points(mask, both_i, both_j, margin_i, margin_j, periodic)
    area = float(np.count_nonzero(valid)) * hx * hy
    # summit rule: strictly higher than every other point of the r_n disc (one pass per offset)
    ii, jj = np.nonzero(valid)
    zc = zl[ii, jj]
    keep = np.ones(ii.shape, dtype=bool)
    for a, b in zip(ni, nj):  # loop over neighbourhood offsets, vectorized over the candidates
        if a or b:
            keep &= zc > zl[(ii + a) % ny, (jj + b) % nx]
    ii, jj = ii[keep], jj[keep]
    # least-squares quadratic over the r_fit disc, all summits at once
    P = summit_fit_matrix(fi, fj, hx, hy, sigma_w)
    V = zl[(ii[:, None] + fi[None, :]) % ny, (jj[:, None] + fj[None, :]) % nx]  # (summits, m)
    c = V @ P.T
    design = np.stack([np.ones(fi.size), fj * hx, fi * hy, (fj * hx) ** 2, fj * hx * fi * hy,
                       (fi * hy) ** 2], axis=1)
    w = np.exp(-((fj * hx) ** 2 + (fi * hy) ** 2) / (2.0 * sigma_w**2))
    w /= w.sum()
    residual = np.sqrt(((V - c @ design.T) ** 2) @ w)
    zxx, zxy, zyy = 2 * c[:, 3], c[:, 4], 2 * c[:, 5]
    det = zxx * zyy - zxy * zxy
    with np.errstate(invalid="ignore", divide="ignore"):
        u = (-c[:, 1] * zyy + c[:, 2] * zxy) / det  # H (u, v) = -g
        v = (-c[:, 2] * zxx + c[:, 1] * zxy) / det
    vertex = (zxx < 0) & (det > 0) & (np.hypot(u, v) <= r_fit)
    u, v = np.where(vertex, u, 0.0), np.where(vertex, v, 0.0)
    # the lambda_s surface at the grid point, plus the rise to the vertex
    top = V @ w + 0.5 * (c[:, 1] * u + c[:, 2] * v)
    x, y = jj * hx + u, ii * hy + v
    if periodic:
        x, y = np.mod(x, nx * hx), np.mod(y, ny * hy)
    mean_z = float(zz[mask].mean())
    kappa = -0.5 * (zxx + zyy)
    split = np.sqrt((0.5 * (zxx - zyy)) ** 2 + zxy ** 2)

    def var(values, units, long_name):
        return ("summit", values, attrs(units, long_name))

    return xr.Dataset(
        {
            "x": var(x, "m", "x of the summit (fitted vertex)"),
            "y": var(y, "m", "y of the summit (fitted vertex)"),
            "row": var(ii.astype(np.int64), "1", "row index of the summit's grid point (y)"),
            "column": var(jj.astype(np.int64), "1", "column index of the summit's grid point (x)"),
            "height": var(top - mean_z, "m", "summit height above the mean height of the map"),
            "curvature": var(kappa, "1/m", "mean summit curvature -(z_xx + z_yy)/2"),
            "z_xx": var(zxx, "1/m", "second derivative d2z/dx2 of the fitted quadratic"),
            "z_yy": var(zyy, "1/m", "second derivative d2z/dy2 of the fitted quadratic"),
            "z_xy": var(zxy, "1/m", "mixed second derivative d2z/dxdy of the fitted quadratic"),
            "principal_curvature_1": var(kappa + split, "1/m", "larger principal curvature kappa_1"),
            "principal_curvature_2": var(kappa - split, "1/m", "smaller principal curvature kappa_2"),
            "fit_residual": var(residual, "m", "weighted rms residual of the quadratic fit over its disc"),
            "vertex": var(vertex, "1", "position is the fitted vertex (else the grid point)"),
        },
        coords={"summit": ("summit", np.arange(ii.size), attrs("1", "summit number"))},
        attrs={
            "title": "summits of a height map at a lateral scale (report 2.4.3)",
            "scale": s,
            "fit_radius": r_fit,
            "fit_sigma": sigma_w,
            "prefilter_scale": pre,
            "neighbourhood_radius": r_n,
            "fit_points": int(fi.size),
            "area": area,
            "summit_density": ii.size / area if area > 0 else np.nan,
            "mean_height": mean_z,
            "periodic": int(bool(periodic)),
            "method": (f"lambda_s = {s:.6g} m: Gaussian low-pass (ISO 16610-61) at lambda_s' = {pre:.6g} m "
                       f"({'periodic FFT' if periodic else 'truncated kernel, edges cut'}); summit: higher "
                       f"than every point within r_n = {r_n:.6g} m; least-squares quadratic with Gaussian "
                       f"weights sigma_w = {sigma_w:.6g} m over the {fi.size} points within r_fit = "
                       f"{r_fit:.6g} m; height and position at the vertex"),
        },
    )


def default_scale(dx: float, dy: float, z=None, *, defined=None, periodic: bool = True,
                  pixels: float = DEFAULT_SCALE_PIXELS, least: float = LEAST_SCALE_PIXELS,
                  min_summits: int = DEFAULT_MIN_SUMMITS) -> tuple[float, str]:
    """The default lateral scale lambda_s of a map (m), and the rule as text.

    Rule, with h = max(dx, dy) and N(lambda) the number of summits of the map
    at lambda (:func:`map_summits`)::

        lambda_s = 8 h                                  if N(8 h) >= 200 (or no map given)
        lambda_s = max(5 h, 8 h sqrt(N(8 h) / 200))     otherwise

    Reasons:

    * 8 h: from lambda_s = 8 h on, the fit's Gaussian weights are resolved
      (sigma_w = sigma_s / 2 >= 0.75 h), so the summits' curvatures are those
      of the surface low-passed at lambda_s whatever the sampling interval
      (module text); below, they follow the pixel (Greenwood and Wu 2001).
    * 5 h: the same scale is applied to the map of the boundary-element
      reference (:mod:`asperity.references.boundary_element`), whose light-load
      contact patches must hold at least 10 cells at a real contact area
      ratio of 0.1 % for its area and count to be trusted; on AFM maps whose
      pixel-scale peaks are noise (data/topographies/mi-1.mi) the patches
      hold about 5 cells at the pixel scale and reach 10 cells at
      lambda_s = 5 h (26 at 8 h).
    * 200 summits: the density and the height-curvature histograms of 2.4.3
      need some hundreds of summits; the summit density of a rough surface
      low-passed at lambda_s goes as lambda_s^-2 (Nayak: m4 / m2 ~
      lambda_s^-2), hence the square root.  The reduction stops at 5 h: if
      the map still holds fewer summits, the text says so (a larger map is
      needed, not a finer scale).

    Returns ``(lambda_s, text)``.
    """
    hx, hy = _spacing(dx, "dx"), _spacing(dy, "dy")
    h = max(hx, hy)
    scale = pixels * h
    text = f"lambda_s = {pixels:g} max(dx, dy) = {scale:.4g} m (fit weights resolved; >= 10 BE cells per contact)"
    if z is None:
        return scale, text
    count = map_summits(z, hx, hy, scale, defined=defined, periodic=periodic).sizes["summit"]
    if count >= min_summits:
        return scale, text + f"; {count} summits"
    reduced = max(least * h, scale * math.sqrt(count / min_summits))
    found = map_summits(z, hx, hy, reduced, defined=defined, periodic=periodic).sizes["summit"]
    text = (f"lambda_s = max({least:g} h, {pixels:g} h sqrt(N / {min_summits})) = {reduced:.4g} m "
            f"(h = max(dx, dy), N = {count} summits at {pixels:g} h): {found} summits")
    if found < min_summits:
        text += f"; fewer than {min_summits}: summit statistics are uncertain (a larger map is needed)"
    return reduced, text


def summit_profiles(z, dx: float, dy: float, rows, cols, curvatures, *, defined=None,
                    tip_pixels: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The axisymmetric profile of each summit, from the map's own shape below its tip.

    Each summit's region is its watershed basin on `z` (the map as the routes see it;
    `scipy.ndimage.watershed_ift` from markers at the summits' grid points `rows`,
    `cols`).  Its bearing area A(d), the area of the basin within a depth d of the
    summit's grid height, defines the radius r = sqrt(A / pi) of an axisymmetric
    asperity with the same area at every depth, so f(r) is the depth at which the
    basin's area reaches pi r^2.  Within `tip_pixels` grid steps of the tip, where the
    basin's area is a cell or two, f is the fitted paraboloid kappa r^2 / 2 (`curvatures`
    kappa); beyond, the bearing profile continues from it.  The boundary elements see
    the same grid: a summit whose top is flatter than its fitted curvature says (a top
    of a few cells within a small depth) carries what its cells carry, which a
    paraboloid over two grid steps would miss.  Past the basin's whole area the profile
    is a wall (its neighbours' basins begin).

    Returns ``(radii, slopes)``: the common radial grid (m; a quarter of the smaller
    grid step apart) and f'(r) of each summit on it, the input of
    `asperity.references.sneddon.profile_law`.
    """
    from scipy import ndimage

    zz = np.array(z, dtype=float)
    mask = np.isfinite(zz) if defined is None else (np.asarray(defined, bool) & np.isfinite(zz))
    low, high = float(np.min(zz[mask])), float(np.max(zz[mask]))
    zz = np.where(mask, zz, low)
    rows, cols = np.asarray(rows, dtype=int) % zz.shape[0], np.asarray(cols, dtype=int) % zz.shape[1]
    kappa = np.asarray(curvatures, dtype=float)
    n = rows.size
    markers = np.zeros(zz.shape, dtype=np.int32)
    markers[rows, cols] = np.arange(1, n + 1)
    level = np.round((high - zz) / max(high - low, np.finfo(float).tiny) * 65534).astype(np.uint16)
    basin = ndimage.watershed_ift(level, markers)
    label = basin.ravel() - 1
    keep = (label >= 0) & mask.ravel()
    depth = np.maximum(zz[rows, cols][label[keep]] - zz.ravel()[keep], 0.0)
    label = label[keep]
    order = np.lexsort((depth, label))
    label, depth = label[order], depth[order]
    counts = np.bincount(label, minlength=n)
    first = np.concatenate([[0], np.cumsum(counts)[:-1]])
    rank = np.arange(label.size) - first[label]  # pixels of the basin within that depth, less one
    cell = dx * dy
    radius = np.sqrt((rank + 1) * cell / np.pi)
    step = min(dx, dy) / 4.0
    r_tip = tip_pixels * max(dx, dy)
    grid = np.arange(0.0, np.sqrt(counts.max() * cell / np.pi) + 2 * step, step)
    # f(r) of every summit on the grid: the bearing depth at radius r (rows side by side)
    span = grid[-1] + 1.0
    keys = radius + span * label
    query = (grid[None, :] + span * np.arange(n)[:, None]).ravel()
    at = np.clip(np.searchsorted(keys, query, side="left"), 0, label.size - 1).reshape(n, grid.size)
    bearing = depth[at]
    beyond = grid[None, :] > np.sqrt(counts * cell / np.pi)[:, None]
    tip = 0.5 * kappa[:, None] * grid[None, :] ** 2
    j_tip = min(int(np.searchsorted(grid, r_tip)), grid.size - 1)
    profile = np.where(grid[None, :] <= grid[j_tip], tip,
                       bearing - bearing[:, [j_tip]] + tip[:, [j_tip]])
    profile = np.maximum.accumulate(profile, axis=1)
    slopes = np.gradient(profile, step, axis=1)
    wall = 20.0 * max(float(np.nanmax(slopes[~beyond])) if (~beyond).any() else 1.0, 1.0)
    slopes = np.where(beyond, wall, np.maximum(slopes, 0.0))
    return grid, slopes
