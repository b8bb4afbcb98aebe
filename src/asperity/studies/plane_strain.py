"""Plane-strain asperities pressed by a rigid flat: the studies of report 6.3.2 and 6.3.3.

Report 6.3.2 presses an aluminum cylinder (a "macro asperity", the spaced circular rods
of Fig. 6.8c) analysed as a plane section (Figs. 6.15 to 6.18); 6.3.3 presses the
truncated V ridge (the 45-degree grooves of Fig. 6.8b, Figs. 6.19 to 6.23). Both use the
Bodner-Partom constants of 6061-T4 fitted in 6.3.1 and compare, as Figs. 6.17 and 6.22 do,

- a purely elastic body and the viscoplastic one (report 3.2.2, 3.13), and
- the original mesh and the mesh refined after the first solution pass (Figs. 6.15,
  6.16, 6.19, 6.20).

`plane_strain_study` runs both bodies on each named mesh. A mesh is an accuracy preset
(`asperity.fe.presets`) with overrides: ``{"sweeps": 0}`` is the initial graded mesh
(the report's "original" mesh), the preset itself its adaptively refined mesh. The
elastic body is solved by `asperity.fe.solve_asperity`, the viscoplastic one along the
loading history by `asperity.fe.solve_asperity_history` (incremental form of 3.22, time
error control of 3.36); both are meshed by the same call of the adaptive loop with the
same elastic constants and interference levels, so that on each mesh the two bodies
share every node.

The viscoplastic curve is also interpolated (linearly, its steps are at most
``max_interference_step`` of the range apart) onto the elastic body's levels, so that
the two forces are compared at the same interference. A history that goes back after
its largest interference (the scene's effect ``unloading``) unloads the viscoplastic
body until its force is zero: the loading branch is interpolated, every step is kept,
and the interference where the force returned to zero is the permanent set of the
asperity (``residual_interference``; the elastic twin has none). For a cylinder the
elastic contact half width is compared with the plane-strain Hertz solution
a = 2 sqrt(F' R / (pi E*)), E* = E / (1 - nu^2) (Johnson, Contact Mechanics, 4.3;
`asperity.fe.analytic.hertz_line_half_width`): the approach of a
plane-strain contact depends logarithmically on the size of the body, the width at a
given force per length does not.

Forces are per unit length of the ridge or cylinder, over its whole section (both
sides of the plane of symmetry); the interference is the approach of the flat to the
cut-off boundary of the block (`asperity.fe.presets.PLANE_STRAIN_DOMAIN` footprints
away), from first touch.
"""

from __future__ import annotations

import time
from typing import Mapping

import numpy as np
import xarray as xr

from asperity.units import attrs

#: the bodies of a study, in order
BODIES = ("elastic", "viscoplastic")
#: the history's variables interpolated onto the interference levels
TRACKED = ("force", "contact_radius", "max_inelastic_strain", "max_von_mises",
           "max_equivalent_strain")


def levels(max_interference: float, points: int) -> np.ndarray:
    """The interference levels of a study: `points` evenly spaced up to the largest."""
    if not (max_interference > 0 and points >= 2):
        raise ValueError("max_interference must be positive and points at least 2")
    return max_interference * np.arange(1, points + 1) / points


def _loading(history: xr.Dataset) -> slice:
    """The steps of the loading branch: up to the first at the largest interference."""
    return slice(0, int(np.argmax(history["interference"].values)) + 1)


def _interpolated(history: xr.Dataset, w: np.ndarray) -> dict[str, np.ndarray]:
    """The loading branch's variables at the interferences `w` (linear in w)."""
    loading = history.isel(step=_loading(history))
    wi = loading["interference"].values
    return {k: np.interp(w, wi, loading[k].values) for k in TRACKED}


def _unloading_stiffness(history: xr.Dataset) -> float:
    """dF/dw over the first step after the largest interference (NaN if none)."""
    peak = _loading(history).stop - 1
    if peak + 1 >= history.sizes["step"]:
        return float("nan")
    w, f = history["interference"].values, history["force"].values
    return float((f[peak] - f[peak + 1]) / (w[peak] - w[peak + 1]))


def _padded(values: np.ndarray, n: int) -> np.ndarray:
    out = np.full(n, np.nan)
    out[: len(values)] = values
    return out


