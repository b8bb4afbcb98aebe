"""What a workflow run tells the user on the console: the warnings of its jobs, the
error of a failed job in one line, and the progress of a long solve.

Each job writes its log to ``<results>/<scene>/logs/<job>.log`` (`joblog.job_log`:
lines ``<date> <time> <LEVEL> <message>``, a captured Python warning as
``<file>:<line>: <Category>: <message>`` followed by its source line, a failure as
``ERROR failed <job>: <error>`` followed by the traceback).  At the end of a run the
workflow reads the logs its jobs wrote (`logs_since`), groups identical warnings
(`warning_summary`) and names the error of each failed job (`failure_lines`), so a
warning is seen where the run ends, not only in a log file.

`StepProgress` throttles progress lines of a time-marching solve: one INFO line at
most every `interval` seconds of wall time, none in the first `delay` seconds, with
the step reached, the load or slide reached, the Newton iterations of the last step
and the time left, extrapolated linearly in the driving parameter.
"""

from __future__ import annotations

import logging
import math
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

#: a line of a job log: date, time, level, message (`joblog.job_log`'s format)
_LINE = re.compile(r"^\d{4}-\d\d-\d\d \d\d:\d\d:\d\d(?:,\d+)? (?P<level>[A-Z]+) (?P<message>.*)$")
#: the location Python's warnings module puts before a captured warning
_WHERE = re.compile(r"^\S+\.py:\d+: ")
#: longest message shown on the console (the log keeps the whole line)
WIDTH = 240
#: the wall clock of `StepProgress` (seconds; a test sets a fake one)
CLOCK: Callable[[], float] = time.monotonic


@dataclass
class JobLog:
    """What one job's log says: its scene and job, its warnings, its last error."""

    path: Path
    scene: str
    job: str
    warnings: list[str] = field(default_factory=list)
    error: str | None = None

    @property
    def name(self) -> str:
        """'<scene> <job>' (a sample: 'sample <key>'; a study: 'accuracy <study>')."""
        return f"sample {self.job}" if self.scene == "samples" else f"{self.scene} {self.job}"


def job_of(path: str | Path) -> tuple[str, str]:
    """(scene, job) of ``<results>/<scene>/logs/<job>.log``."""
    path = Path(path)
    return path.parent.parent.name, path.stem


def logs_since(results: str | Path, since: float) -> list[Path]:
    """The job logs ``<results>/*/logs/*.log`` written at or after `since` (seconds of the
    epoch, as `time.time`): those of the jobs of a run that started then, in the order
    they were last written."""
    found = []
    for path in Path(results).glob("*/logs/*.log"):
        try:
            mtime = path.stat().st_mtime
        except OSError:  # removed meanwhile
            continue
        if mtime >= since:
            found.append((mtime, path))
    return [path for _, path in sorted(found)]


def _shorten(text: str, width: int = WIDTH) -> str:
    text = " ".join(text.split())
    return text if len(text) <= width else text[: width - 3] + "..."


def read_job_log(path: str | Path) -> JobLog:
    """The warnings (each once, in order, location prefix of a Python warning dropped)
    and the last error line of a job log; lines not in the log format (tracebacks, the
    source line of a warning) are skipped."""
    path = Path(path)
    scene, job = job_of(path)
    entry = JobLog(path, scene, job)
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return entry
    for line in text.splitlines():
        m = _LINE.match(line)
        if m is None:
            continue
        level, message = m.group("level"), m.group("message").strip()
        if level == "WARNING":
            message = _WHERE.sub("", message)
            if message not in entry.warnings:
                entry.warnings.append(message)
        elif level in ("ERROR", "CRITICAL"):
            entry.error = message
    return entry


def _names(entries: list[JobLog], most: int = 3) -> str:
    names = [e.name for e in entries]
    if len(names) <= most:
        return ", ".join(names)
    return f"{', '.join(names[:most])} and {len(names) - most} more jobs"


