"""The plane-strain scenes (report 6.3.2, 6.3.3) side by side: meshes, presets and the
variants the report leaves open.

:func:`plane_strain_table` reads the ``plane_strain.nc`` of several runs (a scene at a
preset; a variant is a scene of its own, e.g. ``truncated_v_unloading``, written
``like: truncated_v``) and writes, per run and mesh (coarse, refined):

* the degrees of freedom of the elastic body, the force per unit length of both bodies at
  the largest interference, and the viscoplastic body's force over the elastic one's;
* the largest nonelastic strain, the elements the viscoplastic displacement turns inside
  out, the CPU time of the solves;
* for a cylinder, the largest deviation of the elastic contact half width from
  plane-strain Hertz (Johnson 1985, 4.3);
* with the effect ``unloading``: the permanent set (residual interference w_r), the
  elastic recovery (w_max - w_r) k / F_max and the unloading stiffness over k, k the
  elastic body's stiffness at w_max, and the viscoplastic contact half width at w_max
  over the elastic one's;

and per run the viscoplastic force's difference between the meshes.  Nothing is computed
again: the table says what the runs' files say.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import xarray as xr

from asperity.units import attrs

__all__ = ["plane_strain_table"]

#: name -> (units, long name) of the variables per run and mesh
PER_MESH = {
    "dofs": ("1", "degrees of freedom of the elastic body"),
    "elastic_force": ("N/m", "elastic body's force per unit length at the largest interference"),
    "viscoplastic_force": ("N/m", "viscoplastic body's force per unit length at the largest interference"),
    "viscoplastic_over_elastic": ("1", "viscoplastic over elastic force at the largest interference"),
    "largest_inelastic_strain": ("1", "largest nonelastic strain of the viscoplastic body"),
    "inverted_elements": ("1", "elements the viscoplastic displacement turns inside out"),
    "cpu_time": ("s", "CPU time of both bodies' solves"),
    "hertz_half_width_deviation": ("1", "largest |a / a_Hertz - 1| of the elastic half width (cylinder; "
                                        "NaN: no Hertz)"),
    "residual_interference": ("m", "permanent set after unloading (NaN: not unloaded)"),
    "recovery_ratio": ("1", "elastic recovery (w_max - w_r) k / F_max, k the elastic stiffness at w_max"),
    "unloading_over_elastic_stiffness": ("1", "unloading stiffness over the elastic stiffness at w_max"),
    "loaded_over_elastic_half_width": ("1", "viscoplastic over elastic contact half width at w_max"),
}


def _unloading(d: xr.Dataset) -> dict:
    if "residual_interference" not in d:
        return {k: np.nan for k in ("residual_interference", "recovery_ratio", "unloading_over_elastic_stiffness",
                                    "loaded_over_elastic_half_width")}
    w, f = d["step_interference"].values, d["step_force"].values
    peak = int(np.nanargmax(w))
    residual = float(d["residual_interference"])
    k = float(d["elastic_stiffness"][-1])
    a = d["contact_half_width"].isel(interference=-1)
    return {"residual_interference": residual, "recovery_ratio": (w[peak] - residual) * k / float(f[peak]),
            "unloading_over_elastic_stiffness": float(d["unloading_stiffness"]) / k,
            "loaded_over_elastic_half_width": float(a.sel(body="viscoplastic") / a.sel(body="elastic"))}


def _mesh(ds: xr.Dataset, mesh: str) -> dict:
    d = ds.sel(mesh=mesh)
    end = d.isel(interference=-1)
    f_el, f_vp = (float(end["force"].sel(body=b)) for b in ("elastic", "viscoplastic"))
    deviation = (float(np.abs(d["contact_half_width"].sel(body="elastic") / d["hertz_half_width"] - 1).max())
                 if "hertz_half_width" in d else np.nan)
    return {"dofs": int(d["dofs"].sel(body="elastic")), "elastic_force": f_el, "viscoplastic_force": f_vp,
            "viscoplastic_over_elastic": f_vp / f_el,
            "largest_inelastic_strain": float(d["largest_inelastic_strain"]),
            "inverted_elements": int(d["inverted_elements"]), "cpu_time": float(d["cpu_time"].sum()),
            "hertz_half_width_deviation": deviation, **_unloading(d)}


def plane_strain_table(runs: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """Module text.  `runs`: ``<scene>@<preset>`` -> its plane_strain.nc."""
    names = list(runs)
    meshes = [str(m) for m in runs[names[0]]["mesh"].values]
    rows = {name: {m: _mesh(ds, m) for m in meshes} for name, ds in runs.items()}
    data = {k: (("run", "mesh"), [[rows[n][m][k] for m in meshes] for n in names], attrs(*meta))
            for k, meta in PER_MESH.items()}
    vp = np.array(data["viscoplastic_force"][1], float)
    data["mesh_difference"] = ("run", vp[:, meshes.index("coarse")] / vp[:, meshes.index("refined")] - 1,
                               attrs("1", "viscoplastic force at the largest interference, coarse over refined "
                                          "mesh less 1"))
    text = {
        "scene": ([n.partition("@")[0] for n in names], "scene of the run"),
        "preset": ([n.partition("@")[2] for n in names], "accuracy preset of the run"),
        "kinematics": ([str(ds.attrs["kinematics"]) for ds in runs.values()], "small or finite strain"),
        "max_interference": ([float(ds.attrs["max_interference"]) for ds in runs.values()],
                             "largest interference"),
    }
    for k, (v, long_name) in text.items():
        data[k] = ("run", v, attrs("m" if k == "max_interference" else "", long_name))
    coords = {"run": ("run", names, attrs("", "scene@preset")), "mesh": ("mesh", meshes, attrs("", "mesh"))}
    return xr.Dataset(data, coords=coords)
