"""The numbers of the README's subsection "The coupled hill family": the scenes with
coupled hills scaled from a family of aspects (report 2.5.1, 8.2.2) beside the same
scenes with the representative hill (8.2.2).

Reads a results tree made by the pipeline (default ``results/``), e.g. after

    snakemake --cores 1 --config 'scenes=[rough_aluminum,steel_glass_bead]' \
        studies=False accuracy=draft

(each coupled scene compares with its representative one, which the run makes too), and
prints per scene, on the loading branch:

- per separation: the nominal pressure of both mappings and their ratio, the share of the
  pressure from extrapolated responses (``extrapolated_load_fraction``), the shares of
  contacting asperities with large strain and beyond first yield, the real contact area
  ratio, the interaction indicator, and the first limit that fails (``validity``);
- the valid separation range of both mappings;
- the friction coefficient (shear and total) where the friction section gives a measured
  or the report's nominal pressure, and over the valid range;
- the FE cost: jobs and CPU seconds (``asperities.nc``), and the interpolation error of
  the family at its left-out job (``aspect_check_*``).

Writes benchmarks/results/coupled_<accuracy>.json (``--out``).

    python benchmarks/coupled_numbers.py [results] [--inelastic] [--out FILE]

and the family against one FE job per sample: the elastic hills of asperity_shape_coupled,
and with ``--inelastic`` the Bodner-Partom hills of rough_aluminum on a small
population (8 heights x 4 curvatures: 32 jobs, minutes).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
PAIRS = (("steel_glass_bead", "steel_glass_bead_representative"),
         ("rough_aluminum", "rough_aluminum_representative"))
INDICATORS = ("extrapolated_load_fraction", "extrapolated_fraction", "large_strain_fraction",
              "yielded_fraction", "contact_area_ratio", "interaction")


def _loading(ds):
    if "branch" in ds.dims:
        return ds.sel(branch="loading")
    return ds


def _float(x) -> float | None:
    x = float(x)
    return None if not np.isfinite(x) else x


def scene_numbers(results: Path, scene: str, separations: np.ndarray | None = None) -> dict:
    """The numbers of `scene`, at its own `separations` [m] or at those given (an unloading
    branch adds separations of its own: the nearest loading one is taken)."""
    from asperity.io.netcdf import read_dataset
    from asperity.population.density import height_scale

    d = results / scene
    interface = _loading(read_dataset(d / "interface.nc"))
    if separations is not None:
        interface = interface.sel(separation=separations, method="nearest")
    sigma = height_scale(read_dataset(d / "surface.nc"))
    asperities = read_dataset(d / "asperities.nc")
    h = interface["separation"].values
    out = {"sigma_um": sigma * 1e6, "separation_sigma": [float(x) for x in h / sigma],
           "nominal_pressure_MPa": [float(x) for x in interface["nominal_pressure"].values / 1e6],
           "valid": [bool(v) for v in interface["valid"].values],
           "validity": [str(v) for v in interface["validity"].values]}
    for name in INDICATORS:
        if name in interface:
            out[name] = [_float(v) for v in interface[name].values]
    valid = interface["valid"].values.astype(bool)
    out["valid_range_sigma"] = ([float(h[valid].min() / sigma), float(h[valid].max() / sigma)]
                                if valid.any() else None)
    out["valid_count"] = int(valid.sum())
    cost = {"accuracy": str(asperities.attrs.get("accuracy", "")),
            "fe_jobs": int(asperities.attrs.get("fe_jobs", 0)),
            "fe_cpu_time": float(asperities.attrs.get("fe_cpu_time", np.nan))}
    cost.update({k: float(v) for k, v in asperities.attrs.items() if k.startswith("aspect_check")})
    if "aspects" in asperities.attrs:
        cost["aspects"] = [float(q) for q in np.atleast_1d(asperities.attrs["aspects"])]
    out["fe"] = cost
    if (d / "friction.nc").exists():
        fr = read_dataset(d / "friction.nc")
        fr_load = _loading(fr)
        if separations is not None:
            fr_load = fr_load.sel(separation=separations, method="nearest")
        out["mu_shear"] = [_float(v) for v in fr_load["mu_shear"].values]
        out["mu"] = [_float(v) for v in fr_load["mu"].values]
        out["mu_interlocking"] = float(fr["mu_interlocking"])
        if "mu_at_measurement" in fr:
            out["mu_at_measurement"] = [_float(v) for v in fr["mu_at_measurement"].values]
            out["mu_shear_at_measurement"] = [_float(v) for v in fr["mu_shear_at_measurement"].values]
            out["measured_mu"] = [float(v) for v in fr["measured_mu"].values]
            out["measured_nominal_pressure_MPa"] = [float(v) / 1e6 for v in fr["measured_nominal_pressure"].values]
        mu_s = np.array(out["mu_shear"], float)
        if valid.any():
            out["mu_shear_valid_range"] = [float(np.nanmin(mu_s[valid])), float(np.nanmax(mu_s[valid]))]
        out["mu_shear_range"] = [float(np.nanmin(mu_s)), float(np.nanmax(mu_s))]
    return out


def family_against_direct(accuracy: str = "draft", aspects: int = 6, scene_name: str = "asperity_shape_coupled",
                          samples: dict | None = None) -> dict:
    """The family of aspects against one job per sample: the nominal pressure and contact
    area ratio of the two over the scene's separations, the jobs and their CPU time.
    Computed here (no pipeline). By default the elastic coupled hills of
    asperity_shape_coupled (elastic jobs at `draft` cost about 0.3 s each); `samples`
    replaces the scene's sample counts (a small population for inelastic hills)."""
    import yaml

    from asperity.population import samples as population
    from asperity.stages import homogenize, surface
    from asperity.stages import population as stage
    sys.path.insert(0, str(REPO))
    from tests.scene_defaults import filled_scene

    raw = yaml.safe_load((REPO / "config" / "scenes" / f"{scene_name}.yaml").read_text())
    for key in ("compare_with", "friction", "laws"):
        raw.pop(key, None)
    if samples:
        raw["population"]["samples"] = {**raw["population"].get("samples", {}), **samples}
    out = {}
    for name, extra in (("direct", {"scaling": "none"}),
                        ("family", {"scaling": "self_similar", "aspects": aspects, "aspect_check": True})):
        scene = filled_scene({**raw, "asperity": {**raw["asperity"], **extra}})
        sds = surface.surface_from_statistics(scene["surface"], scene["units"])
        plan = stage.plan_dataset(sds, scene["population"], scene["asperity"], scene["material"],
                                  scene.get("effects", []), scene["units"], accuracy)
        jobs = {}
        for r in np.flatnonzero(plan["job"].values):
            key = str(plan["key"].values[r])
            jobs[key] = population.solve(json.loads(str(plan["spec"].values[r])), key)
        asp = population.gather(plan, jobs)
        itf = homogenize.interface_dataset(asp, sds, plan, scene["population"], scene["homogenization"],
                                           scene["units"])
        out[name] = {"fe_jobs": len(jobs), "fe_cpu_time": float(sum(j.attrs["cpu_time"] for j in jobs.values())),
                     "p": itf["nominal_pressure"].values, "a": itf["contact_area_ratio"].values,
                     "check": {k: float(v) for k, v in asp.attrs.items() if k.startswith("aspect_check")}}
    p_ratio = out["family"]["p"] / out["direct"]["p"]
    a_ratio = out["family"]["a"] / out["direct"]["a"]
    return {"scene": scene_name, "samples": samples, "accuracy": accuracy, "aspects": aspects,
            "jobs": {k: v["fe_jobs"] for k, v in out.items()},
            "cpu_s": {k: v["fe_cpu_time"] for k, v in out.items()},
            "left_out_job": out["family"]["check"],
            "pressure_family_over_direct": [float(np.nanmin(p_ratio)), float(np.nanmax(p_ratio))],
            "area_family_over_direct": [float(np.nanmin(a_ratio)), float(np.nanmax(a_ratio))]}


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="?", type=Path, default=REPO / "results",
                    help="a results tree (default results/)")
    ap.add_argument("--inelastic", action="store_true",
                    help="also the Bodner-Partom hills of rough_aluminum (minutes)")
    ap.add_argument("--out", type=Path,
                    help="JSON file (default benchmarks/results/coupled_<accuracy>.json)")
    args = ap.parse_args(argv)
    results = args.results
    report = {"results": str(results), "scenes": {}}
    accuracy = "unknown"
    for coupled, representative in PAIRS:
        if not (results / coupled / "interface.nc").exists():
            print(f"{coupled}: no {results / coupled / 'interface.nc'}; run the scene first")
            continue
        c = scene_numbers(results, coupled)
        own = np.array(c["separation_sigma"]) * c["sigma_um"] * 1e-6
        r = (scene_numbers(results, representative, own)
             if (results / representative / "interface.nc").exists() else None)
        report["scenes"][coupled] = c
        if r is not None:
            report["scenes"][representative] = r
        accuracy = c["fe"].get("accuracy", accuracy)
        print(f"\n{coupled} (against {representative}), loading branch, sigma = {c['sigma_um']:.3g} um")
        print("  h/sigma  p_coupled  p_repr  ratio  extrap.load(c/r)  large_strain(c/r)  yielded  area   inter.  validity")
        hs = np.array(c["separation_sigma"])
        step = max(1, hs.size // 10)
        for i in list(range(0, hs.size, step)) + ([hs.size - 1] if (hs.size - 1) % step else []):
            pc = c["nominal_pressure_MPa"][i]
            pr = r["nominal_pressure_MPa"][i] if r else float("nan")
            el_r = r["extrapolated_load_fraction"][i] if r else float("nan")

            def g(name):
                v = c.get(name, [None] * hs.size)[i]
                return float("nan") if v is None else v

            ls_r = r.get("large_strain_fraction", [None] * hs.size)[i] if r else None
            print(f"  {hs[i]:6.3f}  {pc:9.4g}  {pr:8.4g}  {pc / pr:5.3f}  "
                  f"{100 * g('extrapolated_load_fraction'):5.1f}/{100 * el_r:5.1f} %  "
                  f"{100 * g('large_strain_fraction'):5.1f}/{100 * (ls_r if ls_r is not None else np.nan):5.1f} %  "
                  f"{100 * g('yielded_fraction'):5.1f} %  "
                  f"{g('contact_area_ratio'):.3g}  {g('interaction'):.3g}  {c['validity'][i] or 'valid'}")
        print(f"  valid: coupled {c['valid_count']} of {hs.size} separations {c['valid_range_sigma']} sigma; "
              f"representative {r['valid_count'] if r else '-'} {r['valid_range_sigma'] if r else ''}")
        el = np.array([np.nan if v is None else v for v in c["extrapolated_load_fraction"]])
        print(f"  extrapolated load fraction: coupled {100 * np.nanmin(el):.2f}-{100 * np.nanmax(el):.2f} %")
        if r:
            ratio = np.array(c["nominal_pressure_MPa"]) / np.array(r["nominal_pressure_MPa"])
            print(f"  p_coupled / p_representative: {np.nanmin(ratio):.3f}-{np.nanmax(ratio):.3f}")
        for name, x in (("coupled", c), ("representative", r)):
            if x and "mu_shear" in x:
                line = (f"  mu_shear {name}: {x['mu_shear_range'][0]:.3f}-{x['mu_shear_range'][1]:.3f}"
                        f" (valid range: {x.get('mu_shear_valid_range')}), interlocking {x['mu_interlocking']:.3f}")
                if "mu_at_measurement" in x:
                    line += (f"; at the measured {x['measured_nominal_pressure_MPa']} MPa: mu "
                             f"{x['mu_at_measurement']} (shear {x['mu_shear_at_measurement']}), "
                             f"measured {x['measured_mu']}")
                print(line)
        print(f"  FE: coupled {c['fe']}; representative {r['fe'] if r else '-'}")
    out = args.out or REPO / "benchmarks" / "results" / f"coupled_{accuracy}.json"
    checks = [family_against_direct()]
    if args.inelastic:  # one Bodner-Partom job per sample of a small population: minutes
        checks.append(family_against_direct(scene_name="rough_aluminum",
                                            samples={"height": 8, "curvature": 4}))
    elif out.exists():  # keep the inelastic comparison of an earlier run
        checks += [c for c in json.loads(out.read_text()).get("family_against_direct", [])
                   if c["scene"] != "asperity_shape_coupled"]
    report["family_against_direct"] = checks
    for check in checks:
        print(f"\n{check['scene']} ({check['accuracy']}, samples {check['samples'] or 'of the scene'}): family of "
              f"{check['aspects']} aspects against one job per sample: jobs {check['jobs']}, CPU s "
              f"{check['cpu_s']}, pressure ratio {check['pressure_family_over_direct']}, area ratio "
              f"{check['area_family_over_direct']}; left-out job {check.get('left_out_job')}")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(report, indent=1) + "\n")
    print(f"\nwritten {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
