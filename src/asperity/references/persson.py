"""Persson's contact theory: the interface law of a rough surface from its power spectrum.

A route beside the statistical one of the report (2.4 - 2.5, 7.1) and the
boundary elements (`asperity.references.boundary_element`): a rigid rough
surface (or, for small slopes, the equivalent problem) pressed by an elastic
flat of contact modulus E* = E / (1 - nu^2), described by nothing but the
isotropic power spectral density C(q) of the heights.

Spectrum
--------
C(q) is Persson's two-dimensional density (Jacobs, Junge and Persson, Surf.
Topogr. Metrol. Prop. 5 (2017) 013001):

    C(q) = (2 pi)^-2 int d^2x <h(x) h(0)> exp(-i q.x),
    <h^2> = 2 pi int q C(q) dq,   <|grad h|^2> = h'_rms^2 = 2 pi int q^3 C(q) dq,
    <(lap h)^2> = 2 pi int q^5 C(q) dq,

q angular (rad/m), C in m^4.  A map's C is its periodogram averaged over rings
(:func:`isotropic_spectrum`).  A spectrum here is a set of nodes q_k with
values C_k, and every integral over q is the midpoint-cell rule

    int f(q) C(q) dq = sum_k f(q_k) C_k W_k,

W_k the width of the cell about q_k bounded by the midpoints between nodes
(the outer cells symmetric about their node) (:func:`quadrature_weights`); on
a uniform grid this is the rectangle rule.  :func:`isotropic_spectrum` defines
C_k with this rule so that the height and gradient moments of the map are
reproduced exactly (Parseval).

Contact area (Persson, J. Chem. Phys. 115 (2001) 3840)
-------------------------------------------------------
The probability density of the contact stress P(sigma, q) obeys a diffusion
equation in G(q) = (pi/4) E*^2 int_{q0}^{q} q'^3 C(q') dq', starting from a
delta at the nominal pressure p, with P(0) = 0 (elastic: the stress vanishes at
the edge of contact).  Its integral is the real contact area ratio

    A/A0 = erf(p / (2 sqrt(G))),  G = G(q1) = E*^2 h'_rms^2 / 8,

so A/A0 -> sqrt(8/pi) p / (E* h'_rms) at small p.

Mean gap (Persson, Phys. Rev. Lett. 99 (2007) 125502; Yang and Persson, J. Phys.
Condens. Matter 20 (2008) 215214)
----------------------------------------------------------------------------------

    u(p) = sqrt(pi) int dq q^2 C(q) w(q) int_p^inf dp'/p' [gamma + (1 - gamma) P(q, p')^2]
           exp(-(w(q) p' / E*)^2),
    w(q) = (pi int_{q0}^{q} q'^3 C(q') dq')^(-1/2),  P(q, p) = erf(w(q) p / E*),

(P(q, p) = erf(p / (2 sqrt(G(q)))) since 2 sqrt(G(q)) = E* / w(q)).  gamma
corrects the elastic energy stored in the partly contacting interface;
Persson and co-workers take gamma about 0.4 - 0.45 from comparison with
numerical contact mechanics (default 0.42).  With s = w p / E* the inner
integral is a universal function

    F(s) = int_s^inf dt/t [gamma + (1 - gamma) erf(t)^2] exp(-t^2)
         = gamma E1(s^2) / 2 + (1 - gamma) g(s),  g(s) = int_s^inf erf(t)^2 exp(-t^2) / t dt,

(E1 the exponential integral; g is tabulated once by Gauss-Legendre quadrature
and interpolated by cubic Hermite polynomials with its exact derivative, to
about 1e-12), so that u(p) = sqrt(pi) sum_k W_k q_k^2 C_k w_k F(w_k p / E*), a
sum over the nodes for every pressure (vectorized).  w_k uses the cumulative
integral up to the midpoint of the cell k (half of the cell's own term).  The
pressure at a given mean gap is found by Newton's method in log p (u is
strictly decreasing), started from a dense log grid; the stiffness is exact:

    -dp/du = p / (sqrt(pi) sum_k W_k q_k^2 C_k w_k [gamma + (1 - gamma) erf(s_k)^2] exp(-s_k^2)).

At small pressure every s_k << 1, F(s) -> -gamma ln s + const and
p ~ exp(-u / u0), u0 = gamma sqrt(pi) int q^2 C w dq (Persson 2007).

Mean gap and separation: the theory's u is the mean gap between the flat and
the deformed surface; for the elastic periodic boundary-element reference
this is the flat's height above the mean plane, its ``separation``.

Hardness (Persson 2001; Persson, Surf. Sci. Rep. 61 (2006) 201, sec. 6)
------------------------------------------------------------------------
A perfectly plastic surface of hardness H: the stress cannot exceed H, and
Persson's diffusion gets a second absorbing boundary, P(H, q) = 0; the
probability that reaches it is the plastically flowing area.  The solution on
(0, H) by images (a Gaussian of variance 2G, images at +-p + 2mH) or by its
Fourier series,

    A_el/A0 = sum_{n odd} 4/(n pi) sin(n pi p/H) exp(-(n pi/H)^2 G),
    A_pl/A0 = p/H - (1/H) int_0^H sigma P(sigma) dsigma
            = p/H - sum_{n>=1} 2 (-1)^(n+1)/(n pi) sin(n pi p/H) exp(-(n pi/H)^2 G),

(force balance: the flowing area carries H), A/A0 = A_el + A_pl >= p/H, -> erf
as H -> inf, -> p/H as p -> H or G/H^2 -> inf.  This is all the theory gives with
a hardness here: the pressure-gap relation stays the elastic u(p) above
(Persson derives it from the elastic energy; the change of the gap by plastic
flow is not modelled), so nominal pressure, stiffness and mean gap at a given
separation are the elastic ones and only the areas change.  Where the elastic
pressure reaches H the whole surface flows (A/A0 = A_pl/A0 = 1).

Persson's theory gives no number of contacts: ``contact_count`` is NaN.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import xarray as xr
from scipy import special

from asperity.surface.spectra import window as _window
from asperity.units import attrs

__all__ = [
    "DEFAULT_GAMMA",
    "isotropic_spectrum",
    "quadrature_weights",
    "spectrum_moments",
    "gap_function",
    "mean_gap",
    "persson_interface",
    "elastoplastic_areas",
]

#: gamma of the mean-gap theory (Yang and Persson 2008: about 0.4 - 0.45)
DEFAULT_GAMMA = 0.42
_T_MAX = 7.0  # erf(t)^2 exp(-t^2) / t < 1e-22 beyond: g(s) = 0 there
_T_STEP = 2.0e-3
_SMALL_S = 1.0e-4  # below: the series of E1
_BLOCK = 1 << 19  # spectrum nodes x pressures evaluated at once


def quadrature_weights(q) -> np.ndarray:
    """Widths W_k of the midpoint cells about the nodes q_k (increasing): the cell
    boundaries are the midpoints between nodes, the outer cells symmetric about their
    node; int f dq = sum f(q_k) W_k (the rectangle rule on a uniform grid)."""
    q = np.asarray(q, dtype=float)
    if q.size == 1:
        return np.ones(1) * q[0]  # a single node: the cell (q/2, 3q/2)
    mid = 0.5 * (q[1:] + q[:-1])
    edges = np.concatenate([[q[0] - (mid[0] - q[0])], mid, [q[-1] + (q[-1] - mid[-1])]])
    return np.diff(edges)


def isotropic_spectrum(z, dx: float, dy: float, *, defined=None, window: str = "none"
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged two-dimensional power spectral density C(q) of a height map.

    Normalization (Persson's; Jacobs, Junge and Persson 2017): with the module's
    quadrature (:func:`quadrature_weights`) ``2 pi sum q C W`` is the variance of the
    (filled, windowed) heights and ``2 pi sum q^3 C W`` their mean squared gradient,
    both exactly for the map's periodic Fourier interpolation.

    Method: the map (undefined points set to the mean of the defined ones, then the mean
    removed) times the window, its DFT Z, the 2-D density C2(qx, qy) = |Z|^2 A /
    ((2 pi)^2 N sum w^2) (A the map's area, N its points) over the full grid of
    wavenumbers (corners beyond the Nyquist circle included).  Modes are gathered into
    rings of width dq = max(2 pi/(nx dx), 2 pi/(ny dy)) about k dq (k >= 1; empty rings
    dropped).  A ring's node is its power-weighted rms wavenumber
    q_k = (sum q^2 |Z|^2 / sum |Z|^2)^(1/2) (its centre if it holds no power) and
    C_k = (ring's share of the variance) / (2 pi q_k W_k): then both
    moments above are the map's own (the gradient's is the spectral gradient of
    `asperity.stages.reference.gradient_rms`).

    Window: ``"none"`` (default) takes the map as one period of a periodic surface.  The
    boundary-element reference solves exactly that periodic surface (its default
    boundary), so the spectrum it sees is the unwindowed DFT of the map as given, edge
    jump included; Persson's prediction compared with it should use the same.  ``"hann"``
    or ``"blackman"`` suppress the edge jump's q^-4 leakage of a non-periodic
    measurement when the spectrum itself is wanted; the density is then normalized by
    the window power (its moments estimate the surface's, not the map's).

    Parameters
    ----------
    z : (ny, nx) array, ``z[i, j] = z(x = j dx, y = i dy)`` (m); NaN where undefined.
    dx, dy : grid spacings (m).
    defined : optional bool array of z's shape, False where undefined (besides NaN).
    window : "none", "hann" or "blackman".

    Returns
    -------
    q : ndarray, increasing ring nodes (rad/m).
    C : ndarray, C(q_k) (m^4).
    """
    zz = np.array(z, dtype=float)
    if zz.ndim != 2 or min(zz.shape) < 4:
        raise ValueError(f"isotropic_spectrum needs a map of at least 4 x 4 points; got {zz.shape}")
    if not (dx > 0 and dy > 0):
        raise ValueError(f"grid spacings must be positive; got dx = {dx!r}, dy = {dy!r}")
    ok = np.isfinite(zz)
    if defined is not None:
        ok &= np.asarray(defined, dtype=bool)
    if not ok.any():
        raise ValueError("the map has no defined height")
    zz = np.where(ok, zz - zz[ok].mean(), 0.0)
    ny, nx = zz.shape
    w = _window(ny, window)[:, None] * _window(nx, window)[None, :]
    power = np.abs(np.fft.fft2(w * zz)) ** 2 / (zz.size * np.sum(w * w))  # sums to variance
    power[0, 0] = 0.0  # the mean (nonzero only with a window)
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=dy)
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=dx)
    q2 = qy[:, None] ** 2 + qx[None, :] ** 2
    dq = max(2 * np.pi / (nx * dx), 2 * np.pi / (ny * dy))
    ring = np.rint(np.sqrt(q2) / dq).astype(np.int64).ravel()
    n_rings = int(ring.max()) + 1
    share = np.bincount(ring, weights=power.ravel(), minlength=n_rings)
    share_q2 = np.bincount(ring, weights=(q2 * power).ravel(), minlength=n_rings)
    modes = np.bincount(ring, minlength=n_rings)
    keep = (np.arange(n_rings) >= 1) & (modes > 0)
    share, share_q2 = share[keep], share_q2[keep]
    centre = dq * np.arange(n_rings)[keep]
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.where(share > 0, np.sqrt(share_q2 / share), centre)
    q = np.where(np.isfinite(q) & (q > 0), q, centre)
    C = share / (2 * np.pi * q * quadrature_weights(q))
    return q, C


