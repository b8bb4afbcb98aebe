"""Intermediate unloading paths of one asperity by blending functions (report 8.3).

Report section 8.3 ("Studies of Unloading", seed text lines 2078-2138): because
asperity heights are random, every asperity of a surface is "caught" at a
different maximum interference when the surface starts to unload, so the
asperity model needs a whole *family* of unloading paths.  The report
(lines 2086-2089) therefore

(a) computes a few (three to four) unloading paths of the asperity in detail,
    starting from different maximum interferences w_max,i, and
(b) builds the path from any intermediate w_max with the "blending function
    formula" (lines 2089-2114): a transfinite (Coons) mapping of the unit
    square (s, t) in [0, 1]^2 onto a domain with four curvilinear sides
    gamma_1 = AB, gamma_2 = BC, gamma_3 = DC, gamma_4 = AD (figure 8.26),
    gamma_1, gamma_3 parametrized by s and gamma_2, gamma_4 by t, x the
    approaches (interference), y the contact forces::

        x(s,t) = x1(s)(1-t) + x2(t) s + x3(s) t + x4(t)(1-s)
                 - xA (1-t)(1-s) - xB (1-t) s - xC t s - xD t (1-s)

    and the same for y (unnumbered display equations after the caption of
    figure 8.25, lines 2110 and 2112; :func:`coons_patch`).

The four sides
--------------
Figure 8.26 itself is not in the text; it shows "contact force for an asperity
in terms of deformation during loading and unloading at three different
levels" (caption, line 2117), and line 2114 says that a curve gamma_0 "was
not generated but computed" and is compared with the blended family of
figure 8.27 -- i.e. (presumably the middle) one of the three computed paths
is a check, and the blend is spanned by the others.  So the two *outer*
computed unloading paths are two opposite sides, and the region between them
in the (interference, force) plane is closed by the loading curve (above) and
the zero-force axis (below).  We read
the corners as

    A = (w_r,lo, 0)        lowest path at zero force (its residual interference)
    B = (w_r,hi, 0)        highest path at zero force
    C = (w_max,hi, F_hi)   highest path's start, on the loading curve
    D = (w_max,lo, F_lo)   lowest path's start, on the loading curve

    gamma_1 = AB   zero-force line F = 0 between the two residual interferences
                   (the "residual-interference curve"), parameter s
    gamma_2 = BC   highest computed unloading path, parameter t
    gamma_3 = DC   loading curve between w_max,lo and w_max,hi, parameter s
    gamma_4 = AD   lowest computed unloading path, parameter t

The letters are our reading (the figure is missing); the Coons formula is
invariant under relabelling the corners of the square, so the blended paths
depend only on *which* four curves are the sides, which the text fixes.  A
blended unloading path is a curve s = const, t from 1 (on the loading curve,
at w_max) to 0 (on the zero-force line, at the residual interference).

Parametrizations (the report leaves them open, "given generally in the form"):

* s is linear in the maximum interference along the loading curve,
  x3(s) = w_max,lo + s (w_max,hi - w_max,lo), so the blended curve of
  parameter s starts exactly at w_max = x3(s) on the loading curve;
* on the zero-force side x1(s) = R(x3(s)), where R(w_max) interpolates the
  computed residual interferences w_r,i through *all* computed levels (monotone
  PCHIP by default, or piecewise linear).  Since y1 = 0, the Coons formula
  gives y(s, 0) = 0 and x(s, 0) = R(w_max): every blended path ends at zero
  force exactly at the interpolated residual interference
  (:func:`residual_interference`), consistently with the blend;
* along an unloading path (sides gamma_2, gamma_4) t is, by default
  (``param="force"``), the normalized force t = F / F(w_max,i); the path's
  interference is interpolated in t by a monotone PCHIP through the computed
  points.  Then y2(t) = t F_hi, y4(t) = t F_lo and the y-equation collapses to
  y(s, t) = t L(x3(s)), L the loading curve: the blended force is exactly the
  fraction t of the peak force, never negative, and increasing in t and
  (for an increasing loading curve) in w_max,
  while the x-equation blends the interference at equal force fraction,
  x(s,t) = x1(s)(1-t) + x3(s) t + s [x2(t) - chord] + (1-s) [x4(t) - chord].
  ``param="interference"`` instead uses t = (w - w_r,i)/(w_max,i - w_r,i),
  giving x(s,t) = x1(s)(1-t) + x3(s) t and
  y(s,t) = (1-s) F_lo(t) + s F_hi(t) + t [L(w_max) - (1-s) F_lo - s F_hi];
  with a convex loading curve the last term is negative and ~t, which can
  outweigh F ~ t^m near zero force, so the blended force may dip slightly
  below zero there (tests show -4e-4 of F_max for three computed levels).
  Hence "force" is the default.

With more than two computed paths the domain is split into adjacent
four-sided patches, one between each pair of consecutive computed levels
(the report notes that the agreement "improves with increasing number of
calculated unloading curves", line 2119); the family is continuous in
w_max and reproduces every computed path exactly.  The report remarks that
blended curves can also be generated outside ABCD (line 2114, extrapolation
in s); this
module refuses that and raises ValueError outside
[min w_max,i, max w_max,i].

The same machinery blends contact *area* (or any other response) versus
interference: pass area in place of force.  Units are arbitrary but must be
consistent.
"""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np


