"""A fresh copy of the repository's workflow, to run Snakemake on without
touching the repository's own results/ and .snakemake/ (the workflow tests in
tests/workflow/ and the scene timing of benchmarks/scenes.py both use it)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
#: the snakemake of the running interpreter's environment (.venv/bin/snakemake)
SNAKEMAKE = Path(sys.executable).with_name("snakemake")


def copy_workflow(dest: Path) -> Path:
    """Snakefile, config/, workflow/, profiles/ and data/ copied to `dest` (results go
    there too); Snakemake finds the default profile there (profiles/default)."""
    dest = Path(dest)
    shutil.copy(REPO / "Snakefile", dest / "Snakefile")
    shutil.copytree(REPO / "config", dest / "config")
    shutil.copytree(REPO / "workflow", dest / "workflow")
    shutil.copytree(REPO / "profiles", dest / "profiles")
    if (REPO / "data").exists():
        shutil.copytree(REPO / "data", dest / "data")
    return dest