def _check_bodies(geometry, body, elastic) -> None:
    """Refuse a body of revolution and an elastic twin without the body's E and nu."""
    if geometry.axisymmetric:
        raise ValueError("a plane-strain study needs a plane section (axisymmetric=False)")
    if abs(elastic.E - body.E) > 1e-12 * body.E or abs(elastic.nu - body.nu) > 1e-12:
        raise ValueError("the elastic twin must have the body's E and nu")


def _solve_meshes(geometry, body, elastic, history, meshes: Mapping[str, dict],
                  w: np.ndarray, w_max: float, unloads: bool, kinematics: str,
                  progress) -> tuple:
    """Solve both bodies on each mesh: the elastic results and the viscoplastic loading
    branch on the levels `w` (grid), the elastic stiffness, CPU times, degrees of freedom,
    inverted elements at the end and the viscoplastic histories (runs)."""
    from asperity.fe import solve_asperity, solve_asperity_history
    from asperity.fe.presets import resolve

    names = list(meshes)
    shape = (len(names), len(BODIES), len(w))
    grid = {k: np.full(shape, np.nan) for k in TRACKED}
    stiffness = np.full((len(names), len(w)), np.nan)
    cpu = np.full((len(names), len(BODIES)), np.nan)
    dofs = np.zeros((len(names), len(BODIES)), dtype=np.int64)
    inverted = np.zeros(len(names), dtype=np.int64)
    runs = []
    for i, name in enumerate(names):
        preset = resolve("elastic", meshes[name])
        t0 = time.process_time()
        e = solve_asperity(geometry, elastic, w, accuracy=preset)
        cpu[i, 0] = time.process_time() - t0
        t0 = time.process_time()
        v = solve_asperity_history(geometry, body, history, accuracy=preset, mesh_levels=w,
                                   kinematics=kinematics, end_fields=True)
        cpu[i, 1] = time.process_time() - t0
        runs.append(v)
        grid["force"][i, 0] = e["force"].values
        grid["contact_radius"][i, 0] = e["contact_radius"].values
        grid["max_von_mises"][i, 0] = e["max_von_mises"].values
        grid["max_equivalent_strain"][i, 0] = e["max_equivalent_strain"].values
        grid["max_inelastic_strain"][i, 0] = 0.0
        stiffness[i] = e["normal_stiffness"].values
        for k, values in _interpolated(v, w).items():
            grid[k][i, 1] = values
        dofs[i] = (int(e["dofs"].values[0]), int(v["dofs"].values[0]))
        inverted[i] = int((v["element_jacobian"] <= 0).sum())
        if progress is not None:
            progress(f"mesh {name}: {dofs[i, 1]} dofs, elastic {cpu[i, 0]:.2f} s, "
                     f"viscoplastic {v.attrs['steps']} steps {cpu[i, 1]:.2f} s, force at "
                     f"{w_max:.4g} m {grid['force'][i, 0, -1]:.6g} / "
                     f"{grid['force'][i, 1, -1]:.6g} N/m, "
                     f"largest nonelastic strain {float(v['max_inelastic_strain'].max()):.4g}, "
                     + (f"residual interference {v.attrs['residual_interference']:.4g} m, "
                        if unloads else "")
                     + f"{inverted[i]} elements inside out at the end")
    return grid, stiffness, cpu, dofs, inverted, runs