def _check_spectrum(q, C) -> tuple[np.ndarray, np.ndarray]:
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    if q.ndim != 1 or q.shape != C.shape or q.size == 0:
        raise ValueError(f"q and C must be 1-D arrays of one length; got {q.shape} and {C.shape}")
    if not (np.all(np.isfinite(q)) and np.all(q > 0) and np.all(np.diff(q) > 0)):
        raise ValueError("q must be positive, finite and strictly increasing")
    if not (np.all(np.isfinite(C)) and np.all(C >= 0) and C.sum() > 0):
        raise ValueError("C must be finite, non-negative and not all zero")
    return q, C


def spectrum_moments(q, C) -> dict[str, float]:
    """rms height, gradient and curvature from an isotropic spectrum (module quadrature).

    ``height_rms`` = (2 pi int q C dq)^(1/2), ``gradient_rms`` h'_rms = (2 pi int q^3 C dq)^(1/2),
    ``curvature_rms`` = <(lap h)^2>^(1/2) = (2 pi int q^5 C dq)^(1/2) (the Laplacian, twice the
    mean curvature); and the profile moments of the report (2.3.1) of an isotropic surface,
    ``m0`` = h_rms^2, ``m2`` = pi int q^3 C dq, ``m4`` = (3 pi/4) int q^5 C dq (m^2, 1, 1/m^2).
    """
    q, C = _check_spectrum(q, C)
    W = quadrature_weights(q)
    i1, i3, i5 = (float(np.sum(q**p * C * W)) for p in (1, 3, 5))
    return {"height_rms": math.sqrt(2 * np.pi * i1), "gradient_rms": math.sqrt(2 * np.pi * i3),
            "curvature_rms": math.sqrt(2 * np.pi * i5),
            "m0": 2 * np.pi * i1, "m2": np.pi * i3, "m4": 0.75 * np.pi * i5}


