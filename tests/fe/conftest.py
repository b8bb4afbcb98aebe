"""Shared runs of the finite element model (computed once per session)."""

from __future__ import annotations

import pytest

from asperity.fe import LinearElastic, Paraboloid, Sphere, solve_asperity

#: report 6.1: R = 1, E = 1000, nu = 0.3
HERTZ_W = (0.001, 0.002, 0.005, 0.01, 0.02)
HERTZ_MATERIAL = LinearElastic(1000.0, 0.3)


@pytest.fixture(scope="session")
def hertz_standard():
    """The paraboloid (Hertz's idealization) at the standard preset."""
    return solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W, accuracy="standard")


@pytest.fixture(scope="session")
def sphere_standard():
    return solve_asperity(Sphere(1.0), HERTZ_MATERIAL, HERTZ_W, accuracy="standard")