def _pchip(x, y, **options):
    """scipy's PchipInterpolator, imported on first use (most jobs never need it)."""
    from scipy.interpolate import PchipInterpolator

    return PchipInterpolator(x, y, **options)


__all__ = [
    "coons_patch",
    "UnloadingFamily",
    "blend_unloading",
    "residual_interference",
]


def coons_patch(gamma1, gamma2, gamma3, gamma4, s, t):
    """Blending-function (Coons) map of report 8.3 for one coordinate.

    ``gamma1(s)`` = AB, ``gamma2(t)`` = BC, ``gamma3(s)`` = DC, ``gamma4(t)`` = AD
    are callables on [0, 1]; the corners are taken as A = gamma1(0),
    B = gamma1(1), C = gamma3(1), D = gamma3(0).  ``s`` and ``t`` broadcast.
    Returns x(s, t) of the report's formula.
    """
    s = np.asarray(s, dtype=float)
    t = np.asarray(t, dtype=float)
    xa, xb = gamma1(0.0), gamma1(1.0)
    xd, xc = gamma3(0.0), gamma3(1.0)
    return (
        gamma1(s) * (1.0 - t)
        + gamma2(t) * s
        + gamma3(s) * t
        + gamma4(t) * (1.0 - s)
        - xa * (1.0 - t) * (1.0 - s)
        - xb * (1.0 - t) * s
        - xc * t * s
        - xd * t * (1.0 - s)
    )


def _as_curve(w, y, what):
    w = np.asarray(w, dtype=float).ravel()
    y = np.asarray(y, dtype=float).ravel()
    if w.shape != y.shape:
        raise ValueError(f"{what}: interference and force arrays differ in length "
                         f"({w.size} vs {y.size})")
    if w.size < 2:
        raise ValueError(f"{what}: need at least 2 points")
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(y))):
        raise ValueError(f"{what}: non-finite values")
    order = np.argsort(w, kind="stable")
    w, y = w[order], y[order]
    if np.any(np.diff(w) <= 0.0):
        raise ValueError(f"{what}: interference values must be distinct")
    return w, y