@functools.lru_cache(maxsize=1)
def _g_table():
    """g(s) = int_s^inf erf(t)^2 exp(-t^2)/t dt as a cubic Hermite spline on [0, _T_MAX]."""
    from scipy.interpolate import CubicHermiteSpline

    t = np.linspace(0.0, _T_MAX, int(round(_T_MAX / _T_STEP)) + 1)
    x, wts = np.polynomial.legendre.leggauss(10)
    a, b = t[:-1, None], t[1:, None]
    nodes = 0.5 * (b - a) * x[None, :] + 0.5 * (a + b)
    pieces = 0.5 * (b[:, 0] - a[:, 0]) * np.sum(wts * _g_integrand(nodes), axis=1)
    g = np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])
    return CubicHermiteSpline(t, g, -_g_integrand(t))


def _g_integrand(t):
    t = np.asarray(t, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = special.erf(t) ** 2 * np.exp(-t * t) / t
    return np.where(t > 0, out, 0.0)


def gap_function(s, gamma: float = DEFAULT_GAMMA) -> np.ndarray:
    """F(s) = int_s^inf dt/t [gamma + (1 - gamma) erf(t)^2] exp(-t^2) (module text), s > 0."""
    s = np.asarray(s, dtype=float)
    small = s < _SMALL_S
    ss = np.where(small, 1.0, s)
    e1 = np.where(small, -np.euler_gamma - 2 * np.log(np.where(small, s, 1.0)) + s**2,
                  special.exp1(ss * ss))
    g = np.where(s < _T_MAX, _g_table()(np.minimum(s, _T_MAX)), 0.0)
    return gamma * 0.5 * e1 + (1 - gamma) * g


def _gap_terms(q, C):
    """Per node: a_k = sqrt(pi) W q^2 C w, w_k (module text), and the full h'_rms."""
    W = quadrature_weights(q)
    m = q**3 * C * W
    upto = np.cumsum(m) - 0.5 * m  # int_{q0}^{q_k}: up to the midpoint of cell k
    has = C > 0
    w = np.where(has, 1.0 / np.sqrt(np.pi * np.where(has, upto, 1.0)), 1.0)
    a = np.sqrt(np.pi) * W * q**2 * C * w
    return a, w, math.sqrt(2 * np.pi * m.sum())


def mean_gap(q, C, contact_modulus: float, pressures, *, gamma: float = DEFAULT_GAMMA
             ) -> tuple[np.ndarray, np.ndarray]:
    """Persson's mean gap u(p) (m) and its derivative du/dp (m/Pa) at `pressures` (Pa > 0)."""
    q, C = _check_spectrum(q, C)
    a, w, _ = _gap_terms(q, C)
    p = np.asarray(pressures, dtype=float)
    if not (np.all(np.isfinite(p)) and np.all(p > 0)):
        raise ValueError("pressures must be positive and finite")
    flat = p.ravel()
    u, du = np.empty(flat.size), np.empty(flat.size)
    block = max(1, _BLOCK // a.size)  # nodes x pressures per block: bounded memory
    for start in range(0, flat.size, block):
        pb = flat[start:start + block]
        s = w[:, None] * pb[None, :] / contact_modulus
        u[start:start + block] = a @ gap_function(s, gamma)
        du[start:start + block] = -(a @ ((gamma + (1 - gamma) * special.erf(s) ** 2)
                                        * np.exp(-s * s))) / pb
    return u.reshape(p.shape), du.reshape(p.shape)


def _pressure_at_gap(q, C, modulus: float, gaps: np.ndarray, gamma: float) -> np.ndarray:
    """p(u) at the mean gaps: a dense log-p grid, then safeguarded Newton in x = ln p."""
    a, w, _ = _gap_terms(q, C)
    u0 = gamma * a.sum()  # du/dln p -> -u0 at small p
    x_grid = np.log(modulus) + np.linspace(np.log(1e-40), np.log(1e3), 1201)
    u_grid, _ = mean_gap(q, C, modulus, np.exp(x_grid), gamma=gamma)
    j = np.clip(np.searchsorted(-u_grid, -gaps), 1, x_grid.size - 1)
    lo, hi = x_grid[j - 1], x_grid[j]  # bracketing grid points (u decreasing in x)
    hi = np.where(gaps < u_grid[-1], x_grid[-1] + 50.0, hi)  # above 1e3 E*: unphysical, but bracketed
    beyond = gaps > u_grid[0]  # below the grid's smallest pressure: the exponential tail
    lo = np.where(beyond, x_grid[0] - (gaps - u_grid[0]) / u0 - 5.0, lo)
    hi = np.where(beyond, x_grid[0], hi)
    x = np.where(beyond, x_grid[0] - (gaps - u_grid[0]) / u0,
                 np.interp(-gaps, -u_grid, x_grid))
    for _ in range(100):
        u, du = mean_gap(q, C, modulus, np.exp(x), gamma=gamma)
        f = u - gaps
        lo = np.where(f > 0, x, lo)  # u too large: pressure too small
        hi = np.where(f <= 0, x, hi)
        step = -f / (du * np.exp(x))
        x_new = x + step
        out = ~((x_new > lo) & (x_new < hi))
        x_new = np.where(out, 0.5 * (lo + hi), x_new)
        done = np.abs(x_new - x) < 1e-13 * np.maximum(1.0, np.abs(x))
        x = x_new
        if np.all(done):
            break
    return np.exp(x)


def _erf_images(a, c, H):
    """int_0^H of a Gaussian density centred at a (variance c^2/2): 0.5 [erf((H-a)/c) + erf(a/c)]."""
    return 0.5 * (special.erf((H - a) / c) + special.erf(a / c))


def _first_moment_images(a, c, H):
    """int_0^H sigma of the same Gaussian density."""
    return a * _erf_images(a, c, H) + c / (2 * np.sqrt(np.pi)) * (
        np.exp(-(a / c) ** 2) - np.exp(-((H - a) / c) ** 2))


def elastoplastic_areas(pressures, G: float, hardness: float, *, method: str = "auto"
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Persson's elastic and plastic contact area ratios (module text) at `pressures` (Pa),
    G = (pi/4) E*^2 int q^3 C dq (Pa^2), for a hardness H (Pa); p >= H gives (0, 1).

    ``method``: ``"images"`` (the Gaussian of variance 2G and its images at +-p + 2mH),
    ``"fourier"`` (the sine series), or ``"auto"``: images when 2 sqrt(G) <= H (few images
    and H -> inf exact), the series otherwise (few terms); both are summed to rounding."""
    p = np.asarray(pressures, dtype=float)
    H = float(hardness)
    c = 2.0 * math.sqrt(G)
    if not (c > 0 and H > 0):
        raise ValueError(f"G and the hardness must be positive; got G = {G!r}, H = {hardness!r}")
    if method == "auto":
        method = "images" if c <= H else "fourier"
    x = np.clip(p.ravel(), 0.0, H)
    if method == "images":
        m = np.arange(-(int(math.ceil(3 * c / H)) + 6), int(math.ceil(3 * c / H)) + 7)[:, None]
        plus, minus = x[None, :] + 2 * m * H, -x[None, :] + 2 * m * H
        el = np.sum(_erf_images(plus, c, H) - _erf_images(minus, c, H), axis=0)
        first = np.sum(_first_moment_images(plus, c, H) - _first_moment_images(minus, c, H), axis=0)
    elif method == "fourier":
        n = np.arange(1, int(math.ceil(8 * H / c)) + 6)[:, None]
        decay = np.exp(-((n * np.pi / H) ** 2) * G) * np.sin(n * np.pi * x[None, :] / H)
        el = np.sum(np.where(n % 2 == 1, 4.0 / (n * np.pi), 0.0) * decay, axis=0)
        first = H * np.sum(2.0 * (-1.0) ** (n + 1) / (n * np.pi) * decay, axis=0)
    else:
        raise ValueError(f"method must be 'auto', 'images' or 'fourier'; got {method!r}")
    plastic = np.maximum(x / H - first / H, 0.0)
    full = p.ravel() >= H
    return (np.where(full, 0.0, el).reshape(p.shape),
            np.where(full, 1.0, plastic).reshape(p.shape))


def persson_interface(q, C, contact_modulus: float, separations, *, hardness: float | None = None,
                      gamma: float = DEFAULT_GAMMA) -> xr.Dataset:
    """Persson's interface law at the mean gaps `separations` (module text).

    Parameters
    ----------
    q, C : the isotropic spectrum (rad/m, m^4), q increasing (:func:`isotropic_spectrum`).
    contact_modulus : E* = E / (1 - nu^2) of the elastic body (the flat rigid) (Pa).
    separations : mean gaps u (m, > 0); for an elastic body the boundary elements'
        separation (the flat's height above the mean plane).
    hardness : optional hardness H (Pa) of a perfectly plastic surface: Persson's
        elastoplastic areas; the pressure-gap relation stays elastic (module text).
    gamma : the energy correction of the mean-gap theory (Yang and Persson 2008).

    Returns
    -------
    xarray.Dataset on ``separation`` (increasing): nominal_pressure, contact_area_ratio,
    normal_stiffness (-dp/du), mean_gap, contact_count (NaN), plastic_area_ratio (with a
    hardness); attrs method, gradient_rms, contact_modulus, hardness, gamma,
    gap_decay_length (u0 of p ~ exp(-u/u0)).
    """
    q, C = _check_spectrum(q, C)
    if not contact_modulus > 0:
        raise ValueError(f"contact modulus must be positive; got {contact_modulus!r}")
    if hardness is not None and not hardness > 0:
        raise ValueError(f"hardness must be positive; got {hardness!r}")
    if not 0.0 <= gamma <= 1.0:
        raise ValueError(f"gamma must lie in [0, 1]; got {gamma!r}")
    u = np.sort(np.asarray(separations, dtype=float))
    if u.ndim != 1 or u.size == 0 or not np.all(np.isfinite(u)) or not np.all(u > 0):
        raise ValueError("separations must be a non-empty 1-D array of positive finite numbers")
    a, w, grad = _gap_terms(q, C)
    p = _pressure_at_gap(q, C, contact_modulus, u, gamma)
    _, dudp = mean_gap(q, C, contact_modulus, p, gamma=gamma)
    G = contact_modulus**2 * grad**2 / 8.0
    area = special.erf(p / (2.0 * math.sqrt(G)))
    data = {}
    if hardness is not None:
        elastic, plastic = elastoplastic_areas(p, G, hardness)
        area = elastic + plastic
        data["plastic_area_ratio"] = ("separation", plastic, attrs(
            "1", "plastically flowing area ratio A_pl/A0 (stress at the hardness), Persson 2001"))
    data.update({
        "nominal_pressure": ("separation", p, attrs("Pa", "nominal pressure (Persson's theory)")),
        "contact_area_ratio": ("separation", area, attrs(
            "1", "real contact area ratio A/A0 (Persson's theory; elastic + plastic with a hardness)")),
        "normal_stiffness": ("separation", -1.0 / dudp, attrs(
            "Pa/m", "normal stiffness per unit area -dp/du (Persson's theory)")),
        "mean_gap": ("separation", u.copy(), attrs(
            "m", "mean gap between the flat and the deformed surface (equals the separation)")),
        "contact_count": ("separation", np.full(u.size, np.nan), attrs(
            "1/m^2", "contacts per unit area: not given by Persson's theory (NaN)")),
    })
    ds = xr.Dataset(data, coords={"separation": ("separation", u, attrs(
        "m", "mean gap: height of the rigid flat above the mean plane of the surface"))})
    ds.attrs.update({
        "method": "Persson's theory: area, Persson J. Chem. Phys. 115 (2001) 3840 (elastoplastic "
                  "with a hardness); mean gap, Persson PRL 99 (2007) 125502 and Yang and Persson, "
                  "J. Phys. Condens. Matter 20 (2008) 215214",
        "gradient_rms": grad,
        "contact_modulus": float(contact_modulus),
        "hardness": float(hardness) if hardness is not None else np.nan,
        "gamma": float(gamma),
        "gap_decay_length": float(gamma * a.sum()),
    })
    return ds
