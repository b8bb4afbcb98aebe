"""Meshes that follow the contact (`asperity.fe.drivers.adhesive_model`, module docstring "Mesh"),
meant for the flat asperities of report 7.3 (R up to 300 um at d = 0.3 nm).

The fine band is a window around the cohesive zone, moved (surface displacement
interpolated, equilibrium re-solved) when the zone nears its ends; a contact edge far
inside it has a coarser band of its own.  Checked, with the following forced on a
steeper asperity, against the whole band refined once (the fixed mesh the solver uses
below `follow_above`), with narrow margins that give the contact edge its own band,
and through a jump-in that lands outside the window (a mesh change in the middle of
the jump).
"""

import numpy as np
import pytest

from asperity.fe import BodnerPartom, LennardJones, LinearElastic, Paraboloid, solve_asperity_adhesive
from asperity.fe.drivers import adhesive_model
from asperity.fe.presets import resolve
from asperity.population.kinds.adhesive import on_levels

D = 0.3e-9
LAW = LennardJones(1.0, D)
ALLOY = BodnerPartom.aluminum_6061_t4()  # Fig. 7.6's aluminum (report 6.3.1)
MAT = LinearElastic(ALLOY.E, ALLOY.nu)
W_MAX = 10e-9


def _main_jumps(ds):
    """Indices of the jumps on each branch (a jump's record and the one before it)."""
    jump = ds.jump.values.astype(bool)
    branch = ds.branch.values.astype(str)
    return (np.nonzero(jump & (branch == "approach"))[0],
            np.nonzero(jump & (branch == "retract"))[0])


FOLLOWING = dict(base="draft", follow_above=0)


@pytest.fixture(scope="module")
def pair():
    """R = 15.4 um (Fig. 7.6, mu = 4.7) on the whole band and on a following mesh."""
    R = 15.4e-6
    fixed = solve_asperity_adhesive(Paraboloid(R), MAT, LAW, w_max=W_MAX, accuracy="draft")
    moving = solve_asperity_adhesive(Paraboloid(R), MAT, LAW, w_max=W_MAX, accuracy=FOLLOWING)
    return R, fixed, moving


@pytest.fixture(scope="module")
def two_bands():
    """The R = 15.4 um asperity on following meshes with margins narrow enough (6 ring
    elements) for its contact edge to lie more than two margins inside the cohesive
    zone, as at R >= 150 um with the preset's margins: the bands of each new mesh are
    recorded."""
    bands = []
    window_for = adhesive_model.AdhesiveModel.window_for

    def recorded(model, state):
        out = window_for(model, state)
        if out is not None:
            bands.append(out)
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(adhesive_model.AdhesiveModel, "window_for", recorded)
        ds = solve_asperity_adhesive(Paraboloid(15.4e-6), MAT, LAW, w_max=W_MAX,
                                     accuracy=dict(FOLLOWING, follow_margin_elements=6.0))
    return ds, bands


@pytest.mark.slow
def test_following_mesh_agrees_with_the_whole_band(pair):
    R, fixed, moving = pair
    assert fixed.attrs["meshes"] == 1 and moving.attrs["meshes"] >= 3
    assert moving.attrs["band_facets"] < fixed.attrs["band_facets"]
    _agree(fixed, moving)


@pytest.mark.slow
def test_contact_edge_band_agrees_with_the_whole_band(pair, two_bands):
    """The contact edge in a band of its own, of elements EDGE_COARSENING times
    longer than the ring's, gives the whole band's path (the tolerances of
    `test_following_mesh_agrees_with_the_whole_band`), and its contact radius
    within 2.5e-3 of the largest: about draft's own error there (the whole band at
    draft against standard: 1.1e-3 on approach, 1.9e-3 on retraction; the single
    following band within 5e-5 of the whole band; measured here 2.2e-3)."""
    R, fixed, _ = pair
    ds, bands = two_bands
    split = [b for b in bands if len(b) == 2]
    assert len(split) >= 5
    for (lo, hi, h), (lo_e, hi_e, h_e) in split:  # the edge's band inside the ring's
        assert h_e == adhesive_model.EDGE_COARSENING * h and hi_e < lo
    _agree(fixed, ds)
    for af, a2 in on_levels(fixed, ds, "contact_radius", 0.1 * D):
        ok = np.isfinite(af) & (af > 0)
        np.testing.assert_allclose(a2[ok], af[ok], rtol=0, atol=2.5e-3 * af[ok].max())