class _Path:
    """One computed unloading path: top w_max, residual w_r, force of t."""

    def __init__(self, w_max, w, f, index, param="force"):
        what = f"unloading path {index} (w_max={w_max!r})"
        w_max = float(w_max)
        if not np.isfinite(w_max):
            raise ValueError(f"{what}: w_max must be finite")
        w, f = _as_curve(w, f, what)
        span = max(w[-1] - w[0], abs(w_max), 1e-300)
        if w_max > w[-1] + 1e-9 * span or w_max < w[0]:
            raise ValueError(f"{what}: data cover w in [{w[0]!r}, {w[-1]!r}], "
                             f"which does not reach w_max")
        tol = 1e-9 * span
        near = np.abs(w - w_max) <= tol          # round-off: snap onto w_max
        if np.count_nonzero(near) > 1:
            raise ValueError(f"{what}: several points coincide with w_max")
        w = np.where(near, w_max, w)
        if w[-1] > w_max:  # data continue beyond w_max: cut there
            f_cut = np.interp(w_max, w, f)
            keep = w < w_max
            w, f = np.append(w[keep], w_max), np.append(f[keep], f_cut)
        f_top = f[-1]
        if not f_top > 0.0:
            raise ValueError(f"{what}: force at w_max must be positive")
        nonpos = np.nonzero(f <= 0.0)[0]
        if nonpos.size == 0:
            raise ValueError(f"{what}: path does not return to zero force")
        j = nonpos[-1]  # last point at or below zero force; j+1 is above
        if f[j] == 0.0:
            w_r = w[j]
        else:
            w_r = w[j] + (w[j + 1] - w[j]) * (-f[j]) / (f[j + 1] - f[j])
        if not w_r < w_max:
            raise ValueError(f"{what}: residual interference not below w_max")
        wu = np.concatenate(([w_r], w[j + 1:]))   # from zero force up to w_max
        fu = np.concatenate(([0.0], f[j + 1:]))
        self.w_max, self.w_r, self.f_top = w_max, float(w_r), float(f_top)
        self.param = param
        if param == "interference":
            tau = (wu - w_r) / (w_max - w_r)
            tau[-1] = 1.0
            self._f_of_t = _pchip(tau, fu, extrapolate=False)
        else:  # "force"
            if np.any(np.diff(fu) <= 0.0):
                raise ValueError(f"{what}: force must increase strictly with w between "
                                 f"the residual interference and w_max for "
                                 f"param='force' (use param='interference')")
            tau = fu / f_top
            tau[-1] = 1.0
            self._w_of_t = _pchip(tau, wu, extrapolate=False)

    def x(self, t):
        t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
        if self.param == "interference":
            return self.w_r + t * (self.w_max - self.w_r)
        return self._w_of_t(t)

    def y(self, t):
        t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
        if self.param == "interference":
            return self._f_of_t(t)
        return t * self.f_top


