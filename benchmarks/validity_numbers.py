"""The numbers of the README's section "Validity": how much of the FE scenes with the
report's representative hills rests on extrapolated responses, why their rough
aluminum's friction coefficient is half the report's, and what the yielded-share limit
costs in pressure (smooth aluminum).

Reads a results tree made by the pipeline (default ``results/``), e.g. after

    snakemake --cores 2 --config \
        'scenes=[steel_glass_bead_representative,rough_aluminum_representative,asperity_shape]' \
        studies=False

and prints, per separation of the loading branch of each scene, the share of the
contacting asperities pressed beyond their FE job's range (``extrapolated_fraction``)
and the share of the nominal pressure they carry (``extrapolated_load_fraction``).

For rough_aluminum_representative it splits mu = tau_s A_c / p (report 9.41) into what it rests on:

- the mean real contact pressure p / A_c (mu = tau_s / (p / A_c)), against the
  hardness of the interface file (2.8 x the saturated Bodner-Partom flow stress);
- mu of the asperities inside their FE range only, and of those beyond it (the
  scene homogenized again with the force and area of the other part set to zero);
- the mean contact pressure F / A of the computed FE asperity along its job;
- the shear strength: mu at tau_s = Y / sqrt(3) with Y the initial and the
  saturated flow stress, and the tau_s the report's 0.3 would need.

and, for smooth_aluminum against smooth_aluminum_elastic (report 7.3), the share of
contacting elastic asperities beyond first yield beside the elastic pressure over the J2
pressure, per separation.

Writes benchmarks/results/validity.json (``--out``).

    python benchmarks/validity_numbers.py [results] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
SCENES = ("steel_glass_bead_representative", "rough_aluminum_representative", "asperity_shape")


def _loading(ds):
    if "branch" in ds.dims:
        return ds.sel(branch=ds["branch"].values[0])
    return ds


def run_config(results: Path, scene: str) -> dict:
    """The scene's sections as the run used them (the schema's defaults filled in), from
    the files' own `config` attributes: the plan's and the interface's."""
    from asperity.io.netcdf import read_dataset, scene_config

    cfg = scene_config(read_dataset(results / scene / "plan.nc"))
    cfg.update(scene_config(read_dataset(results / scene / "interface.nc")))
    return cfg


def shares(results: Path, scene: str) -> list[dict]:
    from asperity.io.netcdf import read_dataset
    from asperity.population.density import height_scale

    interface = _loading(read_dataset(results / scene / "interface.nc"))
    sigma = height_scale(read_dataset(results / scene / "surface.nc"))
    p = interface["nominal_pressure"].values
    keep = np.isfinite(p) & (p > 0)
    rows = []
    for i in np.flatnonzero(keep):
        rows.append({"separation_sigma": float(interface["separation"][i]) / sigma,
                     "nominal_pressure_MPa": float(p[i]) / 1e6,
                     "extrapolated_fraction": float(interface["extrapolated_fraction"][i]),
                     "extrapolated_load_fraction": float(interface["extrapolated_load_fraction"][i])})
    return rows


def beyond_height(results: Path, scene: str, fractions=(0.5, 0.75, 1.0)) -> dict:
    """The share of the load carried by asperities pressed beyond a fraction of their
    representative hill's height 2 C = 2 pi^2 / (ratio^2 kappa) (8.2): 0.5 is the FE
    jobs' range (the extrapolated share again), 1 the whole hill."""
    from asperity.io.netcdf import read_dataset
    from asperity.stages.homogenize import interface_dataset

    cfg = run_config(results, scene)
    d = results / scene
    asperities, surface, plan = (read_dataset(d / f) for f in ("asperities.nc", "surface.nc", "plan.nc"))
    ratio = cfg["asperity"].get("width_to_height", plan.attrs.get("width_to_height"))
    height = 2 * math.pi**2 / (ratio**2 * asperities["curvature"])
    interface = _loading(read_dataset(d / "interface.nc"))
    out = {"width_to_height": float(ratio)}
    for f in fractions:
        part = asperities[["force", "contact_area"]].copy()
        beyond = asperities["interference"] > f * height
        part["force"] = part["force"].where(beyond, 0.0).assign_attrs(asperities["force"].attrs)
        q = interface_dataset(part, surface, plan, cfg["population"],
                              cfg["homogenization"], cfg["units"])["nominal_pressure"]
        share = q.values / interface["nominal_pressure"].sel(separation=q["separation"]).values
        out[f"load_share_beyond_{f:g}_of_the_hill_height"] = [float(np.nanmin(share)), float(np.nanmax(share))]
    return out


