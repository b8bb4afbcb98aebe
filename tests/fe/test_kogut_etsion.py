"""The J2 sphere against a published reference: Kogut and Etsion's finite element fits of
the elastic-plastic sphere pressed by a rigid flat (asperity.references.kogut_etsion)."""

from __future__ import annotations

import numpy as np
import pytest

from asperity import fe
from asperity.fe.drivers.inelastic import History
from asperity.references.hertz import hertz_response, plane_strain_modulus
from asperity.references.kogut_etsion import critical_interference, kogut_etsion

E, NU, Y, R = 70e9, 0.33, 280e6, 1e-6  # the aluminum of the reference scenes, E / Y = 250
E_STAR = float(plane_strain_modulus(E, NU))


def test_the_fits_are_hertz_below_yield_and_the_papers_pieces():
    """Below w_c the fits are Hertz's sphere (1e-12); at 1 and 6 w_c they step as the
    paper's coefficients do (force x 1.03 and x 1.40 / 1.03 6^-0.162; 1e-6), and past
    110 w_c there is no fit."""
    wc = critical_interference(R, E_STAR, NU, Y)
    below = np.array([0.2, 0.7]) * wc
    out = kogut_etsion(below, R, E_STAR, NU, Y)
    hertz = hertz_response(below, 1.0 / R, E_STAR, 0.0)
    np.testing.assert_allclose(out["force"], hertz["force"], rtol=1e-12)
    np.testing.assert_allclose(out["contact_area"], hertz["contact_area"], rtol=1e-12)
    for x, step in ((1.0, 1.03), (6.0, 1.40 / 1.03 * 6.0 ** (1.263 - 1.425))):
        left, right = kogut_etsion(np.array([x * (1 - 1e-12), x * (1 + 1e-12)]) * wc, R, E_STAR, NU, Y)["force"]
        assert right / left == pytest.approx(step, rel=1e-6), x
    assert np.isnan(kogut_etsion(120 * wc, R, E_STAR, NU, Y)["force"])


@pytest.mark.parametrize("accuracy", ["draft", pytest.param("standard", marks=pytest.mark.slow)])
def test_the_j2_sphere_follows_kogut_and_etsion(accuracy):
    """The axisymmetric J2 sphere pressed to 300 w_c (its first step 0.6 w_c, its mesh
    adapted from 3 w_c): force and area within 5 % of Kogut and Etsion's fits from 2 to
    50 w_c, their fits' own accuracy against their finite elements (a few per cent) and
    ours (draft and standard differ by 1 %). Measured: force -3.6 to +1.4 %, area -0.4 to
    +4.6 %; at 100 w_c, the end of their middle range, the force is 6-7 % below theirs."""
    wc = critical_interference(R, E_STAR, NU, Y)
    top = 300 * wc
    ds = fe.solve_asperity_history(fe.Sphere(R), fe.J2Plasticity(E, NU, Y), History((0.0, 1.0), (0.0, top)),
                                   accuracy=accuracy, mesh_levels=np.geomspace(0.01 * top, top, 6),
                                   initial_time_step=2e-3)
    w = np.array([2, 4, 6, 10, 20, 50]) * wc
    ref = kogut_etsion(w, R, E_STAR, NU, Y)
    force = np.interp(w, ds["interference"].values, ds["force"].values)
    area = np.interp(w, ds["interference"].values, ds["contact_area"].values)
    np.testing.assert_allclose(force, ref["force"], rtol=0.05)
    np.testing.assert_allclose(area, ref["contact_area"], rtol=0.05)


def test_a_population_job_resolves_the_onset_of_yield():
    """A finite element job of a population presses its sphere to R / 4, 2,900 w_c of this
    aluminum, its first step 1e-4 of that (0.29 w_c): its mesh is adapted from w_c
    (`asperity.population.kinds.inelastic.mesh_levels`, 9 levels; 6 from a hundredth of
    the range for a body without a yield stress), and its force is within 5 % of Kogut
    and Etsion's from 1 to 50 w_c (from a hundredth of the range, 29 w_c, it was 0.81 and
    1.14 of theirs at 1 and 2 w_c)."""
    from asperity.population.kinds.inelastic import FIRST_STEP, mesh_levels
    from asperity.scene import Material

    wc = critical_interference(R, E_STAR, NU, Y)
    top = R / 4
    body = Material(model="j2", youngs_modulus=E, poisson=NU, yield_stress=Y)
    levels = mesh_levels(top, 1.0 / R, body)
    assert levels[0] == pytest.approx(wc, rel=1e-12) and levels.size == 9
    assert mesh_levels(top, 1.0 / R, Material(model="elastic", youngs_modulus=E, poisson=NU)).size == 6
    ds = fe.solve_asperity_history(fe.Sphere(R), fe.J2Plasticity(E, NU, Y), History((0.0, 1.0), (0.0, top)),
                                   accuracy="draft", mesh_levels=levels, initial_time_step=FIRST_STEP)
    w = np.array([1, 2, 4, 6, 10, 20, 50]) * wc
    force = np.interp(w, ds["interference"].values, ds["force"].values)
    np.testing.assert_allclose(force, kogut_etsion(w, R, E_STAR, NU, Y)["force"], rtol=0.05)
