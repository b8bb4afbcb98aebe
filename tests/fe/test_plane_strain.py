"""Plane-strain sections: the cylinder (Hertz line contact), the truncated V."""

import numpy as np
import pytest

from asperity.fe import Cylinder, LinearElastic, TruncatedV, solve_asperity
from asperity.fe.analytic import hertz_line_half_width

MAT = LinearElastic(1000.0, 0.3)


def test_cylinder_half_width_follows_hertz_line_contact():
    # b = sqrt(4 P R / (pi E')) holds whatever the block size (the approach
    # of a plane section depends on it logarithmically, the width does not)
    ds = solve_asperity(Cylinder(1.0), MAT, [0.001, 0.002, 0.005, 0.01, 0.02])
    b = hertz_line_half_width(1.0, MAT.E, MAT.nu, ds.force.values)
    np.testing.assert_allclose(ds.contact_radius.values, b, rtol=0.01)
    assert np.all(np.diff(ds.normal_stiffness.values) > 0)


def test_truncated_v_flat_top_acts_as_a_punch():
    v = TruncatedV(top_half_width=0.1, ridge_height=1.0)
    ds = solve_asperity(v, MAT, [0.001, 0.005, 0.01, 0.02], accuracy="draft")
    # the whole flat top touches at once and the contact stays at its corners
    np.testing.assert_allclose(ds.contact_radius.values, 0.1, rtol=1e-4)
    # linear response: force proportional to interference, constant stiffness
    F, w = ds.force.values, ds.interference.values
    np.testing.assert_allclose(F / w, F[0] / w[0], rtol=1e-3)
    np.testing.assert_allclose(ds.normal_stiffness.values, F[0] / w[0], rtol=1e-3)


def test_truncated_v_converges_with_accuracy():
    v = TruncatedV(top_half_width=0.1, ridge_height=1.0)
    forces = [solve_asperity(v, MAT, [0.01], accuracy=acc).force.item()
              for acc in ("draft", "standard", "fine")]
    assert abs(forces[1] / forces[2] - 1) < abs(forces[0] / forces[2] - 1)
    assert forces[1] == pytest.approx(forces[2], rel=0.005)
