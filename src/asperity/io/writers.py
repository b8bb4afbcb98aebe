"""Writing input files (profiles, maps) in the formats `asperity.io.inputs` reads."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np


def write_profile(path: str | os.PathLike, x: np.ndarray, z: np.ndarray, *, comment: str = "") -> Path:
    """Write columns x, z to a text file atomically (temporary name, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            for line in comment.splitlines():
                fh.write(f"# {line}\n")
            fh.write("# x z\n")
            np.savetxt(fh, np.column_stack([x, z]), fmt="%.17g")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def write_map(path: str | os.PathLike, z: np.ndarray) -> Path:
    """Write a 2-D height map as .npy atomically."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp.npy", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            np.save(fh, np.asarray(z, float))
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
