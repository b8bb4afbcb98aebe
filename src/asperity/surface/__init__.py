"""Stage 1-2 of the report's route (section 2): a rough surface's statistics.

* `form` -- form removal (mean, tilt, polynomial) by least squares;
* `filters` -- the Gaussian profile and areal filters of ISO 16610-21/-61;
* `missing` -- undefined points: masks, runs, complete neighbourhoods, harmonic in-fill;
* `statistics` -- profile statistics by sampling, counting and spectrum on
  the dimension ``estimator`` (2.3.1);
* `directional` -- the spectral moments of an anisotropic surface from
  profiles in several directions, and their invariants (2.3.2);
* `spectra` -- periodograms with a choice of window, the radially averaged
  PSD of maps, autocorrelation (2.2, 2.3.1);
* `maps` -- map statistics and the peaks of maps (2.4.3);
* `distribution` -- skewness, kurtosis, bearing-area curve: is it Gaussian? (2.4.1, 2.4.3);
* `synthetic` -- random-phase series (2.3, eq. 2.4), the report's example
  profiles (2.6.1), anisotropic series (2.3.2), Gaussian random maps.
"""

from asperity.surface.directional import *  # noqa: F401,F403
from asperity.surface.distribution import *  # noqa: F401,F403
from asperity.surface.filters import *  # noqa: F401,F403
from asperity.surface.form import *  # noqa: F401,F403
from asperity.surface.maps import *  # noqa: F401,F403
from asperity.surface.missing import *  # noqa: F401,F403
from asperity.surface.spectra import *  # noqa: F401,F403
from asperity.surface.statistics import *  # noqa: F401,F403
from asperity.surface.synthetic import *  # noqa: F401,F403
from asperity.surface import (directional, distribution, filters, form, maps, missing, spectra, statistics,
                              synthetic)

__all__ = [name for module in (distribution, filters, form, maps, missing, spectra, statistics, directional,
                               synthetic)
           for name in module.__all__]
