"""The penalty's own error, measured against the exact option on one mesh."""

import numpy as np

from asperity.fe import CosineHill, LinearElastic, Paraboloid, penalty_error
from asperity.fe.contact.penalty import PENALTY_FACTOR

from .conftest import HERTZ_MATERIAL, HERTZ_W


def test_penalty_error_falls_as_the_penalty_stiffens():
    factors = (10.0, 100.0, PENALTY_FACTOR, 10 * PENALTY_FACTOR)
    ds = penalty_error(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W, accuracy="draft",
                       penalty_factors=factors)
    for name in ("force_error", "radius_error", "max_penetration"):
        err = np.abs(ds[name].values)  # (factor, step)
        assert np.all(np.diff(err, axis=0) <= 1e-12), name
        assert err[-1].max() < 0.2 * err[0].max()
    # about 1 / c: ten times stiffer, ten times smaller
    F = np.abs(ds.force_error.values)
    np.testing.assert_allclose(F[2] / F[1], 0.1, rtol=0.3)
    # the default is well below the discretization error (~1e-3)
    default = list(factors).index(PENALTY_FACTOR)
    assert np.abs(ds.force_error.values[default]).max() < 2e-4
    assert np.abs(ds.radius_error.values[default]).max() < 2e-4
    assert ds.max_penetration.values[default].max() < 1e-3
    # a penalty lets the body in: less force than exact contact
    assert np.all(ds.force_error.values < 0)
    for var in ds.variables.values():
        assert var.attrs["units"] and var.attrs["long_name"]


def test_penalty_error_on_a_cosine_hill():
    hill = CosineHill.from_aspect(13.4, 1.0)
    ds = penalty_error(hill, LinearElastic(1.0, 0.3), [0.01, 0.1, 0.3], accuracy="draft",
                       penalty_factors=(100.0, 1000.0))
    F = np.abs(ds.force_error.values)
    assert np.all(F[1] < F[0]) and F[1].max() < 1e-3
