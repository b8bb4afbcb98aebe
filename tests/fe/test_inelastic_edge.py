"""The contact edge of an inelastic asperity located between nodes
(`asperity.fe.contact.penalty.contact_edge_pressure`, used by `solve_asperity_history`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.fe import J2Plasticity, Paraboloid, Sphere, solve_asperity_history
from asperity.fe.contact.penalty import contact_edge_pressure
from asperity.fe.drivers.inelastic import History
from asperity.studies.inelastic_accuracy import area_scatter

E, NU = 1000.0, 0.3
E_STAR = E / (1 - NU**2)
Y = E / 400  # elastic-perfectly plastic, E/Y = 400
#: Hertz first yield (p0 = 1.6 Y) of the unit sphere
W_C = (math.pi * 1.6 * Y / (2 * E_STAR)) ** 2
W_MAX = 50 * W_C
#: the mesh of tests/fe/test_inelastic.py: `draft` a little finer
ACC = dict(base="draft", growth=1.3, n_theta=6, sweeps=3, adapt_levels=6)


def _loading(ds):
    k = int(np.argmax(ds.interference.values))
    return ds.isel(step=slice(1, k + 1))  # from the first step in contact


def _sphere(accuracy):
    """An elastic-perfectly plastic sphere pressed to 50 times its critical interference."""
    return _loading(solve_asperity_history(Sphere(1.0), J2Plasticity(E, NU, Y),
                                           History.loading(W_MAX, 1.0), accuracy=accuracy))


def _grows_with_the_force(ds):
    F, A = ds.force.values, ds.contact_area.values
    assert np.all(np.diff(F) > 0)
    # d ln A / d ln F at every step: about 0.9 (A ~ F^0.9 here); where the edge
    # stayed on the last node in contact the area grew by that node's
    # penetration only (1e-3); measured at least 0.35 (draft) and 0.44 (standard)
    slope = np.diff(np.log(A)) / np.diff(np.log(F))
    assert slope.min() > 0.25, slope


def test_area_grows_with_the_force_at_every_step():
    _grows_with_the_force(_sphere("draft"))


#: contact area [m^2] of the same sphere at `fine` (its one mesh with the band, 116
#: steps: the reference run of `snakemake --cores 2 accuracy_inelastic`, case j2_sphere,
#: interpolated in ln F between its steps) at these forces [N]; fine's mesh before,
#: adapted further to the elastic solutions and without the band, gave 2.5909e-4,
#: 6.3420e-4, 1.8341e-3, 3.4461e-3, 6.4382e-3 (up to 1 % apart)
FINE_FORCE = np.array([1e-3, 3e-3, 1e-2, 2e-2, 4e-2])
FINE_AREA = np.array([2.5973e-4, 6.3756e-4, 1.8403e-3, 3.4124e-3, 6.4296e-3])


@pytest.mark.slow
def test_standard_grows_with_the_force_and_agrees_with_fine():
    ds = _sphere("standard")
    _grows_with_the_force(ds)
    F, A = ds.force.values, ds.contact_area.values
    area = np.exp(np.interp(np.log(FINE_FORCE), np.log(F), np.log(A)))
    # the elastic solver's tolerance at `standard`: 2 % in radius (measured 0.7 %)
    np.testing.assert_allclose(np.sqrt(area / FINE_AREA), 1.0, atol=0.02)


#: contact area [m^2] of the same sphere at `fine`, whose one mesh is refined where the
#: plastic edge goes (``edge_size`` 0.0125, the run above), interpolated in ln w between
#: its steps, at these fractions of the largest interference; fine's mesh before, with
#: the same band, gave these within 0.21 %
BAND_W = np.array([0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0])
BAND_AREA = np.array([1.33240e-3, 2.13270e-3, 2.96864e-3, 3.83432e-3, 4.72801e-3,
                      5.64040e-3, 6.56695e-3, 7.52001e-3, 8.46584e-3])


def _scatter(ds):
    """The area's step-to-step scatter (`asperity.studies.inelastic_accuracy.area_scatter`,
    which `snakemake --cores 2 accuracy_inelastic` reports for every run)."""
    return area_scatter(ds.interference.values, ds.contact_area.values)


@pytest.mark.slow
def test_edge_band_smooths_the_area_and_puts_standard_within_one_percent_of_fine():
    """Issue #14: the contact area at `standard` within 1 % of `fine`.  With the top
    refined over the radii the plastic edge sweeps (`remesh.edge_band`) the area is
    within 0.8 % of fine's at these interferences (1 % asserted, the target) and
    scatters by 0.7 % about a smooth curve (below 1 % asserted); the default mesh,
    adapted to elastic edges only, scatters by 2.3 % (asserted above 1.5 %: the band
    is what removes it)."""
    band = _sphere(dict(base="standard", edge_size=0.02))
    _grows_with_the_force(band)
    w, A = band.interference.values, band.contact_area.values
    area = np.exp(np.interp(np.log(BAND_W * W_MAX), np.log(w), np.log(A)))
    np.testing.assert_allclose(area / BAND_AREA, 1.0, atol=0.01)
    assert _scatter(band) < 0.01
    assert _scatter(_sphere("standard")) > 0.015


def test_elastic_j2_body_has_the_hertz_area():
    """With nothing yielding the edge is that of Hertz (report 6.1: A = pi R w)
    within the elastic solver's tolerance at `standard` (2 % in radius), on
    the mesh of the inelastic tests (`draft` a little finer)."""
    ds = _loading(solve_asperity_history(Paraboloid(1.0), J2Plasticity(E, NU, 1e9),
                                         History.loading(0.02, 1.0), accuracy=ACC))
    assert float(ds.max_inelastic_strain.max()) == 0.0
    w, a = ds.interference.values, ds.contact_radius.values
    late = w >= 0.1 * w[-1]  # beyond the first few nodes in contact
    assert np.all(np.abs(a[late] / np.sqrt(w[late]) - 1) < 0.02), a / np.sqrt(w) - 1
    np.testing.assert_allclose(ds.contact_area.values, np.pi * a**2)


@pytest.mark.parametrize("a_true", [0.605, 0.63, 0.68])
def test_edge_exact_for_plastic_and_for_elastic_fields(a_true):
    r = np.linspace(0.0, 1.0, 11)  # spacing 0.1; the edge between r[6] and r[7]
    touching = r < a_true
    # a plastic contact across an element: the pressure of the node before up
    # to the edge (r[6] carries its share of the interval), a linearly opening gap
    pressure = np.where(touching, 5.0, 0.0)
    pressure[6] = 5.0 * (a_true - r[6]) / 0.1
    gap = 0.2 * np.maximum(r - a_true, 0.0)
    assert contact_edge_pressure(r, gap, pressure, touching) == pytest.approx(a_true, rel=1e-12)
    # an elastic (Hertz) edge: p ~ (a - r)^(1/2), g ~ (r - a)^(3/2)
    pressure = 5.0 * np.sqrt(np.maximum(a_true - r, 0.0))
    gap = 0.2 * np.maximum(r - a_true, 0.0) ** 1.5
    assert contact_edge_pressure(r, gap, pressure, touching) == pytest.approx(a_true, rel=1e-12)


def test_edge_moves_from_node_to_node():
    r = np.linspace(0.0, 1.0, 11)
    touching = r < 0.65
    pressure = np.where(touching, 5.0, 0.0)
    gap = 0.2 * np.maximum(r - 0.6, 0.0) ** 1.2
    # the last node just touching, the next one about to
    edge = lambda p, g1: contact_edge_pressure(r, np.where(r == r[7], g1, gap),
                                               np.where(r == r[6], p, pressure), touching)
    assert edge(0.0, gap[7]) == pytest.approx(r[6], rel=1e-12)
    assert edge(3.0, 0.0) == pytest.approx(r[7], rel=1e-12)
    assert contact_edge_pressure(r, gap, pressure, np.zeros(11, bool)) == 0.0
