"""Is the surface Gaussian?  Skewness, kurtosis and the bearing-area curve of the heights.

The Nayak/Francis density of peaks (report 2.4.1) and Greenwood and
Williamson's model (7.1) assume Gaussian heights; the report (2.4.3) says
that surfaces of "non-Gaussian random distribution" need the peaks sampled
from a map instead.  Whether that applies is read off the height
distribution:

* skewness Sk = <z^3> / Rq^3 (ISO 4287 Rsk, ISO 25178 Ssk) and kurtosis
  Ku = <z^4> / Rq^4 (Rku, Sku), with Rq^2 = <z^2> and <> the mean over the
  defined points (heights about their mean); a Gaussian has 0 and 3;
* the bearing-area (Abbott-Firestone) curve: the height c below which a
  share 1 - mr of the surface lies, against the material ratio mr (the
  share of points at or above c), every 0.01 and, below 0.01, ten ratios a
  decade down to 1e-6, where the light-load contact lies
  (`bearing_heights`: the separations of a scene in unit ``bearing``).

The limits: the surface is called clearly non-Gaussian when |Sk| > 0.3, or
Ku < 2.5, or Ku > 4.  The light-load contact of an asperity model is the
upper tail of the heights, and Greenwood and Williamson's load integral
F_3/2(h) = int_h^inf (z - h)^(3/2) phi(z) dz is sensitive to it: at these
limits F_3/2 at a separation of 2 sigma is off by a factor of about 2 (1.9
for gamma-distributed heights with Sk = +0.3, 0.37 for Sk = -0.3; 1.9 for
Student-t heights with Ku = 4; 0.38 for symmetric beta heights with
Ku = 2.5) and at 1 sigma by 8 to 23 %.  Inside the limits the error shrinks
smoothly but is not zero (Sk = 0.1: 28 % at 2 sigma, 8 % at 1 sigma); the
warning marks where the light-load answer is off by a factor, not by a
fraction.  The limits are also outside the sampling scatter of a Gaussian
record: the standard errors of Sk and Ku are sqrt(6/N) and sqrt(24/N) for
N independent patches, 0.1 and 0.2 for N = 600.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SKEWNESS_LIMIT", "KURTOSIS_RANGE", "MATERIAL_RATIOS", "height_distribution", "gaussianity",
           "bearing_heights"]

SKEWNESS_LIMIT = 0.3
KURTOSIS_RANGE = (2.5, 4.0)
#: the material ratios of the bearing-area curve: every 0.01, and ten a decade below 0.01
MATERIAL_RATIOS = np.union1d(np.linspace(0.0, 1.0, 101), np.logspace(-6.0, -2.0, 41))


def height_distribution(z, defined=None) -> dict:
    """Skewness, kurtosis, rms height (1/n) and the bearing-area curve of the defined heights.

    Returns a dict with ``rms`` (Rq), ``skewness``, ``kurtosis``,
    ``material_ratio`` (`MATERIAL_RATIOS`) and ``bearing_height``
    (the height, about the mean, at which that share of the points is at
    or above it: the empirical quantile 1 - mr).
    """
    zz = np.asarray(z, dtype=np.float64)
    m = np.isfinite(zz) if defined is None else (np.asarray(defined, bool) & np.isfinite(zz))
    values = zz[m]
    if values.size < 2:
        raise ValueError("the height distribution needs at least 2 defined points")
    values = values - values.mean()
    v2 = values * values
    rq2 = float(v2.mean())
    if rq2 == 0.0:
        raise ValueError("all defined heights are equal: no roughness to describe")
    skew = float((v2 * values).mean()) / rq2**1.5
    kurt = float((v2 * v2).mean()) / rq2**2
    bearing = np.quantile(values, 1.0 - MATERIAL_RATIOS)
    return {"rms": rq2**0.5, "skewness": skew, "kurtosis": kurt,
            "material_ratio": MATERIAL_RATIOS.copy(), "bearing_height": bearing}


def gaussianity(skewness: float, kurtosis: float) -> tuple[bool, str]:
    """(True, "") for heights within the limits of the module text, else (False, why)."""
    why = []
    if abs(skewness) > SKEWNESS_LIMIT:
        why.append(f"skewness {skewness:.3g} beyond +-{SKEWNESS_LIMIT:g}")
    lo, hi = KURTOSIS_RANGE
    if not lo <= kurtosis <= hi:
        why.append(f"kurtosis {kurtosis:.3g} outside {lo:g} ... {hi:g}")
    return (not why), "; ".join(why)


def bearing_heights(material_ratio, bearing_height, ratios) -> np.ndarray:
    """The heights above which the shares `ratios` (0 < r <= 1) of a surface lie, from its
    bearing-area curve (`height_distribution`: `bearing_height` on `material_ratio`),
    interpolated linearly in the logarithm of the ratio between the curve's ratios."""
    mr = np.asarray(material_ratio, dtype=float)
    height = np.asarray(bearing_height, dtype=float)
    r = np.asarray(ratios, dtype=float)
    if np.any(~(r > 0)) or np.any(r > 1):
        raise ValueError(f"material ratios must lie in (0, 1]; got {r.tolist()}")
    if r.min() < mr[mr > 0].min():
        raise ValueError(f"material ratio {r.min():g} below the bearing-area curve's smallest, "
                         f"{mr[mr > 0].min():g}")
    keep = mr > 0
    return np.interp(np.log(r), np.log(mr[keep]), height[keep])
