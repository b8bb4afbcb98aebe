"""Logging of one pipeline job to its log file, with progress and failures.

A job's log holds its progress lines (so long work is visible with
``tail -f``) and, if it fails, the error and its traceback.  On the console the
failure is one line (the error, and where its traceback is), and the job exits
with status 1, so that the workflow manager sees it fail and the user sees no
traceback; an interrupt is passed on as it is.
"""

from __future__ import annotations

import contextlib
import logging
import sys
import time
import warnings
from pathlib import Path
from typing import Iterator

log = logging.getLogger("asperity")


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
        with warnings.catch_warnings():
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
