"""The README's quickstart, as a user runs it: its commands, on a shared topography file,
in a copy of the workflow, make the files it names."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import REPO, copy_workflow, result

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

BIN = Path(sys.executable).parent


def quickstart_commands() -> list[list[str]]:
    """The commands of the README's quickstart block (the environment's activation aside)."""
    text = (REPO / "README.md").read_text()
    section = text.split("## Quickstart", 1)[1].split("\n## ", 1)[0]
    block = re.search(r"\n((?:    .+\n)+)", section).group(1)
    lines = [line.strip() for line in block.splitlines()]
    return [shlex.split(line) for line in lines if line and not line.startswith("source ")]


def test_the_quickstart_makes_what_it_names(tmp_path):
    commands = quickstart_commands()
    assert [c[0] for c in commands] == ["asperity", "snakemake", "asperity"]
    workdir = copy_workflow(tmp_path)
    outputs = []
    for argv in commands:
        proc = subprocess.run([str(BIN / argv[0]), *argv[1:]], cwd=workdir, capture_output=True,
                              text=True, timeout=900)
        assert proc.returncode == 0, (argv, proc.stdout, proc.stderr)
        outputs.append(proc.stdout + proc.stderr)
    scene = commands[0][3]
    for target in commands[1][3:]:  # the files the snakemake line names
        assert (workdir / target).stat().st_size > 0, target
    interface = result(workdir, scene, "interface.nc")
    p = interface["nominal_pressure"].values
    assert p[0] > p[-1] >= 0  # more pressure at smaller separations
    # the material given by name reached the file: the named aluminum's E and nu, in MPa
    import yaml

    from asperity.scene.materials import named_materials

    aluminum = named_materials()["aluminum"]
    material = yaml.safe_load(interface.attrs["config"])["material"]
    assert material["youngs_modulus"] == pytest.approx(aluminum.youngs_modulus / 1e6, rel=1e-12)
    assert material["poisson"] == pytest.approx(aluminum.poisson, rel=1e-12)
    # asperity show: where the result holds; the end-of-run summary names the scene's jobs
    assert "valid" in outputs[2]
    assert f"{scene} surface" in outputs[1]