class UnloadingFamily:
    """Unloading paths of one asperity from any w_max in the computed range.

    Parameters
    ----------
    loading : (w, F) arrays of the loading branch, or a callable F(w).
    paths : sequence of (w_max_i, w_i, F_i), at least two computed unloading
        paths (the report uses three or four), distinct w_max_i, each running
        from w_max_i down to (at least) zero force.  Points may be in any order.
    residual : "pchip" (default, monotone cubic through all (w_max_i, w_r_i))
        or "linear" -- interpolation of the residual interference, i.e. the
        parametrization of the zero-force side gamma_1 = AB.
    param : "force" (default) or "interference" -- parametrization t of the
        unloading sides gamma_2, gamma_4 (see the module docstring).
    corner_rtol : allowed relative mismatch between a path's force at w_max_i
        and the loading curve there (corners C, D must lie on both sides).
    """

    def __init__(self, loading, paths: Sequence, *, residual: str = "pchip",
                 param: str = "force", corner_rtol: float = 1e-2):
        if param not in ("force", "interference"):
            raise ValueError(f"param must be 'force' or 'interference', got {param!r}")
        if residual not in ("pchip", "linear"):
            raise ValueError(f"residual must be 'pchip' or 'linear', got {residual!r}")
        if len(paths) < 2:
            raise ValueError("need at least two computed unloading paths "
                             "(the report uses three or four)")
        ps = [_Path(p[0], p[1], p[2], i, param) for i, p in enumerate(paths)]
        ps.sort(key=lambda p: p.w_max)
        wm = np.array([p.w_max for p in ps])
        if np.any(np.diff(wm) <= 0.0):
            raise ValueError("computed unloading paths must have distinct w_max")
        self.paths = ps
        self.levels = wm
        self.residuals = np.array([p.w_r for p in ps])

        if callable(loading):
            self._load: Callable = lambda w: np.asarray(loading(w), dtype=float)
        else:
            lw, lf = _as_curve(loading[0], loading[1], "loading curve")
            span = lw[-1] - lw[0]
            if lw[0] > wm[0] + 1e-12 * span or lw[-1] < wm[-1] - 1e-12 * span:
                raise ValueError(f"loading curve covers w in [{lw[0]!r}, {lw[-1]!r}] "
                                 f"but the computed levels span [{wm[0]!r}, {wm[-1]!r}]")
            interp = _pchip(lw, lf, extrapolate=True)
            self._load = lambda w: interp(np.asarray(w, dtype=float))
        f_load = self._load(wm)
        f_top = np.array([p.f_top for p in ps])
        bad = np.abs(f_top - f_load) > corner_rtol * np.abs(f_load)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise ValueError(f"unloading path from w_max={wm[i]!r} starts at force "
                             f"{f_top[i]!r} but the loading curve gives {f_load[i]!r} "
                             f"(corner mismatch above corner_rtol={corner_rtol})")

        if residual == "pchip":
            self._res = _pchip(wm, self.residuals, extrapolate=False)
        else:
            self._res = lambda w: np.interp(w, wm, self.residuals)

    @property
    def w_range(self):
        """(smallest, largest) computed maximum interference."""
        return float(self.levels[0]), float(self.levels[-1])

    def _check(self, w_max):
        w_max = np.asarray(w_max, dtype=float)
        lo, hi = self.w_range
        if w_max.ndim > 1:
            raise ValueError("w_max must be a scalar or a 1-D array")
        if not np.all(np.isfinite(w_max)) or np.any((w_max < lo) | (w_max > hi)):
            raise ValueError(f"w_max must lie in the computed range [{lo!r}, {hi!r}] "
                             f"(smallest and largest computed unloading levels); "
                             f"got {w_max.tolist()!r}")
        return w_max

    def residual(self, w_max):
        """Residual interference (force back to zero) of the blended path(s)."""
        w_max = self._check(w_max)
        return np.asarray(self._res(w_max), dtype=float)[()]

    def blend(self, w_max, t=None, n: int = 101):
        """(w, F) of the unloading path(s) from ``w_max``.

        ``t`` (default ``linspace(0, 1, n)``) are the normalized positions along
        the path: t = 0 at the residual interference (F = 0), t = 1 at w_max on
        the loading curve; w increases with t.  Scalar ``w_max`` gives 1-D
        arrays of len(t); a 1-D ``w_max`` gives arrays of shape (len(w_max),
        len(t)), one blended path per row.
        """
        w_max = self._check(w_max)
        scalar = w_max.ndim == 0
        wm = np.atleast_1d(w_max)
        if t is None:
            t = np.linspace(0.0, 1.0, int(n))
        t = np.asarray(t, dtype=float).ravel()
        if t.size == 0 or np.any((t < 0.0) | (t > 1.0)) or not np.all(np.isfinite(t)):
            raise ValueError("t must be non-empty and lie in [0, 1]")
        levels = self.levels
        # patch k lies between computed levels k and k+1
        k = np.clip(np.searchsorted(levels, wm, side="right") - 1, 0, levels.size - 2)
        w_out = np.empty((wm.size, t.size))
        f_out = np.empty((wm.size, t.size))
        for kk in np.unique(k):
            sel = k == kk
            lo_p, hi_p = self.paths[kk], self.paths[kk + 1]
            w_lo, dw = levels[kk], levels[kk + 1] - levels[kk]
            s = ((wm[sel] - w_lo) / dw)[:, None]
            # side x-coordinates (approaches) and y-coordinates (forces)
            x1 = lambda ss: self._res(w_lo + np.asarray(ss) * dw)      # AB, F = 0
            x3 = lambda ss: w_lo + np.asarray(ss) * dw                  # DC, loading
            y1 = lambda ss: np.zeros_like(np.asarray(ss, dtype=float))  # AB
            y3 = lambda ss: self._load(w_lo + np.asarray(ss) * dw)      # DC
            w_out[sel] = coons_patch(x1, hi_p.x, x3, lo_p.x, s, t[None, :])
            f_out[sel] = coons_patch(y1, hi_p.y, y3, lo_p.y, s, t[None, :])
        if scalar:
            return w_out[0], f_out[0]
        return w_out, f_out


def blend_unloading(loading, paths, w_max, *, t=None, n: int = 101,
                    residual: str = "pchip", param: str = "force",
                    corner_rtol: float = 1e-2):
    """Unloading path(s) from ``w_max`` blended from computed paths (report 8.3).

    ``loading`` = (w, F) of the loading branch (or a callable F(w));
    ``paths`` = list of (w_max_i, w_i, F_i) computed unloading paths (three or
    four in the report; at least two).  Returns (w, F), ascending in w from the
    residual interference (F = 0) to w_max (F on the loading curve); see
    :meth:`UnloadingFamily.blend` for ``t``/``n`` and the shapes for an array
    of ``w_max``.  ValueError if ``w_max`` is outside
    [min w_max_i, max w_max_i].
    """
    fam = UnloadingFamily(loading, paths, residual=residual, param=param,
                          corner_rtol=corner_rtol)
    return fam.blend(w_max, t=t, n=n)


