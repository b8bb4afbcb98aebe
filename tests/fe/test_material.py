"""Linear isotropic elasticity at quadrature points."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from asperity.fe import LinearElastic
from asperity.fe.materials.elastic import METRIC, complementary_energy_density, equivalent_strain, von_mises


def test_uniaxial_stress():
    mat = LinearElastic(E=210e9, nu=0.3)
    s = 1e8
    strain = np.array([s / mat.E, -mat.nu * s / mat.E, -mat.nu * s / mat.E, 0.0])
    stress, D = mat.response(strain)
    np.testing.assert_allclose(stress, [s, 0, 0, 0], atol=1e-6 * s)
    assert D.shape == (4, 4)
    assert von_mises(stress) == pytest.approx(s)


def test_pure_shear():
    mat = LinearElastic(E=3.0, nu=0.25)
    lam, mu = mat.lame
    gamma = 1e-3  # engineering shear, tensor component gamma / 2
    stress, _ = mat.response(np.array([0, 0, 0, gamma / 2]))
    assert stress[3] == pytest.approx(mu * gamma)
    assert von_mises(stress) == pytest.approx(math.sqrt(3) * mu * gamma)
    assert equivalent_strain(np.array([0, 0, 0, gamma / 2])) == pytest.approx(gamma / math.sqrt(3))


@settings(max_examples=50, deadline=None)
@given(e=st.lists(st.floats(-1e-2, 1e-2), min_size=4, max_size=4),
       nu=st.floats(-0.9, 0.49), E=st.floats(1e-3, 1e12))
def test_energy_identities(e, nu, E):
    mat = LinearElastic(E, nu)
    strain = np.array(e)
    stress, D = mat.response(strain)
    work = np.sum(METRIC * stress * strain)
    assert complementary_energy_density(mat, stress[:, None])[0] == pytest.approx(work, rel=1e-7, abs=1e-300)
    assert work >= -1e-12 * E * np.sum(strain**2)  # positive definite
    # tangent symmetric in the work product
    MD = METRIC[:, None] * D
    np.testing.assert_allclose(MD, MD.T * 1.0, rtol=1e-12)


def test_contact_modulus_and_validation():
    mat = LinearElastic(1000.0, 0.3)
    assert mat.contact_modulus == pytest.approx(1000 / 0.91)
    assert mat.yield_stress == math.inf
    with pytest.raises(ValueError):
        LinearElastic(-1.0, 0.3)
    with pytest.raises(ValueError):
        LinearElastic(1.0, 0.5)
    with pytest.raises(ValueError):
        LinearElastic(1.0, 0.3, yield_stress=0.0)


def test_volumetric_strain_has_no_equivalent_strain():
    assert equivalent_strain(np.array([1e-3, 1e-3, 1e-3, 0.0])) == pytest.approx(0.0, abs=1e-18)
