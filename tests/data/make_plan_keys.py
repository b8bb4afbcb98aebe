"""Write tests/data/plan_keys.json.gz: the sample keys and job specs of every plan of a
finished default run (`snakemake --cores 2`), with the configuration each plan was made
from and the surface section of its scene.

    python tests/data/make_plan_keys.py RESULTS [SCENE_DIR]

The file in the repository was made from a default run of the code before the asperity
kinds moved into a registry (commit 352e06e); tests/test_plan_keys.py checks that the
plans made now from the same inputs give the same keys and specs, byte for byte, so that
no finished FE sample is rerun after an upgrade that changes no FE job; a deliberate change
of some jobs' specs is listed there (``CHANGES``), and the record stays the baseline.
"""

from __future__ import annotations

import gzip
import json
import sys
from pathlib import Path

import yaml

from asperity.io.netcdf import read_dataset, scene_config

OUT = Path(__file__).with_name("plan_keys.json.gz")


def plan_record(plan_file: Path, scene_dir: Path) -> dict:
    plan = read_dataset(plan_file)
    keys = [str(k) for k in plan["key"].values]
    specs: dict[str, str] = {}
    for key, spec in zip(keys, plan["spec"].values):
        specs.setdefault(key, str(spec))
    scene = yaml.safe_load((scene_dir / f"{plan_file.parent.name}.yaml").read_text())
    return {"config": scene_config(plan), "surface": scene["surface"], "keys": keys, "specs": specs}


def main(results: str, scene_dir: str = "config/scenes") -> None:
    plans = sorted(Path(results).glob("*/plan.nc"))
    if not plans:
        raise SystemExit(f"{results}: no */plan.nc")
    data = {p.parent.name: plan_record(p, Path(scene_dir)) for p in plans if "@" not in p.parent.name}
    OUT.write_bytes(gzip.compress(json.dumps(data, sort_keys=True, indent=1).encode(), mtime=0))
    print(f"{OUT}: {len(data)} plans, {sum(len(d['specs']) for d in data.values())} distinct keys")


if __name__ == "__main__":
    main(*sys.argv[1:])