def warning_summary(logs: Iterable[str | Path], results: str = "results",
                    max_lines: int = 20) -> list[str]:
    """Console lines of the warnings in `logs`: a heading, then one line per distinct
    message, ``  <scene> <job>[, ...]: <message>``, in the order first met, the jobs
    that gave it named (three, then how many more); past `max_lines` lines, one line
    ``and N more in <results>/*/logs``.  Empty if no log has a warning."""
    entries = [read_job_log(p) for p in logs]
    groups: dict[str, list[JobLog]] = {}
    for entry in entries:
        for message in entry.warnings:
            groups.setdefault(message, []).append(entry)
    if not groups:
        return []
    jobs = len({id(e) for group in groups.values() for e in group})
    lines = [f"Warnings of this run: {len(groups)} distinct, from {jobs} job"
             f"{'s' if jobs > 1 else ''} (whole lines in {results}/<scene>/logs/<job>.log):"]
    items = list(groups.items())
    shown = items if len(items) <= max_lines else items[: max_lines - 1]
    for message, group in shown:
        lines.append(f"  {_names(group)}: {_shorten(message)}")
    if len(shown) < len(items):
        lines.append(f"and {len(items) - len(shown)} more in {results}/*/logs")
    return lines


def failure_lines(logs: Iterable[str | Path]) -> list[str]:
    """One line per log of `logs` with an error, ``<scene> <job> failed: <error> (traceback
    in <log>)``, the error being the log's last error line without `job_log`'s
    ``failed <job>:`` (it names the file and the key at fault where the job could)."""
    lines = []
    for path in logs:
        entry = read_job_log(path)
        if entry.error is not None:
            error = entry.error
            if error.startswith("failed ") and ": " in error:
                error = error.partition(": ")[2]
            lines.append(f"{entry.name} failed: {_shorten(error, 2 * WIDTH)} "
                         f"(traceback in {path})")
    return lines


class StepProgress:
    """Throttled progress lines of a time-marching solve, on `logger` at INFO.

    ``update(step, fraction, reached, iterations)`` after each accepted step logs one
    line if the run has gone on for more than `delay` seconds and the last line is
    `interval` seconds old (`clock`, default the module's `CLOCK`, is read once per call):

        <label>step 37 of about 120 (31 %), interference 1.2e-07 of 4e-07 m,
        4 Newton iterations in the last step, about 62 s left

    `fraction` is the share of the driving parameter (time, or levels of a path)
    done; the time left is linear in it, elapsed x (1 - fraction) / fraction; the
    total of an adaptive run is estimated the same way, step / fraction, unless
    `total` is given.  Logging only: nothing the solver computes depends on it.
    """

    def __init__(self, logger: logging.Logger, label: str = "", total: int | None = None,
                 interval: float = 5.0, delay: float = 5.0,
                 clock: Callable[[], float] | None = None):
        self.logger, self.label, self.total = logger, label, total
        self.interval, self.delay = float(interval), float(delay)
        self.clock = clock or CLOCK
        self.start = self.clock()
        self.last = -math.inf
        self.lines = 0

    def update(self, step: int, fraction: float, reached: str, iterations: int) -> str | None:
        """Log (and return) a progress line if one is due, else None."""
        now = self.clock()
        elapsed = now - self.start
        if elapsed <= self.delay or now - self.last < self.interval:
            return None
        self.last = now
        self.lines += 1
        fraction = min(max(float(fraction), 0.0), 1.0)
        if self.total is not None:
            of = f"of {self.total}"
        elif fraction > 0:
            of = f"of about {max(step, round(step / fraction))}"
        else:
            of = "of ?"
        left = (f"about {elapsed * (1.0 - fraction) / fraction:.0f} s left" if fraction > 0
                else "time left unknown")
        line = (f"{self.label}step {step} {of} ({100.0 * fraction:.0f} %), {reached}, "
                f"{iterations} Newton iterations in the last step, {left}")
        self.logger.info("%s", line)
        return line
