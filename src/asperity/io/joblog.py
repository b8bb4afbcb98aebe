"""Logging of one pipeline job to its log file, with progress and failures.

A job's log holds its progress lines (so long work is visible with
``tail -f``) and, if it fails, the error and its traceback.  On the console the
failure is one line (the error, and where its traceback is), and the job exits
with status 1, so that the workflow manager sees it fail and the user sees no
traceback; an interrupt is passed on as it is.

With the environment variable ``ASPERITY_PROFILE`` naming a directory, a job also
runs under :mod:`cProfile` and leaves there ``<host>-<pid>.prof`` (its profile) and
``<host>-<pid>.json`` (its name, log, how long the process ran before the job began:
interpreter, Snakemake's preamble and imports, and the job's own time), which
``make bench CASE=profile`` sums over a whole run.
"""

from __future__ import annotations

import contextlib
import cProfile
import json
import logging
import os
import socket
import sys
import time
import warnings
from pathlib import Path
from typing import Iterator

log = logging.getLogger("asperity")

#: the environment variable naming the directory of the jobs' profiles
PROFILE_ENV = "ASPERITY_PROFILE"


def process_age() -> float | None:
    """Seconds since this process started (Linux: /proc, 10 ms), None elsewhere."""
    try:
        stat = Path("/proc/self/stat").read_text()
        started = int(stat.rsplit(")", 1)[1].split()[19]) / os.sysconf("SC_CLK_TCK")
        return float(Path("/proc/uptime").read_text().split()[0]) - started
    except (OSError, ValueError, IndexError):
        return None


@contextlib.contextmanager
def _profiled(path: Path, name: str) -> Iterator[None]:
    """Profile the block into `ASPERITY_PROFILE` if it is set (module docstring)."""
    folder = os.environ.get(PROFILE_ENV)
    if not folder:
        yield
        return
    record = {"name": name, "log": str(path), "before_job_s": process_age(), "ok": False}
    profiler = cProfile.Profile()
    start = time.perf_counter()
    profiler.enable()
    try:
        yield
        record["ok"] = True
    finally:
        profiler.disable()
        record["job_s"] = time.perf_counter() - start
        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        stem = f"{socket.gethostname()}-{os.getpid()}"  # unique on a cluster's nodes too
        profiler.dump_stats(out / f"{stem}.prof")
        (out / f"{stem}.json").write_text(json.dumps(record))


@contextlib.contextmanager
def job_log(path: str | Path, name: str = "") -> Iterator[logging.Logger]:
    """Send the ``asperity`` logger and warnings to `path` for the duration."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(path, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    log.addHandler(handler)
    log.setLevel(logging.INFO)
    logging.captureWarnings(True)
    logging.getLogger("py.warnings").addHandler(handler)
    start = time.perf_counter()
    log.info("start %s", name)
    try:
        with warnings.catch_warnings(), _profiled(path, name):
            warnings.simplefilter("default")
            yield log
    except Exception as err:
        log.exception("failed %s: %s", name, err)
        print(f"error: {name}: {err} (traceback in {path})", file=sys.stderr, flush=True)
        raise SystemExit(1) from None
    except BaseException as err:
        log.exception("failed %s: %s", name, err)
        raise
    else:
        log.info("done %s in %.3f s", name, time.perf_counter() - start)
    finally:
        logging.getLogger("py.warnings").removeHandler(handler)
        log.removeHandler(handler)
        handler.close()
