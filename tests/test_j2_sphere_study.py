"""The boundary-element paraboloid of the J2 sphere study (asperity.studies.j2_sphere)."""

from __future__ import annotations

import numpy as np

from asperity.studies.j2_sphere import _hardness_paraboloid


def test_the_paraboloid_is_hertz_without_hardness_and_flows_with_it():
    """Unlimited, the paraboloid's force and area are Hertz's, 4/3 E* R^1/2 w^3/2 and
    pi R w (within 3 % on 128 x 128 cells, in both windows and in the order asked);
    limited by H, its force lies between 0.8 H A and H A at w = R/4, where nearly all the
    contact flows."""
    R, modulus, w_over_r = 1e-6, 1e11, np.array([0.1, 0.002, 0.01])  # not in order
    force, area = _hardness_paraboloid(R, w_over_r, modulus, np.inf, 128)
    w = w_over_r * R
    np.testing.assert_allclose(force, 4 / 3 * modulus * np.sqrt(R) * w**1.5, rtol=0.03)
    np.testing.assert_allclose(area, np.pi * R * w, rtol=0.03)
    H = 1e9
    f, a = _hardness_paraboloid(R, [0.25], modulus, H, 128)
    assert 0.8 * H * a[0] < f[0] <= H * a[0] * (1 + 1e-9)