def _agree(fixed, moving):
    """A following mesh's path against the whole band's."""
    # the pull-off to 1e-4, below draft's own distance from standard (1.3e-4 to
    # 1.4e-3 at three of the scene's eight tips).  Measured at R = 15.4 um against
    # the whole band (or the margins before 030d000, 0.15 x radius and at least
    # 40 ring elements, which are within 1e-7 of it): 9.9e-5 with the preset's
    # margins of 20 ring elements, 9.0e-5 with 6 (the two-band case), 8e-6 with
    # 30; at R = 30 um 4.4e-5 with 20 and 2.6e-6 with 30.  The narrow margin is
    # the price of R = 300 um at draft in under 60 s (with 30 elements: 82 s).
    # Where it comes from (ad hoc, 2026-11-28): the law's tail beyond the zone's
    # outer end (FINE_SEPARATION = 4 d) on the graded elements past the margin.
    # With the zone reaching 6 d or 8 d and margins of 20 the pull-off is 1.6e-5
    # and 8e-6 from the whole band's, for 10 % more CPU at R = 300 um (6 d).
    assert moving.attrs["pull_off_force"] == pytest.approx(fixed.attrs["pull_off_force"], rel=1e-4)
    for attr in ("jump_in_interference", "jump_off_interference"):
        assert abs(moving.attrs[attr] - fixed.attrs[attr]) <= 0.01 * D, attr
    assert moving.attrs["jumps"] == fixed.attrs["jumps"]
    # both branches on the fixed run's requested levels, away from the jumps
    for Ff, Fm in on_levels(fixed, moving, "force", 0.1 * D):
        ok = np.isfinite(Ff)
        np.testing.assert_allclose(Fm[ok], Ff[ok], rtol=0,
                                   atol=1e-3 * fixed.attrs["pull_off_force"])


@pytest.mark.slow
def test_mesh_change_in_the_middle_of_a_jump_in(pair):
    """The following mesh starts with its fine band at the apex: the jump-in lands
    with the contact edge outside it, is moved to a mesh around the edge and
    re-solved there.  It must land on the branch the fixed mesh jumps to: the
    same force, contact radius and tip at the flat, and at the same interference to
    the resolution with which a path locates a jump, ``min_step * d`` of the preset
    (the bisection in w stops there, `adhesive_trace` module docstring)."""
    R, fixed, moving = pair
    (kf,) = _main_jumps(fixed)[0]
    (km,) = _main_jumps(moving)[0]
    assert moving.dofs.values[km] != moving.dofs.values[km - 1]  # re-meshed on landing
    assert fixed.dofs.values[kf] == fixed.dofs.values[kf - 1]
    located = resolve("adhesive", "draft")["min_step"] * D
    assert moving.interference.values[km] == pytest.approx(fixed.interference.values[kf],
                                                           abs=located)
    P = fixed.attrs["pull_off_force"]
    assert abs(moving.force.values[km] - fixed.force.values[kf]) <= 1e-3 * P
    assert moving.contact_radius.values[km] == pytest.approx(fixed.contact_radius.values[kf],
                                                             rel=0.01)
    assert moving.tip_separation.values[km] == pytest.approx(D, rel=1e-3)
    # and before the jump the tip hung out of contact on both
    assert moving.contact_radius.values[km - 1] == 0 == fixed.contact_radius.values[kf - 1]
