"""asperity: contact and friction interface models from the microscale up.

Implements the method of Oden, Martins, Lee, Rabier, Demkowicz et al. (1993),
"New micro- and macroscopic models of contact and friction": surface
statistics -> asperity statistics -> single-asperity response ->
statistical expectation over the asperity population.

One package per stage of that route (DESIGN.md, layout): `surface`,
`peaks`, `population`, `fe`, `unloading`, `homogenize`, `friction`, `laws`;
beside them `scene` (a scene's sections as SI objects), `references` (closed
forms), `studies` (what accuracy costs), `uniaxial` (material points), `plots`,
`io` (the disk), `stages` (what the workflow scripts call), `versions` (the code
version of each stage), `units` and `cli` (``asperity show``).
"""

__version__ = "0.1.0"
