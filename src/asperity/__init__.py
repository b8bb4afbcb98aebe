"""asperity: contact and friction interface models from the microscale up.

Implements the method of Oden, Martins, Lee, Rabier, Demkowicz et al. (1993),
"New micro- and macroscopic models of contact and friction": surface
statistics -> asperity statistics -> single-asperity response ->
statistical expectation over the asperity population.
"""

__version__ = "0.1.0"
