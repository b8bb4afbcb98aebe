"""Suite-wide collection order.

`make test` runs the suite on one pytest-xdist worker per core, a test file
per worker at a time (``--dist loadfile --no-loadscope-reorder``), handing
out files in collection order.  The longest files go first, so that none
starts last and leaves the other core idle: those of the workflow runs
(``tests/workflow/``, whose module fixtures run snakemake for minutes), then
the other files that hold tests marked ``slow``, then the rest; within that
order each file keeps its own.
"""

from __future__ import annotations


def pytest_collection_modifyitems(config, items):
    slow_files = {item.path for item in items if item.get_closest_marker("slow")}

    def rank(item):
        if item.path in slow_files:
            return 0 if item.path.parent.name == "workflow" else 1
        return 2

    items.sort(key=rank)  # stable: each file keeps its order
