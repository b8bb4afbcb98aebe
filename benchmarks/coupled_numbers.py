"""The numbers of the README's subsection "The coupled hill family": the scenes with
coupled hills scaled from a family of aspects (report 2.5.1, 8.2.2) beside the same
scenes with the representative hill (8.2.2).

Reads a results tree made by the pipeline (default ``results/``), e.g. after

    snakemake --cores 1 --config 'scenes=[rough_aluminum_coupled,steel_glass_bead_coupled]' \
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

Writes benchmarks/results/coupled_<accuracy>.json.

    python benchmarks/coupled_numbers.py [results]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
PAIRS = (("steel_glass_bead_coupled", "steel_glass_bead"), ("rough_aluminum_coupled", "rough_aluminum"))
INDICATORS = ("extrapolated_load_fraction", "extrapolated_fraction", "large_strain_fraction",
              "yielded_fraction", "contact_area_ratio", "interaction")


def _loading(ds):
    if "branch" in ds.dims:
        return ds.sel(branch="loading")
    return ds


def _float(x) -> float | None:
    x = float(x)
    return None if not np.isfinite(x) else x


def scene_numbers(results: Path, scene: str) -> dict:
    from asperity.io.netcdf import read_dataset
    from asperity.population.density import height_scale

    d = results / scene
    interface = _loading(read_dataset(d / "interface.nc"))
    sigma = height_scale(read_dataset(d / "surface.nc"))
    asperities = read_dataset(d / "asperities.nc")
    h = interface["separation"].values
    out = {"sigma_um": sigma * 1e6, "separation_sigma": list(h / sigma),
           "nominal_pressure_MPa": list(interface["nominal_pressure"].values / 1e6),
           "valid": [bool(v) for v in interface["valid"].values],
           "validity": [str(v) for v in interface["validity"].values]}
    for name in INDICATORS:
        if name in interface:
            out[name] = [_float(v) for v in interface[name].values]
    valid = interface["valid"].values.astype(bool)
    out["valid_range_sigma"] = ([float(h[valid].min() / sigma), float(h[valid].max() / sigma)]
                                if valid.any() else None)
    out["valid_count"] = int(valid.sum())
    cost = {k: asperities.attrs[k] for k in ("accuracy", "fe_jobs", "fe_cpu_time") if k in asperities.attrs}
    cost.update({k: float(v) for k, v in asperities.attrs.items() if k.startswith("aspect_check")})
    if "aspects" in asperities.attrs:
        cost["aspects"] = [float(q) for q in np.atleast_1d(asperities.attrs["aspects"])]
    out["fe"] = cost
    if (d / "friction.nc").exists():
        fr = read_dataset(d / "friction.nc")
        fr_load = _loading(fr)
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


def main(argv: list[str]) -> int:
    results = Path(argv[0]) if argv else REPO / "results"
    report = {"results": str(results), "scenes": {}}
    accuracy = "unknown"
    for coupled, representative in PAIRS:
        if not (results / coupled / "interface.nc").exists():
            print(f"{coupled}: no {results / coupled / 'interface.nc'}; run the scene first")
            continue
        c = scene_numbers(results, coupled)
        r = scene_numbers(results, representative) if (results / representative / "interface.nc").exists() else None
        report["scenes"][coupled] = c
        if r is not None:
            report["scenes"][representative] = r
        accuracy = c["fe"].get("accuracy", accuracy)
        print(f"\n{coupled} (against {representative}), loading branch, sigma = {c['sigma_um']:.3g} um")
        print("  h/sigma  p_coupled  p_repr  ratio  extrap.load(c/r)  large_strain  yielded  area   inter.  validity")
        hs = np.array(c["separation_sigma"])
        step = max(1, hs.size // 10)
        for i in list(range(0, hs.size, step)) + ([hs.size - 1] if (hs.size - 1) % step else []):
            pc = c["nominal_pressure_MPa"][i]
            pr = r["nominal_pressure_MPa"][i] if r else float("nan")
            el_r = r["extrapolated_load_fraction"][i] if r else float("nan")

            def g(name):
                v = c.get(name, [None] * hs.size)[i]
                return float("nan") if v is None else v

            print(f"  {hs[i]:6.3f}  {pc:9.4g}  {pr:8.4g}  {pc / pr:5.3f}  "
                  f"{100 * g('extrapolated_load_fraction'):5.1f}/{100 * el_r:5.1f} %  "
                  f"{100 * g('large_strain_fraction'):5.1f} %  {100 * g('yielded_fraction'):5.1f} %  "
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
    out = REPO / "benchmarks" / "results" / f"coupled_{accuracy}.json"
    out.write_text(json.dumps(report, indent=1) + "\n")
    print(f"\nwritten {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