def _part(asperities, inside: bool):
    """The table with only the asperity points inside (or beyond) their FE range."""
    keep = ~asperities["extrapolated"] if inside else asperities["extrapolated"]
    out = asperities[["force", "contact_area", "contact_radius"]].copy()
    for name in out.data_vars:
        out[name] = out[name].where(keep, 0.0).assign_attrs(asperities[name].attrs)
    return out


def friction_split(results: Path, scene: str = "rough_aluminum_representative") -> dict:
    from asperity.io.netcdf import read_dataset
    from asperity.stages.homogenize import interface_dataset
    from asperity.uniaxial.point import uniaxial_flow_stress
    from asperity.scene import materials, units

    cfg = run_config(results, scene)
    d = results / scene
    interface = _loading(read_dataset(d / "interface.nc"))
    friction = read_dataset(d / "friction.nc")
    asperities, surface, plan = (read_dataset(d / f) for f in ("asperities.nc", "surface.nc", "plan.nc"))
    tau = float(friction["junction_shear_strength"])
    p = interface["nominal_pressure"].values
    a = interface["contact_area_ratio"].values
    parts = {}
    for name, inside in (("inside", True), ("beyond", False)):
        part = interface_dataset(_part(asperities, inside), surface, plan, cfg["population"],
                                 cfg["homogenization"], cfg["units"])
        parts[name] = (part["nominal_pressure"].values, part["contact_area_ratio"].values)
    # the computed asperity (one job: a self-similar family) and its mean pressure F / A
    job = str(plan["key"].values[plan["job"].values.astype(bool)][0])
    sample = read_dataset(results / "samples" / f"{job}.nc")
    loading = sample["branch"].values.astype(str) == "loading" if "branch" in sample else True
    touch = (sample["contact_area"].values > 0) & loading
    mean_pressure = sample["force"].values[touch] / sample["contact_area"].values[touch]
    body = materials.build(materials.Material.from_scene(cfg["material"], units.Units.from_section(cfg["units"])),
                           ["plasticity"])
    flow0 = uniaxial_flow_stress(body, 1e-3)
    flow_sat = uniaxial_flow_stress(body, 1e-3, body.Z1)
    hardness = float(interface["hardness"])
    mu = friction["mu_shear"].values
    out = {
        "junction_shear_strength_MPa": tau / 1e6,
        "mu_shear": [float(mu.min()), float(mu.max())],
        "mean_real_pressure_MPa": [float((p / a).min()) / 1e6, float((p / a).max()) / 1e6],
        "hardness_MPa": hardness / 1e6,
        "tau_over_hardness": tau / hardness,
        "flow_stress_initial_MPa": flow0 / 1e6,
        "flow_stress_saturated_MPa": flow_sat / 1e6,
        "mu_inside_fe_range": [float(np.nanmin(tau * parts["inside"][1] / parts["inside"][0])),
                               float(np.nanmax(tau * parts["inside"][1] / parts["inside"][0]))],
        "mu_beyond_fe_range": [float(np.nanmin(tau * parts["beyond"][1] / parts["beyond"][0])),
                               float(np.nanmax(tau * parts["beyond"][1] / parts["beyond"][0]))],
        "load_share_beyond": [float((parts["beyond"][0] / p).min()), float((parts["beyond"][0] / p).max())],
        "area_share_beyond": [float((parts["beyond"][1] / a).min()), float((parts["beyond"][1] / a).max())],
        "fe_job_mean_pressure_MPa": {"first_touch": float(mean_pressure[0]) / 1e6,
                                     "end_of_range": float(mean_pressure[-1]) / 1e6,
                                     "largest": float(mean_pressure.max()) / 1e6},
        "mu_at_tau_initial_flow_over_sqrt3": [float(mu.min() * flow0 / math.sqrt(3) / tau),
                                              float(mu.max() * flow0 / math.sqrt(3) / tau)],
        "mu_at_tau_saturated_flow_over_sqrt3": [float(mu.min() * flow_sat / math.sqrt(3) / tau),
                                                float(mu.max() * flow_sat / math.sqrt(3) / tau)],
        "mu_inside_fe_range_at_tau_saturated_flow_over_sqrt3":
            float(np.nanmax(tau * parts["inside"][1] / parts["inside"][0]) * flow_sat / math.sqrt(3) / tau),
        "mean_real_pressure_for_mu_0p3_MPa": tau / 0.3 / 1e6,
    }
    return out


