"""The documentation's Python example (docs/examples/map_to_interface.py) runs as a user
runs it, and writes what it prints."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "docs" / "examples" / "map_to_interface.py"

pytestmark = pytest.mark.slow


def test_the_python_example_writes_the_interface_it_prints(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLE), str(ROOT / "data" / "topographies" / "di-3.di")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    from asperity.io.netcdf import read_dataset

    law = read_dataset(tmp_path / "map_interface.nc")
    assert list(law["route"].values) == ["interacting", "persson", "boundary_elements"]
    rows = [line.split() for line in proc.stdout.splitlines()[2:]]
    assert len(rows) == 11
    for k, row in enumerate(rows):  # h/sigma, then (p, 'Pa', A, '%') per route
        for i in range(3):
            p, area = float(row[1 + 4 * i]), float(row[3 + 4 * i])
            assert p == pytest.approx(float(law["nominal_pressure"][i, k]), rel=5e-3)
            assert area == pytest.approx(100 * float(law["contact_area_ratio"][i, k]), rel=5e-3)
    p = law["nominal_pressure"].values
    assert np.all(np.diff(p, axis=1) < 0)  # less pressure at larger separations, every route
    assert np.all((law["contact_area_ratio"].values > 0) & (law["contact_area_ratio"].values < 1))
