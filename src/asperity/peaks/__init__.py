"""Joint probability densities of asperity summits (report 2.4).

* `asperity.peaks.isotropic`: peak height and mean curvature of a Gaussian isotropic
  surface (2.4.1, Nayak / Francis), Greenwood-Williamson's fixed curvature (7.1), and
  the density sampled from the peaks of a height map (2.4.3);
* `asperity.peaks.anisotropic`: peak height, principal curvatures and orientation of a
  Gaussian anisotropic surface (2.4.2; Longuet-Higgins 1957, Nayak 1973, Bush, Gibson
  & Keogh 1979).
"""

from asperity.peaks.isotropic import FixedCurvatureDensity, JointDensity, SampledDensity, francis_density

__all__ = ["francis_density", "JointDensity", "FixedCurvatureDensity", "SampledDensity"]