def residual_interference(loading, paths, w_max, *, residual: str = "pchip",
                          param: str = "force", corner_rtol: float = 1e-2):
    """Residual interference of the blended unloading path(s) from ``w_max``.

    Equals the end point x(s, 0) of :func:`blend_unloading` (gamma_1 = AB).
    """
    fam = UnloadingFamily(loading, paths, residual=residual, param=param,
                          corner_rtol=corner_rtol)
    return fam.residual(w_max)


# ------------------------------------------------------------------ pipeline


#: corners C, D of a computed path may miss the gathered loading curve by this:
#: the paths' loading branches share one mesh but not their time steps (each job
#: caps its steps relative to its own maximum interference), and at `draft` the
#: backward-Euler error of the coarser steps of the largest level reaches ~4 %.
#: The largest mismatch is recorded in unloading.nc (``corner_mismatch``).
CORNER_RTOL = 0.1


def _rowwise_interp(x: np.ndarray, y: np.ndarray, targets: np.ndarray | None,
                    row_targets: np.ndarray | None = None) -> np.ndarray:
    """np.interp row by row, vectorized: x, y (n, m) with x non-decreasing in each
    row, at `targets` (p,) shared by all rows or `row_targets` (n, p) -> (n, p)
    (clamped at the row ends)."""
    n, m = x.shape
    tg = np.broadcast_to(targets[None, :], (n, targets.size)) if row_targets is None else row_targets
    span = float(np.nanmax(x) - np.nanmin(x)) + float(np.nanmax(tg) - np.nanmin(tg)) + 1.0
    offset = (np.arange(n) * 3.0 * span)[:, None]
    base = min(float(np.nanmin(x)), float(np.nanmin(tg)))
    xx = (x - base + offset).ravel()
    tt = (tg - base + offset)
    j = np.clip(np.searchsorted(xx, tt.ravel()) - 1, 0, xx.size - 2).reshape(tt.shape)
    row0 = (np.arange(n) * m)[:, None]
    j = np.clip(j, row0, row0 + m - 2)
    x0, x1 = xx[j], xx[j + 1]
    y0, y1 = y.ravel()[j], y.ravel()[j + 1]
    a = np.clip((tt - x0) / np.where(x1 > x0, x1 - x0, 1.0), 0.0, 1.0)
    return y0 + a * (y1 - y0)


