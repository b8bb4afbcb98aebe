"""Stage 5 of the report's route (2.5): expectation over the asperity population.

`integrate`: the expectation integrals of eqs. 2.5-2.7 (trapezoid or Gauss
cells, or a sum over a map's peaks) and the interface response versus
separation built from a table of asperity responses (`table`: the responses on their
grid, interpolated).  `validity`: where the
homogenized interface holds (extrapolated responses, yield, small strain,
independent asperities).
"""

from asperity.homogenize.integrate import (RULES, Expectation, Quadrature, expectation,
                                           interface_response, quadrature_1d, quadrature_nodes)

__all__ = ["RULES", "Expectation", "Quadrature", "expectation", "interface_response",
           "quadrature_1d", "quadrature_nodes"]
