"""Saving matplotlib figures atomically, with the code version of the stage that drew them."""

from __future__ import annotations

import os
import tempfile
import struct
from pathlib import Path

from asperity.versions import ATTRIBUTE


def save_figure(fig, path: str | os.PathLike, dpi: int = 150, version: str | None = None) -> Path:
    """Save `fig` as PNG to a temporary name in the target folder, then rename;
    `version`: the code version of the stage that drew it (`asperity.versions`),
    kept as the PNG text ``asperity code_version``."""
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".png", dir=path.parent)
    os.close(fd)
    try:
        metadata = {} if version is None else {f"asperity {ATTRIBUTE}": version}
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight", metadata=metadata)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    finally:
        plt.close(fig)
    return path


def figure_version(path: str | os.PathLike) -> str | None:
    """The code version a PNG written by `save_figure` carries (None if it has none)."""
    data = Path(path).read_bytes()
    key = f"asperity {ATTRIBUTE}".encode() + b"\0"
    i = 8  # the PNG signature, then chunks: length, type, data, CRC
    while i + 8 <= len(data):
        (length,), kind = struct.unpack(">I", data[i:i + 4]), data[i + 4:i + 8]
        body = data[i + 8:i + 8 + length]
        if kind == b"tEXt" and body.startswith(key):
            return body[len(key):].decode("latin-1")
        if kind == b"IEND":
            break
        i += 12 + length
    return None
