"""Figures drawn from the pipeline's datasets (never from files).

The matplotlib backend is set here, once, before any submodule imports pyplot:
figures are written to files on machines without a screen.
"""

import matplotlib

matplotlib.use("Agg")

from asperity.plots.figures import *  # noqa: E402,F401,F403
from asperity.plots.surface import *  # noqa: E402,F401,F403