def family_table(asperities, n_t: int = 201):
    """The blended unloading family of every curvature, for every maximum interference (8.3).

    From the computed paths of ``asperities.nc`` (`asperity.population.gather.gather`:
    ``unloading_interference``/``_force``/``_contact_area`` on (curvature,
    unloading_level, point)) and its loading curves: for every maximum
    interference w_max of the grid, the unloading path as points
    t = 0 .. 1 (``path_interference``, ``path_force``,
    ``path_contact_area`` on dims curvature, maximum_interference,
    path_point), from the residual interference (F = 0, t = 0) up to w_max
    (on the loading curve, t = 1).  Paths are kept as curves rather than on
    the interference grid: an unloading path spans a few per cent of
    w_max, finer than any grid spacing.

    Below the smallest computed level (``lowest_level``) the asperity is
    taken to unload along its loading curve (elastic rebound of a barely
    yielded tip); above the largest (``highest_level``) the largest path
    is shifted to start at w_max and scaled to the loading force there
    (extrapolation: the extra flattening taken as permanent).  A path
    marked ``left_out`` is not blended but compared with the blend from its
    level (``check_force_error``: largest force difference at equal
    interference over its largest force; ``check_residual_error``:
    difference of residual interferences over w_max).
    """
    import xarray as xr

    grid = asperities["interference"].values
    w_max = grid[grid > 0]
    curv = asperities["curvature"].values
    nk, nm = curv.size, w_max.size
    t = np.linspace(0.0, 1.0, n_t)
    out = {name: np.full((nk, nm, n_t), np.nan) for name in ("interference", "force", "contact_area")}
    f_err = np.full(nk, np.nan)
    r_err = np.full(nk, np.nan)
    lowest = np.full(nk, np.nan)
    highest = np.full(nk, np.nan)
    mismatch = np.full(nk, np.nan)
    for i in range(nk):  # one family per curvature; everything inside is vectorized over w_max
        loads = {v: asperities[v].isel(height=0, curvature=i).values[grid > 0]
                 for v in ("force", "contact_area")}
        W = asperities["unloading_interference"].values[i]
        level = asperities["maximum_interference"].values[i]
        left = asperities["left_out"].values[i]
        use = np.isfinite(level) & ~left
        fams = {}
        for v, var in (("force", "unloading_force"), ("contact_area", "unloading_contact_area")):
            Y = asperities[var].values[i]
            paths = [(level[j], W[j][np.isfinite(W[j])], Y[j][np.isfinite(W[j])])
                     for j in np.flatnonzero(use)]
            # the area need not fall strictly with the force: parametrized by interference
            fams[v] = UnloadingFamily((w_max, loads[v]), paths, corner_rtol=CORNER_RTOL,
                                      param="force" if v == "force" else "interference")
        lo, hi = fams["force"].w_range
        lowest[i], highest[i] = lo, hi
        ok = np.flatnonzero(use)
        tops = np.array([np.nanmax(asperities["unloading_force"].values[i, j]) for j in ok])
        load_at = _pchip(w_max, loads["force"])(level[ok])  # as the family does
        mismatch[i] = float(np.max(np.abs(tops / load_at - 1)))
        inside = (w_max >= lo) & (w_max <= hi)
        wb, fb = fams["force"].blend(w_max[inside], t=t)
        out["interference"][i, inside], out["force"][i, inside] = wb, fb
        # the area path on the force path's interferences
        wa, ya = fams["contact_area"].blend(w_max[inside], t=t)
        out["contact_area"][i, inside] = _rowwise_interp(wa, ya, None, wb)
        below = w_max < lo  # reversible: back along the loading curve
        wl = t[None, :] * w_max[below][:, None]
        out["interference"][i, below] = wl
        for v in ("force", "contact_area"):
            out[v][i, below] = np.interp(wl, w_max, loads[v], left=0.0)
        beyond = w_max > hi  # the largest path shifted and scaled
        if beyond.any():
            top = np.flatnonzero(inside)[-1]
            shift = w_max[beyond] - hi
            out["interference"][i, beyond] = out["interference"][i, top][None, :] + shift[:, None]
            for v in ("force", "contact_area"):
                scale = loads[v][beyond] / max(loads[v][top], np.finfo(float).tiny)
                out[v][i, beyond] = out[v][i, top][None, :] * scale[:, None]
        check = np.flatnonzero(left & np.isfinite(level))
        if check.size:
            j = int(check[0])
            ok = np.isfinite(W[j])
            wc, fc = W[j][ok], asperities["unloading_force"].values[i, j][ok]
            wbj, fbj = fams["force"].blend(level[j], t=t)
            mask = wc >= wbj[0]
            if mask.any():
                f_err[i] = float(np.max(np.abs(np.interp(wc[mask], wbj, fbj) - fc[mask])) / fc.max())
            res = asperities["residual_interference"].values[i, j]
            r_err[i] = float(abs(fams["force"].residual(level[j]) - res) / level[j])
    dims = ("curvature", "maximum_interference", "path_point")
    ds = xr.Dataset(
        {
            "path_interference": (dims, out["interference"], {"units": "m", "long_name": "interference along the unloading path from maximum_interference"}),
            "path_force": (dims, out["force"], {"units": "N", "long_name": "contact force along the unloading path"}),
            "path_contact_area": (dims, out["contact_area"], {"units": "m^2", "long_name": "real contact area along the unloading path"}),
            "lowest_level": ("curvature", lowest, {"units": "m", "long_name": "smallest computed unloading level (below it: unloading along the loading curve)"}),
            "highest_level": ("curvature", highest, {"units": "m", "long_name": "largest computed unloading level (above it: its path shifted, extrapolated)"}),
            "corner_mismatch": ("curvature", mismatch, {"units": "1", "long_name": "largest relative difference between a computed path's peak force and the loading curve at its level"}),
            "check_force_error": ("curvature", f_err, {"units": "1", "long_name": "largest force error of the blend against the left-out computed path, over its largest force"}),
            "check_residual_error": ("curvature", r_err, {"units": "1", "long_name": "residual interference error of the blend against the left-out path, over its w_max"}),
        },
        coords={
            "curvature": ("curvature", curv, {"units": "1/m", "long_name": "tip curvature"}),
            "maximum_interference": ("maximum_interference", w_max, {"units": "m", "long_name": "interference from which the asperity unloads"}),
            "path_point": ("path_point", t, {"units": "1", "long_name": "position t along a path: 0 at zero force, 1 at the maximum interference"}),
        },
    )
    ds["residual_interference"] = ds["path_interference"].isel(path_point=0, drop=True).assign_attrs(
        units="m", long_name="interference where the unloading path returns to zero force")
    for v in ("unloading_interference", "unloading_force", "unloading_contact_area",
              "maximum_interference", "residual_interference", "left_out"):
        src = asperities[v]
        ds[f"computed_{v}"] = (tuple(f"computed_{d}" if d in ("unloading_level", "point") else d
                                     for d in src.dims), src.values, dict(src.attrs))
    for d in ("unloading_level", "point"):
        ds = ds.assign_coords({f"computed_{d}": (f"computed_{d}", asperities[d].values, dict(asperities[d].attrs))})
    ds.attrs["blend"] = ("Coons patch of report 8.3 between consecutive computed unloading paths, "
                         "force-fraction parametrization; below the smallest level the loading curve")
    return ds


