"""The plane-strain studies of report 6.3.2 (cylinder) and 6.3.3 (truncated V ridge):
the scenes' sections in SI, and the study at `draft` on the scenes' own geometry,
material and history, checked against closed forms and between its two meshes.

Tolerances, and why:
- elastic cylinder: contact half width within 2 % (refined mesh) and 3 % (initial
  graded mesh, whose elements near the edge are 0.4 times their distance from the apex
  at draft) of plane-strain Hertz, a = 2 sqrt(F' R / (pi E*)) (Johnson 4.3), at every
  level (the edge is located between nodes; the approach itself depends on the block's
  size, so the width against the force is the closed form to test);
- elastic ridge: the flat top touches at once and stays the contact, a punch: F / w
  constant to 0.1 %; coarse and refined slopes within 1 %;
- coarse against refined mesh: force within 2 % (cylinder) and 3 % (ridge), what the
  draft meshes give (1.1 % and 2.2 %);
- before anything flows the viscoplastic force is the elastic one within 0.5 % (the
  inelastic driver's own check in tests/fe/test_inelastic.py); once yielded it is below;
- largest nonelastic strain of the ridge: between 0.4 and 2, the report's "about 80 %"
  within a factor of two. It sits at the corners of the flat top, where the elastic
  strain is singular: it grows as the mesh is refined there (0.79 and 1.08 on the
  draft meshes), so it is of the report's order, never a converged number.

The study runs once per scene for the module (about 3 s and 2 s of CPU): those tests
are marked slow.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml

from asperity.fe.analytic import hertz_line_half_width
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.discretization.geometry import Cylinder, TruncatedV
from asperity.fe.materials.elastic import LinearElastic
from asperity.studies.plane_strain import levels, plane_strain_study
from asperity.scene.plane_strain import PlaneStrain

from .scene_defaults import SCHEMA, filled_scene

INCH = 0.0254


def scene(name: str, effects=None) -> PlaneStrain:
    config = yaml.safe_load((SCHEMA.parent / "scenes" / f"{name}.yaml").read_text())
    if effects is not None:
        config["effects"] = effects
    return PlaneStrain.from_scene(filled_scene(config))


def run(name: str, effects=None):
    s = scene(name, effects)
    return plane_strain_study(s.geometry(), s.body(), s.elastic(), s.history(), s.presets("draft"),
                              points=s.points, kinematics=s.kinematics)


@pytest.fixture(scope="module")
def cylinder():
    return run("aluminum_cylinder")


@pytest.fixture(scope="module")
def ridge():
    return run("truncated_v")


def test_scene_sections_in_si():
    """6.2.1: 45-degree grooves 0.1 in apart; the ridge between them comes to a point
    0.1207 in above the groove bottom (the 0.125 in depth within 3.5 %); truncated, the
    ridge still spans one pitch. The body is the 6061-T4 set of 6.3.1."""
    v = scene("truncated_v")
    assert v.pitch == pytest.approx(0.1 * INCH)
    assert v.sharp_ridge_height == pytest.approx(0.05 * INCH / math.tan(math.radians(22.5)))
    assert v.sharp_ridge_height / (0.125 * INCH) == pytest.approx(0.966, abs=0.001)
    g = v.geometry()
    assert isinstance(g, TruncatedV) and not g.axisymmetric
    assert g.extent == pytest.approx(0.5 * v.pitch)
    assert 2 * g.top_half_width == pytest.approx(0.005 * INCH)
    assert g.included_angle_deg == 45.0
    c = scene("aluminum_cylinder")
    assert isinstance(c.geometry(), Cylinder) and c.geometry().radius == pytest.approx(INCH / 16)
    body, elastic = c.body(), c.elastic()
    assert isinstance(body, BodnerPartom) and isinstance(elastic, LinearElastic)
    assert (body.E, body.nu, body.n, body.D0) == (65e9, 0.33, 5.8, 1e8)
    assert (elastic.E, elastic.nu) == (body.E, body.nu)
    assert c.presets("draft") == {"coarse": {"base": "draft", "sweeps": 0},
                                  "refined": {"base": "draft"}}
    assert c.history().interferences[-1] == pytest.approx(6e-6)


def test_study_rejects_a_body_of_revolution_and_a_foreign_elastic_twin():
    from asperity.fe.drivers.inelastic import History

    body = BodnerPartom.aluminum_6061_t4()
    with pytest.raises(ValueError, match="plane section"):
        plane_strain_study(Cylinder(1e-3, axisymmetric=True), body, LinearElastic(body.E, body.nu),
                           History.loading(1e-6, 1e-7), {"m": {"base": "draft"}})
    with pytest.raises(ValueError, match="elastic twin"):
        plane_strain_study(Cylinder(1e-3), body, LinearElastic(70e9, body.nu),
                           History.loading(1e-6, 1e-7), {"m": {"base": "draft"}})
    np.testing.assert_allclose(levels(1.0, 4), [0.25, 0.5, 0.75, 1.0])


@pytest.mark.slow
def test_both_bodies_share_each_mesh_and_the_refined_mesh_is_finer(cylinder, ridge):
    for ds in (cylinder, ridge):
        dofs = ds["dofs"]
        assert np.all(dofs.sel(body="elastic").values == dofs.sel(body="viscoplastic").values)
        assert int(dofs.sel(mesh="refined", body="elastic")) > int(dofs.sel(mesh="coarse",
                                                                             body="elastic"))


@pytest.mark.slow
def test_elastic_cylinder_half_width_follows_plane_strain_hertz(cylinder):
    el = cylinder.sel(body="elastic")
    F = el["force"].values
    a_h = hertz_line_half_width(INCH / 16, 65e9, 0.33, F)
    np.testing.assert_allclose(cylinder["hertz_half_width"].values, a_h, rtol=1e-12)
    a = el["contact_half_width"]
    np.testing.assert_allclose(a.sel(mesh="refined").values, a_h[1], rtol=0.02)
    np.testing.assert_allclose(a.sel(mesh="coarse").values, a_h[0], rtol=0.03)
    # and the closed form written out: a = 2 sqrt(F R / (pi E*))
    e_star = 65e9 / (1 - 0.33**2)
    np.testing.assert_allclose(a_h, 2 * np.sqrt(F * INCH / 16 / (np.pi * e_star)), rtol=1e-12)


@pytest.mark.slow
def test_elastic_ridge_is_a_flat_punch(ridge):
    el = ridge.sel(body="elastic")
    w = ridge["interference"].values
    slope = el["force"].values / w
    np.testing.assert_allclose(slope, np.broadcast_to(slope[:, :1], slope.shape), rtol=1e-3)
    np.testing.assert_allclose(el["contact_half_width"].values, 0.0025 * INCH, rtol=1e-4)
    coarse, refined = slope[:, -1]
    assert coarse == pytest.approx(refined, rel=0.01)


@pytest.mark.slow
@pytest.mark.parametrize("name, rtol", [("cylinder", 0.02), ("ridge", 0.03)])
def test_coarse_and_refined_forces_agree(cylinder, ridge, name, rtol):
    ds = {"cylinder": cylinder, "ridge": ridge}[name]
    for body in ("elastic", "viscoplastic"):
        f = ds["force"].sel(body=body)
        np.testing.assert_allclose(f.sel(mesh="coarse").values, f.sel(mesh="refined").values,
                                   rtol=rtol)


@pytest.mark.slow
def test_viscoplastic_force_is_elastic_until_it_flows_then_below(cylinder, ridge):
    for ds, below_at_end in ((cylinder, 0.95), (ridge, 0.3)):
        f_el = ds["force"].sel(body="elastic").values
        f_vp = ds["force"].sel(body="viscoplastic").values
        eps = ds["max_inelastic_strain"].sel(body="viscoplastic").values
        still = eps < 1e-7
        assert still.any() and (~still).any()
        np.testing.assert_allclose(f_vp[still], f_el[still], rtol=0.005)
        yielded = eps > 1e-3
        assert np.all(f_vp[yielded] < f_el[yielded])
        assert np.all(f_vp[:, -1] < below_at_end * f_el[:, -1])
    # the cylinder is "almost elastic" (6.3.2): within 15 % of the elastic force, a
    # nonelastic strain near 1 %; the ridge's flat top flows and its force levels off
    ratio = (cylinder["force"].sel(body="viscoplastic") / cylinder["force"].sel(body="elastic"))
    assert float(ratio.min()) > 0.85
    assert np.all(cylinder["largest_inelastic_strain"].values < 0.03)
    f = ridge["step_force"].sel(mesh="refined").values
    w = ridge["step_interference"].sel(mesh="refined").values
    late = w > 0.5 * np.nanmax(w)
    assert np.nanmax(f[late]) < 1.05 * np.nanmin(f[late])


@pytest.mark.slow
def test_ridge_largest_nonelastic_strain_is_of_the_reports_order(ridge):
    largest = ridge["largest_inelastic_strain"].values
    assert np.all((0.4 < largest) & (largest < 2.0)), largest
    # reached at the end of the loading: the strain keeps growing at the corners
    np.testing.assert_allclose(ridge["largest_inelastic_strain_interference"].values, 30e-6)


def _end_mesh(ds, mesh):
    """Vertices (r, z), displacements, triangles and element strains of one mesh at the
    end, padding dropped."""
    m = ds.sel(mesh=mesh)
    nv, ne = int(m["vertices"]), int(m["triangles"])
    return (m["vertex_r"].values[:nv], m["vertex_z"].values[:nv],
            m["vertex_displacement_r"].values[:nv], m["vertex_displacement_z"].values[:nv],
            m["triangle_vertices"].values[:ne], m["element_inelastic_strain"].values[:ne])


@pytest.mark.slow
@pytest.mark.parametrize("name", ["cylinder", "ridge"])
def test_end_fields_press_the_top_onto_the_flat(cylinder, ridge, name):
    """The meshes drawn (Figs. 6.15, 6.16, 6.19-6.21) are the ones solved: at the end the
    top surface inside the contact lies on the flat, z + u_z = -w, to the penalty's
    penetration (measured below 2e-5 w; asserted 1e-3 w), and below it beyond; the
    padding of the smaller mesh is NaN and -1."""
    ds = {"cylinder": cylinder, "ridge": ridge}[name]
    geometry = scene({"cylinder": "aluminum_cylinder", "ridge": "truncated_v"}[name]).geometry()
    w = float(ds.attrs["max_interference"])
    for mesh in ds["mesh"].values:
        r, z, ur, uz, t, _ = _end_mesh(ds, mesh)
        a = float(ds["contact_half_width"].sel(mesh=mesh, body="viscoplastic")[-1])
        top = np.abs(z - geometry.body_surface(r)) <= 1e-9 * geometry.extent
        inside, outside = top & (r < 0.8 * a), top & (r > 1.3 * a) & (r < 3 * a)
        assert inside.sum() >= 3 and outside.sum() >= 1
        np.testing.assert_allclose(z[inside] + uz[inside], -w, atol=1e-3 * w)
        assert np.all(z[outside] + uz[outside] < -w)  # below the flat: a gap
        assert t.min() == 0 and t.max() == len(r) - 1
    coarse = ds.sel(mesh="coarse")
    nv, ne = int(coarse["vertices"]), int(coarse["triangles"])
    assert nv < ds.sizes["vertex"] and ne < ds.sizes["triangle"]
    assert np.all(np.isnan(coarse["vertex_r"].values[nv:]))
    assert np.all(coarse["triangle_vertices"].values[ne:] == -1)


@pytest.mark.slow
def test_end_fields_put_the_strain_where_the_contact_puts_it(cylinder, ridge):
    """Element means of the nonelastic strain at the end, against where the theory puts
    its largest value: a line contact yields first below the surface (von Mises stress
    largest at 0.70 a under a Hertz line contact, Johnson 4.3), the ridge at the corners
    of its flat top (the punch's singular edge). Asserted: the element of the largest
    mean has its centroid 0.3-1.0 a deep under the cylinder (measured 0.43-0.55 a on the
    draft meshes) and within 0.5-1.3 half widths of the axis, 0.25 half widths of the top,
    on the ridge (measured 0.71-0.89 and 0.06-0.10); no element mean exceeds the largest
    strain at a quadrature point, and the largest is at least half of it (0.79-0.96). The
    "almost elastic" cylinder turns no element inside out: det(I + grad u) within 2 % of
    1 everywhere (measured 1.1 %, the elastic compression under the contact)."""
    for ds, name in ((cylinder, "cylinder"), (ridge, "ridge")):
        for mesh in ds["mesh"].values:
            r, z, _, _, t, ep = _end_mesh(ds, mesh)
            k = int(np.argmax(ep))
            rc, depth = r[t[k]].mean(), -z[t[k]].mean()
            largest = float(ds["largest_inelastic_strain"].sel(mesh=mesh))
            assert 0.5 * largest <= ep[k] <= largest * (1 + 1e-12)
            if name == "cylinder":
                assert int(ds["inverted_elements"].sel(mesh=mesh)) == 0
                jac = ds["element_jacobian"].sel(mesh=mesh).values[:len(ep)]
                np.testing.assert_allclose(jac, 1.0, atol=0.02)
                a = float(ds["contact_half_width"].sel(mesh=mesh, body="viscoplastic")[-1])
                assert 0.3 * a < depth < 1.0 * a, (mesh, depth / a)
            else:
                b = 0.0025 * INCH
                assert 0.5 * b < rc < 1.3 * b and depth < 0.25 * b, (mesh, rc / b, depth / b)


def test_a_plane_strain_scene_simulates_the_effects_it_names():
    """Plasticity (the study compares the inelastic body with its elastic twin), damage,
    finite strain and unloading; an effect it does not simulate is refused, not ignored."""
    assert scene("truncated_v").kinematics == "small"
    assert scene("truncated_v", ["plasticity", "finite_strain"]).kinematics == "finite"
    w = scene("truncated_v").max_interference
    assert scene("truncated_v").history().interferences == (0.0, w)
    assert scene("truncated_v", ["plasticity", "unloading"]).history().interferences == (0.0, w, 0.0)
    for effects in (["plasticity", "sliding"], ["plasticity", "adhesion"], ["unloading"]):
        with pytest.raises(ValueError, match="effects: a plane_strain scene"):
            scene("truncated_v", effects)


@pytest.mark.slow
def test_unloading_starts_elastic_with_the_loaded_contact(cylinder, ridge):
    """With the effect unloading the flat goes back until the force is zero, and

    - the loading branch is the loading-only study's, step for step (to 1e-12);
    - the permanent set lies between 0 and the largest interference;
    - the ridge unloads as the elastic punch it was before it flowed: its force falls at
      the elastic twin's punch stiffness k (within 0.1 %; measured 0.0001-0.008 %) with
      its contact unchanged over the first 85 % of the force, and it recovers F_max / k
      within 3 % (measured 1.8-2.2 % more: the crushed top is not flat, so the contact
      recedes over the last 15 % and the slope falls);
    - the cylinder's contact has spread plastically (half width 1.35-1.38 times the
      elastic one at the top of the loading: over 1.2 asserted), and it starts to unload
      at the stiffness of an elastic line contact of that width: 1 / k = C - 2 ln(a) /
      (pi E*) (in plane strain the compliance of a contact of half width a grows as
      ln(1/a), plus a constant set by the body), C fitted to the elastic twin's stiffness
      over the upper half of its levels, within 2 % (measured 0.2-0.6 %).
    """
    e_star = {}
    for loaded, name in ((ridge, "truncated_v"), (cylinder, "aluminum_cylinder")):
        s = scene(name, ["plasticity", "unloading"])
        e_star[name] = s.material.youngs_modulus / (1 - s.material.poisson ** 2)
        ds = run(name, ["plasticity", "unloading"])
        assert ds.attrs["unloading"] == 1 and loaded.attrs["unloading"] == 0
        w_max = float(ds.attrs["max_interference"])
        for mesh in ds["mesh"].values:
            d, before = ds.sel(mesh=mesh), loaded.sel(mesh=mesh)
            peak = int(np.nanargmax(d["step_interference"].values))
            assert peak == int(before["viscoplastic_steps"]), mesh   # step 0: untouched
            np.testing.assert_allclose(d["step_force"].values[:peak + 1],
                                       before["step_force"].values[:peak + 1], rtol=1e-12, atol=0)
            residual = float(d["residual_interference"])
            assert 0 < residual < w_max, (name, mesh, residual)
            w, f = d["step_interference"].values, d["step_force"].values
            slope = float(d["unloading_stiffness"])
            assert slope == (f[peak] - f[peak + 1]) / (w[peak] - w[peak + 1])
            k_e = d["elastic_stiffness"].values
            a_e = d["contact_half_width"].sel(body="elastic").values
            if name == "truncated_v":
                np.testing.assert_allclose(slope, k_e[-1], rtol=1e-3)
                np.testing.assert_allclose((w_max - residual) * k_e[-1] / f[peak], 1.0, rtol=0.03)
                continue
            a = float(d["contact_half_width"].sel(body="viscoplastic")[-1])
            assert a > 1.2 * a_e[-1], (mesh, a / a_e[-1])
            upper = slice(len(a_e) // 2, None)
            c = np.mean(1 / k_e[upper] + 2 * np.log(a_e[upper]) / (math.pi * e_star[name]))
            np.testing.assert_allclose(slope * (c - 2 * math.log(a) / (math.pi * e_star[name])),
                                       1.0, rtol=0.02)


@pytest.mark.slow
def test_finite_strain_spreads_the_ridge_at_its_flow_pressure(cylinder, ridge):
    """With the effect finite_strain (the report, and the scenes, are small strain) the
    ridge's crushed top spreads onto the flat: its contact is wider than the section of
    the ridge w below its top, b + w tan 22.5 (1.195 b at 30 um; measured 1.31-1.32 times
    the small-strain width), at the same mean pressure F / 2a within 3 % (the top's flow
    pressure; measured within 1.5 %), so the force is 30 % higher, and no element turns
    inside out. The "almost elastic" cylinder (1.2 % strain) moves by less than 1 %
    (measured 0.06-0.2 %)."""
    w = float(ridge.attrs["max_interference"])
    b = 0.0025 * INCH
    for small, name in ((ridge, "truncated_v"), (cylinder, "aluminum_cylinder")):
        finite = run(name, ["plasticity", "finite_strain"])
        assert finite.attrs["kinematics"] == "finite" and small.attrs["kinematics"] == "small"
        end = {k: d.sel(body="viscoplastic").isel(interference=-1)
               for k, d in (("small", small), ("finite", finite))}
        force = end["finite"]["force"].values / end["small"]["force"].values
        assert np.all(finite["inverted_elements"].values == 0)
        if name == "aluminum_cylinder":
            np.testing.assert_allclose(force, 1.0, atol=0.01)
            continue
        a = {k: e["contact_half_width"].values for k, e in end.items()}
        assert np.all(a["finite"] > b + w * math.tan(math.radians(22.5))), a["finite"] / b
        np.testing.assert_allclose(force, a["finite"] / a["small"], rtol=0.03)


@pytest.mark.parametrize("section, words", [
    ({"shape": "truncated_v", "pitch": 2540.0}, "'top_width' is a required property"),
    ({"shape": "cylinder"}, "'radius' is a required property"),
    ({"shape": "wedge", "radius": 1.0}, "'wedge' is not one of"),
])
def test_schema_requires_each_shapes_dimensions(section, words):
    from snakemake.exceptions import WorkflowError

    bad = {"units": {"length": "um", "pressure": "MPa"},
           "material": {"youngs_modulus": 65000.0, "poisson": 0.33},
           "plane_strain": {"section": section, "max_interference": 1.0, "velocity": 1.0}}
    with pytest.raises(WorkflowError) as err:
        filled_scene(bad)
    text = str(err.value)
    cause = err.value.__cause__ or err.value.__context__
    assert words in text + str(cause)


def test_a_truncation_wider_than_the_pitch_is_refused():
    s = filled_scene({"units": {"length": "um", "pressure": "MPa"},
                      "material": {"youngs_modulus": 65000.0, "poisson": 0.33},
                      "plane_strain": {"section": {"shape": "truncated_v", "pitch": 100.0,
                                                   "top_width": 150.0},
                                       "max_interference": 1.0, "velocity": 1.0}})
    with pytest.raises(ValueError, match="top_width must be smaller than the pitch"):
        PlaneStrain.from_scene(s)


@pytest.mark.slow
def test_the_stage_warns_where_small_strain_turns_elements_inside_out(caplog):
    """The ridge at standard: the refined mesh's corner elements fold over at 30 um (13 of
    them, README), the coarse ones do not; the stage logs a warning naming the mesh and
    the effect that avoids it, and the file keeps it (about 4 s of CPU)."""
    import logging

    from asperity.stages.plane_strain import plane_strain_dataset

    config = filled_scene(yaml.safe_load((SCHEMA.parent / "scenes" / "truncated_v.yaml").read_text()))
    with caplog.at_level(logging.WARNING, logger="asperity"):
        ds = plane_strain_dataset("truncated_v", config, "standard")
    assert int(ds["inverted_elements"].sel(mesh="coarse")) == 0
    assert int(ds["inverted_elements"].sel(mesh="refined")) > 0
    assert "inside out" in ds.attrs["warnings"] and "'refined'" in ds.attrs["warnings"]
    assert "finite_strain" in ds.attrs["warnings"] and "'coarse'" not in ds.attrs["warnings"]
    assert ds.attrs["warnings"] in caplog.text


@pytest.mark.slow
def test_the_stage_warns_where_unloading_resolves_no_permanent_set(caplog):
    """The cylinder pressed 0.3 um (a twentieth of the scene's 6 um) does not flow: its
    force returns to zero only with the flat back at first touch, so the permanent set is
    NaN, and the stage says so in the log and the file, naming the meshes and their
    strain (about 4 s of CPU)."""
    import logging

    from asperity.stages.plane_strain import plane_strain_dataset

    config = yaml.safe_load((SCHEMA.parent / "scenes" / "aluminum_cylinder.yaml").read_text())
    config["effects"] = ["plasticity", "unloading"]
    config["plane_strain"]["max_interference"] = 0.3
    with caplog.at_level(logging.WARNING, logger="asperity"):
        ds = plane_strain_dataset("aluminum_cylinder", filled_scene(config), "draft")
    assert ds["residual_interference"].isnull().all()
    assert np.all(ds["largest_inelastic_strain"].values < 1e-6)
    assert "no permanent set" in ds.attrs["warnings"] and "'refined'" in ds.attrs["warnings"]
    assert ds.attrs["warnings"] in caplog.text


def test_the_table_reads_each_run(cylinder, ridge):
    """`asperity.studies.plane_strain_table` on the draft runs: forces, strains and CPU as
    the runs' files give them; the cylinder's half width against plane-strain Hertz as
    its deviation (under 3 % on both meshes); the unloaded ridge recovers F_max / k (the
    elastic punch it was before it flowed, 3 % as in
    `test_unloading_starts_elastic_with_the_loaded_contact`) and unloads at k (0.1 %)."""
    from asperity.studies.plane_strain_table import plane_strain_table

    unloaded = run("truncated_v", ["plasticity", "unloading"])
    ds = plane_strain_table({"c@draft": cylinder, "r@draft": ridge, "u@draft": unloaded})
    assert list(ds["scene"].values) == ["c", "r", "u"] and set(ds["preset"].values) == {"draft"}
    ds = ds.assign_coords(run=["c", "r", "u"])
    for name, source in (("c", cylinder), ("r", ridge), ("u", unloaded)):
        end = source.isel(interference=-1)
        for body in ("elastic", "viscoplastic"):
            np.testing.assert_array_equal(ds[f"{body}_force"].sel(run=name), end["force"].sel(body=body))
        np.testing.assert_array_equal(ds["largest_inelastic_strain"].sel(run=name), source["largest_inelastic_strain"])
        np.testing.assert_allclose(ds["cpu_time"].sel(run=name), source["cpu_time"].sum("body"), rtol=1e-12)
        f = end["force"].sel(body="viscoplastic")
        assert float(ds["mesh_difference"].sel(run=name)) == pytest.approx(
            float(f.sel(mesh="coarse") / f.sel(mesh="refined") - 1), rel=1e-12)
    assert np.all(ds["hertz_half_width_deviation"].sel(run="c").values < 0.03)
    assert np.all(np.isnan(ds["hertz_half_width_deviation"].sel(run="r").values))
    assert np.all(np.isnan(ds["residual_interference"].sel(run=["c", "r"]).values))
    np.testing.assert_allclose(ds["recovery_ratio"].sel(run="u"), 1.0, rtol=0.03)
    np.testing.assert_allclose(ds["unloading_over_elastic_stiffness"].sel(run="u"), 1.0, rtol=1e-3)
    np.testing.assert_array_equal(ds["residual_interference"].sel(run="u"), unloaded["residual_interference"])
