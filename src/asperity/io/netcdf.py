"""The netCDF contract of DESIGN.md: writers and readers of result files.

Every file is a self-describing xarray Dataset: ``units`` and ``long_name``
on every variable and coordinate, global attributes ``scene``, ``title``,
``history``, ``source`` (package version), ``config`` (the YAML of the
configuration subtree that produced the file) and ``code_version`` (the version
of the stage's code, `asperity.versions`).  Files are written to a
temporary name in the target folder and renamed, so a failed or killed job
never leaves a file that looks finished.
"""

from __future__ import annotations

import datetime as _dt
import glob
import os
import tempfile
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import xarray as xr
import yaml

from asperity import __version__
from asperity.versions import ATTRIBUTE

REQUIRED_ATTRS = ("units", "long_name")


class ContractError(ValueError):
    """A dataset does not meet the netCDF contract of DESIGN.md."""


def missing_attributes(ds: xr.Dataset) -> list[str]:
    """Names of variables or coordinates lacking ``units`` or ``long_name``."""
    bad = []
    for name, var in {**ds.coords, **ds.data_vars}.items():
        lacking = [a for a in REQUIRED_ATTRS if a not in var.attrs]
        if lacking:
            bad.append(f"{name} (no {', '.join(lacking)})")
    return bad


def _plain(obj: Any) -> Any:
    """Config values as plain YAML-able Python objects (numpy scalars included)."""
    if isinstance(obj, Mapping):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def config_yaml(config: Mapping[str, Any] | None) -> str:
    return yaml.safe_dump(_plain(dict(config or {})), sort_keys=True)


def _encodable(ds: xr.Dataset) -> xr.Dataset:
    """Booleans become int8 with a ``flag_values`` note (netCDF has no bool)."""
    out = ds.copy()
    for name, var in {**out.coords, **out.data_vars}.items():
        if var.dtype == bool:
            attrs = dict(var.attrs)
            attrs.setdefault("flag_values", "0 1")
            attrs.setdefault("flag_meanings", "false true")
            out[name] = var.astype("int8").assign_attrs(attrs)
    return out


def write_dataset(
    ds: xr.Dataset,
    path: str | os.PathLike,
    *,
    scene: str,
    title: str,
    config: Mapping[str, Any] | None = None,
    version: str | None = None,
) -> Path:
    """Write `ds` atomically to `path` under the netCDF contract.

    `version`: the code version of the stage that computed it
    (`asperity.versions.code_version`), kept in the attribute ``code_version``.
    Raises ContractError, before anything is written, when a variable or
    coordinate lacks ``units`` or ``long_name``.
    """
    path = Path(path)
    bad = missing_attributes(ds)
    if bad:
        raise ContractError(f"{path}: cannot write, missing attributes on: {'; '.join(bad)}")
    ds = _encodable(ds)
    ds.attrs.update(
        scene=scene,
        title=title,
        history=f"{_dt.datetime.now(_dt.timezone.utc).isoformat(timespec='seconds')} "
        f"written by asperity {__version__}",
        source=f"asperity {__version__}",
        config=config_yaml(config),
    )
    if version is not None:
        ds.attrs[ATTRIBUTE] = version
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp.nc", dir=path.parent)
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine="netcdf4")
        # mkstemp makes the file private (0600); give the result the permissions
        # of any file the user creates (0666 less the umask), e.g. group-readable
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    # what a killed earlier write of this file left behind (never read: hidden name)
    for stale in path.parent.glob(f".{glob.escape(path.name)}.*.tmp.nc"):
        stale.unlink(missing_ok=True)
    return path


def read_dataset(path: str | os.PathLike) -> xr.Dataset:
    """Open a result file fully into memory and close it.

    Integer flag variables written from booleans are turned back into bool.
    """
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such result file")
    with xr.open_dataset(path, engine="netcdf4") as ds:
        ds = ds.load()
    for name, var in {**ds.coords, **ds.data_vars}.items():
        if var.attrs.get("flag_meanings") == "false true":
            ds[name] = var.astype(bool).assign_attrs(var.attrs)
    return ds


def scene_config(ds: xr.Dataset) -> dict:
    """The config subtree stored in a result file's ``config`` attribute."""
    return yaml.safe_load(ds.attrs.get("config", "{}")) or {}