def _study_dataset(names: list[str], w: np.ndarray, grid: dict[str, np.ndarray],
                   stiffness: np.ndarray, cpu: np.ndarray, dofs: np.ndarray,
                   runs: list[xr.Dataset]) -> xr.Dataset:
    """The study's variables on ``mesh``, ``body``, ``interference`` and ``step``: both
    bodies on the levels and the viscoplastic histories, NaN-padded to the longest."""
    steps = max(r.sizes["step"] for r in runs)
    per_step = {k: np.stack([_padded(r[k].values, steps) for r in runs])
                for k in ("time", "interference", "force", "contact_radius",
                          "max_inelastic_strain")}
    largest = np.array([float(r["max_inelastic_strain"].max()) for r in runs])
    where = np.array([float(r["interference"].values[np.argmax(r["max_inelastic_strain"].values)])
                      for r in runs])
    dims3 = ("mesh", "body", "interference")
    return xr.Dataset(
        {
            "force": (dims3, grid["force"], attrs("N/m", "contact force per unit length of the "
                                                  "section (both sides of the symmetry plane)")),
            "contact_half_width": (dims3, grid["contact_radius"],
                                   attrs("m", "contact half width a (edge located between nodes)")),
            "max_inelastic_strain": (dims3, grid["max_inelastic_strain"],
                                     attrs("1", "largest equivalent nonelastic (inelastic) strain "
                                                "at the quadrature points")),
            "max_von_mises": (dims3, grid["max_von_mises"],
                              attrs("Pa", "largest von Mises stress at the quadrature points")),
            "max_equivalent_strain": (dims3, grid["max_equivalent_strain"],
                                      attrs("1", "largest von Mises equivalent total strain")),
            "elastic_stiffness": (("mesh", "interference"), stiffness,
                                  attrs("N/m^2", "normal stiffness dF/dw of the elastic body per "
                                                 "unit length (consistent tangent)")),
            "cpu_time": (("mesh", "body"), cpu,
                         attrs("s", "CPU time of the solve, meshing included")),
            "dofs": (("mesh", "body"), dofs, attrs("1", "degrees of freedom of the mesh")),
            "largest_inelastic_strain": (("mesh",), largest,
                                         attrs("1", "largest equivalent nonelastic strain over the "
                                                    "history (viscoplastic body)")),
            "largest_inelastic_strain_interference": (
                ("mesh",), where, attrs("m", "interference where the largest nonelastic strain "
                                             "was reached (loading or unloading)")),
            "viscoplastic_steps": (("mesh",), np.array([r.attrs["steps"] for r in runs]),
                                   attrs("1", "time steps of the viscoplastic history")),
            "step_time": (("mesh", "step"), per_step["time"], attrs("s", "time of the step")),
            "step_interference": (("mesh", "step"), per_step["interference"],
                                  attrs("m", "interference of the flat at the step")),
            "step_force": (("mesh", "step"), per_step["force"],
                           attrs("N/m", "contact force per length at the step (viscoplastic)")),
            "step_contact_half_width": (("mesh", "step"), per_step["contact_radius"],
                                        attrs("m", "contact half width at the step")),
            "step_inelastic_strain": (("mesh", "step"), per_step["max_inelastic_strain"],
                                      attrs("1", "largest nonelastic strain at the step")),
        },
        coords={
            "mesh": ("mesh", names, attrs("1", "mesh: accuracy preset and its overrides")),
            "body": ("body", list(BODIES), attrs("1", "constitutive model of the body")),
            "interference": ("interference", w,
                             attrs("m", "approach of the flat from first touch")),
            "step": ("step", np.arange(steps), attrs("1", "time step index of the viscoplastic "
                                                          "history (0: untouched)")),
        },
    )


def _with_end_fields(ds: xr.Dataset, runs: list[xr.Dataset],
                     inverted: np.ndarray) -> xr.Dataset:
    """`ds` with each mesh and the viscoplastic body on it at the end, its sizes and its
    inverted elements."""
    from asperity.fe.drivers.inelastic import END_FIELDS

    # each mesh and the viscoplastic body on it at the end (Figs. 6.15, 6.16, 6.19-6.21),
    # padded to the largest mesh: NaN, and -1 for the corners of missing triangles
    ends = xr.concat([r[list(END_FIELDS)] for r in runs], dim="mesh", join="outer",
                     fill_value={k: (-1 if k == "triangle_vertices" else np.nan)
                                 for k in END_FIELDS}, combine_attrs="override")
    ds = ds.merge(ends, combine_attrs="override")
    ds["vertices"] = ("mesh", np.array([r.sizes["vertex"] for r in runs]),
                      attrs("1", "vertices of the mesh (the rest of dim vertex is padding)"))
    ds["triangles"] = ("mesh", np.array([r.sizes["triangle"] for r in runs]),
                       attrs("1", "elements of the mesh (the rest of dim triangle is padding)"))
    ds["inverted_elements"] = ("mesh", inverted,
                               attrs("1", "elements the viscoplastic body's displacement at the "
                                          "end turns inside out (det(I + grad u) <= 0: the "
                                          "small-strain solution past its range)"))
    return ds


