"""Stage 1-2 of the report's route (section 2): a rough surface's statistics.

`statistics`: profile and map statistics by sampling, counting and spectrum,
directional moments and invariants, peaks of maps, and the random-phase
series used to verify them (2.3, 2.4.3, 2.6.1).
"""

from asperity.surface.statistics import *  # noqa: F401,F403
from asperity.surface.statistics import __all__  # noqa: F401
