"""The 3-D asperity as an elliptic paraboloid z = -(kappa_1 x^2 + kappa_2 y^2) / 2
(`geometry.EllipticParaboloid`) against Hertz's elliptic contact (Johnson, *Contact
Mechanics*, 1985, 4.2; `references.hertz.elliptic_hertz`), elastic and J2-plastic.

Axes: kappa_1 = 1 along x, kappa_2 = ratio kappa_1 along y, so the long semi-axis a of
the contact ellipse lies along y and the short one b along x (y = 0 is the half model's
symmetry plane).  Mesh: the `standard` sliding preset's fractions (tip 0.25, refine 0.8,
grading 0.5, depth grading 1.0) about the contact ellipse at the largest approach,
``MeshSpec.refine_radius`` = 0.8 b along x, ``refine_radius_y`` = 0.8 a along y, the tip
size 0.25 b; penalty factor 100 (`PENALTY_FACTOR_3D`)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from asperity.fe import LinearElastic
from asperity.fe.discretization.geometry import EllipticParaboloid, Paraboloid, Sphere
from asperity.fe.discretization.half_model_mesh import MeshSpec, build_mesh
from asperity.fe.drivers.inelastic import History, solve_asperity_history
from asperity.fe.drivers.solid3d import press_3d
from asperity.fe.materials.j2 import J2Plasticity
from asperity.fe.presets import resolve
from asperity.homogenize.anisotropic import peak_pressure_curvature
from asperity.references.hertz import elliptic_hertz, hertz_response

E_, NU = 1000.0, 0.3
ELASTIC = LinearElastic(E_, NU)
W = 0.005                         # the largest approach of the elastic checks [m]


def _spec(geo, a, L, tip=None):
    """`MeshSpec.for_hill` of the `standard` preset about the Hertz ellipse of long
    semi-axis a (the region's semi-axes 0.8 of the ellipse's, the tip 0.25 or `tip` of
    its short semi-axis b) on a block of half width and depth L a, coarse elements L a / 3."""
    p = resolve("sliding", "standard")
    if tip is not None:
        p = dict(p, tip_fraction=tip)
    return dataclasses.replace(MeshSpec.for_hill(geo, a, p), half_width=L * a, depth=L * a,
                               coarse_size=L * a / 3)


def _at(ds, w, name):
    """`name` at the rows of the approaches w."""
    wd = ds["normal_displacement"].values
    return ds[name].values[[int(np.argmin(np.abs(wd - x))) for x in w]]


# ------------------------------------------------------------------------- geometry
def test_elliptic_paraboloid_surface_and_mesh():
    """The surface over the plane: equal curvatures are `Paraboloid`'s surface of
    revolution to round-off; shallow (default) the body is the flat block and the
    paraboloid the gap; with ``shallow=False`` the mesh's top nodes lie on
    z = max(-(kappa_1 x^2 + kappa_2 y^2) / 2, -h) to round-off (1e-12 of h), h the cap
    height, and the elliptic refinement is finest over the ellipse (the longest edge of
    the top facets within it at most the tip size)."""
    x, y = np.meshgrid(np.linspace(-0.3, 0.3, 7), np.linspace(0.0, 0.3, 4))
    round_, par = EllipticParaboloid(2.0, 2.0), Paraboloid(0.5)
    np.testing.assert_allclose(round_.surface_xy(x, y), par.surface_xy(x, y), rtol=1e-14,
                               atol=1e-16)
    np.testing.assert_array_equal(round_.body_surface_xy(x, y), 0.0)
    np.testing.assert_array_equal(round_.gap_offset_xy(x, y), round_.surface_xy(x, y))
    with pytest.raises(ValueError):
        EllipticParaboloid(1.0, -1.0)

    # the Hertz ellipse's semi-axes (x, y): the long one along the smaller curvature
    H = elliptic_hertz(0.01, 4.0, 1.0, 1.0)
    sx, sy = EllipticParaboloid(4.0, 1.0).contact_semi_axes(float(H["semi_axis_a"]))
    assert (sx, sy) == pytest.approx((float(H["semi_axis_b"]), float(H["semi_axis_a"])),
                                     rel=1e-13)
    assert EllipticParaboloid(1.0, 4.0).contact_semi_axes(2.0) == pytest.approx(
        (2.0, 2.0 * sx / sy))
    assert round_.contact_semi_axes(2.0) == (2.0, 2.0)
    spec = MeshSpec.for_hill(EllipticParaboloid(4.0, 1.0), sy, resolve("sliding", "standard"))
    assert spec.refine_radius == pytest.approx(0.8 * sx)
    assert spec.refine_radius_y == pytest.approx(0.8 * sy)
    assert spec.tip_size == pytest.approx(0.25 * sx)
    assert MeshSpec.for_hill(round_, 2.0).refine_radius_y is None

    g = EllipticParaboloid(4.0, 1.0, cap_ratio=0.5, shallow=False)
    h = g.height
    assert h == pytest.approx(0.5**2 / 2.0)
    spec = MeshSpec(half_width=1.4 * g.extent, depth=g.extent, coarse_size=0.5 * g.extent,
                    tip_size=0.05, grading=0.7, refine_radius=0.1, refine_radius_y=0.2)
    hm = build_mesh(g, spec)
    X = np.asarray(hm.mesh.doflocs)
    top = np.abs(hm.nodes_ref[2]) < 1e-12
    exact = np.maximum(-(4.0 * X[0, top] ** 2 + X[1, top] ** 2) / 2.0, -h)
    assert np.abs(X[2, top] - exact).max() <= 1e-12 * h
    # within the ellipse (x / 0.1)^2 + (y / 0.2)^2 < 1 every top edge is at most the tip size
    p, t = hm.reference.p, hm.reference.t
    edges = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])
    a_, b_ = p[:, t[edges[:, 0]]], p[:, t[edges[:, 1]]]          # (3, 6, ne)
    mid = 0.5 * (a_ + b_)
    inside = ((mid[0] / 0.1) ** 2 + (mid[1] / 0.2) ** 2 < 1.0) & (np.abs(mid[2]) < 1e-12)
    assert inside.sum() > 20
    assert np.linalg.norm(a_ - b_, axis=0)[inside].max() <= 0.05 * (1 + 1e-12)


# ------------------------------------------------------------- elastic: elliptic Hertz
@pytest.mark.slow
@pytest.mark.parametrize("ratio", [1.0, 0.25])
def test_elliptic_hertz_3d(ratio):
    """Elastic elliptic paraboloids (kappa_2 / kappa_1 = 1, 1/4), frictionless, pressed
    to 0.4 W and W: the force within 1 % of elliptic Hertz, the contact area within
    8 %, the ellipse's aspect within 8 %.

    The finite block.  Its bottom and sides are held (u = 0), so it is stiffer than the
    half space: a distant load F sinks the half space's points at depth L by about
    c F, c = (3 - 2 nu) / (4 pi G L) (Boussinesq), and F(w) of w ~ F^(2/3) is larger
    by the relative 3 c F / (2 w) ~ 1 / L (1.1 a / L for a circle): 1 to 2.4 % at
    L = 40 a here.  Removed by Richardson extrapolation in the block size: two runs,
    half width and depth L = 40 a and 80 a (a the long semi-axis at W), the same
    fractions about the contact, F_inf = 2 F_80 - F_40 (the next term, O((a / L)^2),
    is below 0.01 % for the circle: a run at 160 a fell within 1e-4 of the 1 / L line
    through 40 a and 80 a).

    The force.  Measured after the extrapolation: ratio 1, -0.99 and -0.86 %; ratio 1/4,
    -0.78 and -0.64 %; ratio 1/8, not run here (four times the CPU time of 1/4), -0.70
    and -0.63 % (area -1.8 and -2.1 %, aspect +2.4 and +6.1 %).
    The remaining error is the mesh's (+0.2 % from tip 0.25 b to 0.18 b for the
    circle) and the penalty's (+0.13 % to a penalty 10 times stiffer), both
    softening: within the 1 % aimed at, with a margin of only 0.01 % for the circle at
    0.4 W (its contact is 0.63 of the refined disc there).

    The area (the touching nodes' weights, a staircase of the P2 nodes about the
    contact's edge, whose spacing is tip / 2 = 0.125 b): measured -5.6 % and -0.3 %
    (circle), -2.1 % and -1.0 % (1/4) on the 80 a block (-3.1 % at W for the circle on
    a 160 a block, whose mesh about the contact differs), 8 % allowed.  The aspect,
    a / b against the touching nodes' largest y over their largest x (each short of
    its semi-axis by up to the node spacing): measured 0 (circle) and +4.7, +2.4 %
    (1/4), 8 % allowed."""
    k1, k2 = 1.0, ratio
    ws = np.array([0.4 * W, W])
    H = elliptic_hertz(ws, k1, k2, ELASTIC.contact_modulus)
    a = float(H["semi_axis_a"][-1])
    geo = EllipticParaboloid(k1, k2)
    acc = dict(base="standard", normal_steps=1)    # elastic, frictionless: path independent
    runs = {L: press_3d(geo, ELASTIC, ws, accuracy=acc, mesh=_spec(geo, a, L), contact_radius=a)
            for L in (40.0, 80.0)}
    f40, f80 = (_at(runs[L], ws, "normal_force") for L in (40.0, 80.0))
    f_inf = 2.0 * f80 - f40
    f_err = f_inf / H["force"] - 1
    ds = runs[80.0]
    a_err = _at(ds, ws, "contact_area") / H["contact_area"] - 1
    x, y = ds["contact_x"].values, ds["contact_y"].values
    aspect = []
    for i in range(ws.size):
        touching = ds["contact_pressure"].values[i] > 0
        aspect.append(y[touching].max() / x[touching].max())
    asp_err = np.array(aspect) / (H["semi_axis_a"] / H["semi_axis_b"]) - 1
    print(f"ratio {ratio}: force {100 * f_err} % (block 40 a {100 * (f40 / H['force'] - 1)},"
          f" 80 a {100 * (f80 / H['force'] - 1)}), area {100 * a_err} %, aspect "
          f"{100 * asp_err} %")                                  # -rP
    assert np.all(np.abs(f_err) < 0.01), f_err
    assert np.all(np.abs(a_err) < 0.08), a_err
    assert np.all(np.abs(asp_err) < 0.08), asp_err
    assert np.all(ds["tangential_force"].values == 0.0)


# ------------------------------------------------------------------------ J2 plasticity
@pytest.mark.slow
def test_j2_elliptic_paraboloid_past_yield():
    """A J2 elliptic paraboloid (kappa_2 / kappa_1 = 1/4, E / Y = 250, nu = 0.3, perfectly
    plastic) pressed to Hertz mean pressures 0.79 Y (elastic: first yield of a Hertz
    contact is at about 1.1 Y mean pressure, p0 ~ 1.6 Y) and 2.5 Y, against the linear
    elastic body on the same mesh (a coarser one than `test_elliptic_hertz_3d`'s: tip
    0.4 b, block 20 a; its force is 2 % below and above Hertz there, the finite block's
    bias).  Before yield the J2 body is the elastic one: the same force to 1e-9 (Newton's
    tolerance) and no inelastic strain; past yield finite, below the elastic body's
    force by more than 5 % (measured 11.7 %) and below elastic Hertz.

    The anisotropic route's ``law: fe`` reads this departure from the axisymmetric J2
    sphere of equal Hertz peak pressure (`anisotropic.peak_pressure_curvature`, curvature
    0.568 kappa_1 here, at draft): its force ratio to Hertz is the 3-D body's ratio J2 /
    elastic within 2 % (the 3-D mesh's own bias against Hertz), measured 0.886 against
    0.883 at 5.3 times the sphere's first-yield interference."""
    Y = E_ / 250.0
    ws = np.array([8e-5, 8e-4])
    H = elliptic_hertz(ws, 1.0, 0.25, ELASTIC.contact_modulus)
    p_mean = H["force"] / H["contact_area"]
    assert p_mean[0] < 0.8 * Y and p_mean[1] > 2.4 * Y
    a = float(H["semi_axis_a"][-1])
    geo = EllipticParaboloid(1.0, 0.25)
    spec = _spec(geo, a, 20.0, tip=0.4)
    acc = dict(base="standard", normal_steps=4)
    el = press_3d(geo, ELASTIC, ws, accuracy=acc, mesh=spec, contact_radius=a)
    pl = press_3d(geo, J2Plasticity(E_, NU, Y), ws, accuracy=acc, mesh=spec, contact_radius=a)
    assert pl.attrs["completed"] == 1
    f_el, f_pl = _at(el, ws, "normal_force"), _at(pl, ws, "normal_force")
    print(f"J2 / elastic {f_pl / f_el}, elastic / Hertz {f_el / H['force']}")   # -rP
    assert np.all(np.isfinite(pl["normal_force"].values))
    assert f_pl[0] == pytest.approx(f_el[0], rel=1e-9)
    assert np.all(pl["plane_inelastic_strain"].values[0] == 0.0)
    assert pl["plane_inelastic_strain"].values[1].max() > 0.0
    assert f_pl[1] < 0.95 * f_el[1]
    assert f_pl[1] < H["force"][1]

    k = float(peak_pressure_curvature(np.array(1.0), np.array(0.25)))
    sphere = solve_asperity_history(Sphere(1.0 / k), J2Plasticity(E_, NU, Y), History((0.0, 1.0), (0.0, 1e-3)),
                                    accuracy="draft", mesh_levels=np.geomspace(1e-5, 1e-3, 6),
                                    initial_time_step=2e-2)
    departure = (np.interp(ws, sphere["interference"].values, sphere["force"].values)
                 / hertz_response(ws, k, ELASTIC.contact_modulus, 0.0)["force"])
    print(f"sphere of equal p0: departure {departure}")                  # -rP
    assert departure[1] == pytest.approx(f_pl[1] / f_el[1], rel=0.02)