def plane_strain_study(geometry, body, elastic, history, meshes: Mapping[str, dict],
                       points: int = 24, kinematics: str = "small",
                       progress=None) -> xr.Dataset:
    """Force against interference of a plane-strain asperity, elastic and viscoplastic,
    on each of `meshes` (module docstring).

    Parameters
    ----------
    geometry
        a plane-strain `asperity.fe.discretization.geometry.Profile` (`Cylinder`, `TruncatedV`).
    body, elastic
        the inelastic body (`BodnerPartom`, `J2Plasticity`) and its elastic twin
        (`LinearElastic` with the same E and nu).
    history
        `asperity.fe.History`: the loading of the flat (interference against time).
    meshes
        mesh name -> accuracy preset (a dict `asperity.fe.presets.resolve` takes for
        "elastic"); both bodies are meshed by it, so that they share the mesh, refined
        to the elastic solutions as the report's (6.3.2).
    points
        interference levels of the elastic body, evenly spaced to the largest of the
        history; they also drive the meshing of both bodies.
    kinematics
        of the inelastic body (`solve_asperity_history`): ``"small"`` (the report's
        theory) or ``"finite"``; the elastic twin is linear, small strain.
    progress
        called with a message after each solve.

    Returns a Dataset in SI on dims ``mesh``, ``body``, ``interference`` (the levels)
    and ``step`` (the viscoplastic history, NaN-padded; with unloading, both branches),
    with the CPU time of each solve, the degrees of freedom of each mesh, the largest
    nonelastic strain of each mesh and where it was reached, for a history that unloads
    the residual interference and the unloading stiffness of each mesh, for a cylinder
    the Hertz half width, and on dims ``vertex``, ``triangle`` and ``corner`` each mesh
    with the viscoplastic body's displacement and nonelastic strain at the end of the
    history (`asperity.fe.drivers.inelastic.mesh_fields`, padded to the largest mesh).
    """
    from asperity.fe.analytic import hertz_line_half_width

    _check_bodies(geometry, body, elastic)
    w_max = float(np.max(history.interferences))
    unloads = float(history.interferences[-1]) < w_max
    w = levels(w_max, points)
    names = list(meshes)
    grid, stiffness, cpu, dofs, inverted, runs = _solve_meshes(
        geometry, body, elastic, history, meshes, w, w_max, unloads, kinematics, progress)
    ds = _study_dataset(names, w, grid, stiffness, cpu, dofs, runs)
    ds = _with_end_fields(ds, runs, inverted)
    if unloads:
        ds["residual_interference"] = (
            "mesh", np.array([r.attrs["residual_interference"] for r in runs]),
            attrs("m", "interference where the viscoplastic body's force returned to zero on "
                       "unloading: its permanent set (NaN: it never did)"))
        ds["unloading_stiffness"] = (
            "mesh", np.array([_unloading_stiffness(r) for r in runs]),
            attrs("N/m^2", "slope of the viscoplastic body's force per length over the first "
                           "unloading step"))
    if geometry.kind == "cylinder":
        ds["hertz_half_width"] = (
            ("mesh", "interference"),
            hertz_line_half_width(geometry.radius, elastic.E, elastic.nu, grid["force"][:, 0]),
            attrs("m", "plane-strain Hertz half width 2 sqrt(F' R / (pi E*)) at the elastic "
                       "body's force"))
    ds.attrs.update(
        geometry=repr(geometry),
        geometry_kind=geometry.kind,
        footprint_half_width=float(geometry.extent),
        ridge_height=float(geometry.height),
        body=getattr(body, "name", "") or type(body).__name__,
        youngs_modulus=float(body.E),
        poisson=float(body.nu),
        max_interference=w_max,
        history_times=np.asarray(history.times, float),
        history_interferences=np.asarray(history.interferences, float),
        meshes=", ".join(f"{n}: {dict(meshes[n])}" for n in names),
        kinematics=kinematics,
        unloading=int(unloads),
        interpolation="viscoplastic loading branch interpolated linearly in interference onto "
                      "the elastic body's levels",
    )
    return ds
