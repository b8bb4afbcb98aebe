"""Gaussian filters of ISO 16610-21 (profiles) and ISO 16610-61 (maps).

The roughness the asperity model sees is a band of wavelengths: longer
waves (waviness) do not form asperities of the size the model resolves, and
shorter ones (instrument noise, the stylus tip) are not surface.  The
Gaussian filter separates them without phase shift.  Its weighting function
is

    s(x) = 1 / (alpha lambda_c) exp(-pi (x / (alpha lambda_c))^2),
    alpha = sqrt(ln 2 / pi),

so the mean line passes a wave of wavelength lambda with amplitude
exp(-pi (alpha lambda_c / lambda)^2): exactly 50 % at the cut-off
wavelength lambda_c.  The roughness is the height less the mean line
(transmission 1 - that).  A short-wavelength cut-off lambda_s applies the
same filter with lambda_s and keeps its mean line.  The areal filter of ISO
16610-61 is the product s(x) s(y): the same transmission for a wave of
wavelength lambda in any direction.

Discretization: the weights are s sampled at the grid and truncated at
+-lambda_c, then normalized to sum 1 (ISO allows truncation at
+-lambda_c/2, where the weight is still 2.8 % of the peak: the mean
line's transmission at the cut-off becomes 51.1 %; at +-lambda_c the
weight is 7e-7 of the peak and the transmission 50 % to 1e-7).  Near an
undefined point or an end of the record the mean line is the normalized
convolution sum s(x - x') h(x') / sum s(x - x') over defined points x'
only (a zero-order end correction); the first and last lambda_c / 2 of
the record (the run-in and run-out of ISO 16610-21, where the weighting
function is cut in half) are dropped from the evaluation, and between
lambda_c / 2 and lambda_c from an end the cut tail of the kernel shifts
the transmission by a few 1e-5.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["ALPHA", "gaussian_weights", "mean_line", "transmission", "evaluation_margin", "filter_heights"]

ALPHA = math.sqrt(math.log(2.0) / math.pi)
TRUNCATION = 1.0  # weights kept for |x| <= TRUNCATION * cutoff


def transmission(wavelength, cutoff: float):
    """Amplitude transmission of the Gaussian mean line at ``wavelength`` (closed form)."""
    return np.exp(-np.pi * (ALPHA * cutoff / np.asarray(wavelength, dtype=np.float64)) ** 2)


def gaussian_weights(cutoff: float, spacing: float) -> np.ndarray:
    """The sampled, truncated and normalized weighting function of ISO 16610-21."""
    if not (cutoff > 0 and spacing > 0):
        raise ValueError(f"cut-off and spacing must be positive; got {cutoff!r}, {spacing!r}")
    half = int(math.floor(TRUNCATION * cutoff / spacing))
    x = spacing * np.arange(-half, half + 1)
    w = np.exp(-np.pi * (x / (ALPHA * cutoff)) ** 2)
    return w / w.sum()


def _convolve(a: np.ndarray, weights: np.ndarray, axis: int) -> np.ndarray:
    """Convolution along one axis with zeros beyond the ends ('same' size)."""
    import scipy.signal

    shape = [1] * a.ndim
    shape[axis] = weights.size
    if weights.size == 1:
        return a * weights[0]
    return scipy.signal.oaconvolve(a, weights.reshape(shape), mode="same", axes=axis)


def mean_line(z, cutoff: float, spacing, defined=None) -> np.ndarray:
    """The Gaussian mean line (profile) or mean surface (map) of the defined heights.

    ``spacing`` is dx for a profile and (dx, dy) for a map with
    ``z[i, j] = z(x = j dx, y = i dy)``.  NaN where no defined point lies
    within the truncated weighting function.
    """
    zz = np.asarray(z, dtype=np.float64)
    mask = np.isfinite(zz) if defined is None else (np.asarray(defined, bool) & np.isfinite(zz))
    steps = np.atleast_1d(np.asarray(spacing, dtype=np.float64))
    axes = [(0, float(steps[0]))] if zz.ndim == 1 else [(1, float(steps[0])), (0, float(steps[-1]))]
    num = np.where(mask, zz, 0.0)
    den = mask.astype(np.float64)
    smallest = 1.0  # the least weight one defined point can carry
    for axis, h in axes:  # x then y: the areal filter is the product of the profile filters
        w = gaussian_weights(cutoff, h)
        num, den = _convolve(num, w, axis), _convolve(den, w, axis)
        smallest *= w.min()
    # den is a sum of positive weights; FFT round-off leaves ~1e-16 where it is empty
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0.5 * smallest, num / den, np.nan)


def evaluation_margin(cutoff: float | None, spacing: float) -> int:
    """Points dropped at each end: the run-in / run-out of lambda_c / 2."""
    if cutoff is None:
        return 0
    return int(math.ceil(0.5 * cutoff / spacing - 1e-9))


def filter_heights(z, spacing, lambda_c: float | None = None, lambda_s: float | None = None,
                   defined=None) -> tuple[np.ndarray, np.ndarray, tuple[slice, ...]]:
    """Roughness between lambda_s and lambda_c, the long-wave part removed, and the
    evaluation region.

    Returns ``(roughness, waviness, region)``: roughness = (mean line at
    lambda_s, or the heights) - (mean line at lambda_c, or 0), NaN at
    undefined points; waviness = the lambda_c mean line (zeros without
    lambda_c); ``region`` the slices (one per axis) of the evaluation
    region, lambda_c / 2 (the larger cut-off's half) in from every end.
    """
    zz = np.asarray(z, dtype=np.float64)
    mask = np.isfinite(zz) if defined is None else (np.asarray(defined, bool) & np.isfinite(zz))
    if lambda_c is not None and lambda_s is not None and not lambda_s < lambda_c:
        raise ValueError(f"lambda_s ({lambda_s!r} m) must be shorter than lambda_c ({lambda_c!r} m)")
    steps = np.atleast_1d(np.asarray(spacing, dtype=np.float64))
    axis_steps = [float(steps[0])] if zz.ndim == 1 else [float(steps[-1]), float(steps[0])]  # (y, x)
    primary = zz if lambda_s is None else mean_line(zz, lambda_s, spacing, mask)
    waviness = np.zeros_like(zz) if lambda_c is None else mean_line(zz, lambda_c, spacing, mask)
    roughness = np.where(mask, primary - waviness, np.nan)
    widest = lambda_c if lambda_c is not None else lambda_s
    region = tuple(slice(evaluation_margin(widest, h), n - evaluation_margin(widest, h))
                   for n, h in zip(zz.shape, axis_steps))
    return roughness, waviness, region