def elastic_against_j2(results: Path) -> list[dict]:
    """smooth_aluminum_elastic's yielded share beside its pressure over smooth_aluminum's (J2)."""
    from asperity.io.netcdf import read_dataset

    el = read_dataset(results / "smooth_aluminum_elastic" / "interface.nc")
    j2 = read_dataset(results / "smooth_aluminum" / "interface.nc")
    ratio = el["nominal_pressure"].values / j2["nominal_pressure"].values
    return [{"separation_um": float(h) * 1e6, "yielded_fraction": float(y), "elastic_over_j2": float(r)}
            for h, y, r in zip(el["separation"].values, el["yielded_fraction"].values, ratio)]


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="?", type=Path, default=REPO / "results",
                    help="a results tree (default results/)")
    ap.add_argument("--out", type=Path, default=REPO / "benchmarks" / "results" / "validity.json",
                    help="JSON file")
    args = ap.parse_args(argv)
    results = args.results
    report = {"results": str(results), "scenes": {}}
    for scene in SCENES:
        if not (results / scene / "interface.nc").exists():
            print(f"{scene}: no {results / scene / 'interface.nc'}; run the scene first")
            continue
        rows = shares(results, scene)
        report["scenes"][scene] = rows
        print(f"\n{scene}: separation / sigma, nominal pressure [MPa], extrapolated share of contacts, "
              "of the load")
        for r in rows[:: max(1, len(rows) // 8)] + rows[-1:]:
            print(f"  {r['separation_sigma']:6.3f}  {r['nominal_pressure_MPa']:10.4g}  "
                  f"{100 * r['extrapolated_fraction']:5.1f} %  {100 * r['extrapolated_load_fraction']:5.1f} %")
        ex = np.array([r["extrapolated_fraction"] for r in rows])
        lo = np.array([r["extrapolated_load_fraction"] for r in rows])
        print(f"  range: contacts {100 * ex.min():.1f}-{100 * ex.max():.1f} %, "
              f"load {100 * lo.min():.1f}-{100 * lo.max():.1f} %")
        reach = beyond_height(results, scene)
        report[f"{scene}_beyond_height"] = reach
        for k, v in reach.items():
            print(f"  {k}: {v if isinstance(v, float) else [round(100 * x, 1) for x in v]}")
    if (results / "rough_aluminum_representative" / "friction.nc").exists():
        split = friction_split(results)
        report["rough_aluminum_representative_friction"] = split
        print("\nrough_aluminum_representative friction, mu = tau_s A_c / p = tau_s / (p / A_c):")
        for k, v in split.items():
            print(f"  {k}: {v}")
    if (results / "smooth_aluminum_elastic" / "interface.nc").exists():
        rows = elastic_against_j2(results)
        report["smooth_aluminum_elastic_against_j2"] = rows
        print("\nsmooth_aluminum_elastic: separation [um], share beyond first yield, p_elastic / p_J2")
        for r in rows[::3]:
            print(f"  {r['separation_um']:.4f}  {100 * r['yielded_fraction']:5.1f} %  {r['elastic_over_j2']:.3f}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=1) + "\n")
    print(f"\nwritten {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