def unloading_asperities(table, heights: np.ndarray, unloading_from: float, separation: float):
    """Unloading responses on (height, curvature) at `separation` [m] when the
    interface unloads from `unloading_from` [m] (report 8.3: each asperity is
    caught at its own stage).

    The asperity of peak height z was pressed to w_max = z - unloading_from
    and is now at w = z - separation = w_max - (separation - unloading_from);
    its force and area come from the family's path from w_max (linear in
    w_max between the table's rows at equal t).  Returned as a table on
    (height, curvature, interference) constant along interference (two
    points, 0 and 1), the form `homogenize.interface_response` takes; with
    ``in_contact`` (1 where the force is positive) for the contact count.
    """
    import xarray as xr

    heights = np.asarray(heights, float)
    grid = table["maximum_interference"].values
    wm = heights - unloading_from
    j = np.clip(np.searchsorted(grid, wm) - 1, 0, grid.size - 2)
    a = np.clip((wm - grid[j]) / (grid[j + 1] - grid[j]), 0.0, 1.0)[None, :, None]

    def at(v):  # (curvature, height, t)
        x = table[v].values
        return (1 - a) * x[:, j, :] + a * x[:, j + 1, :]

    pw = at("path_interference")
    nk, nh, nt = pw.shape
    w = (wm - (separation - unloading_from))[None, :].repeat(nk, 0).reshape(-1, 1)
    rows = pw.reshape(-1, nt)
    data = {}
    for v, name in (("path_force", "force"), ("path_contact_area", "contact_area")):
        y = _rowwise_interp(rows, at(v).reshape(-1, nt), None, w)[:, 0]
        y = np.where((w[:, 0] < rows[:, 0]) | (w[:, 0] <= 0), 0.0, y)
        data[name] = y.reshape(nk, nh).T
    data["in_contact"] = (data["force"] > 0).astype(float)
    attrs = {"force": ("N", "contact force on unloading"), "contact_area": ("m^2", "real contact area on unloading"),
             "in_contact": ("1", "1 where the asperity still presses the flat")}
    return xr.Dataset(
        {k: (("height", "curvature", "interference"), np.repeat(v[:, :, None], 2, axis=2),
             {"units": attrs[k][0], "long_name": attrs[k][1]}) for k, v in data.items()},
        coords={"height": ("height", heights, {"units": "m", "long_name": "asperity peak height"}),
                "curvature": table["curvature"].copy(),
                "interference": ("interference", [0.0, 1.0], {"units": "m", "long_name": "interference (the response is constant along it)"})})
