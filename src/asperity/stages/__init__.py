"""What the workflow scripts call: one module per rules file (DESIGN.md, task graph).

`workflow/rules/X.smk` -> `workflow/scripts/X*.py` -> `asperity.stages.X` -> the science
packages. Each function takes the datasets of the previous stage and the scene's
configuration subtrees (as a scene file spells them, in the scene's units, with the
defaults of config/schema.yaml), turns the subtrees into `asperity.scene` objects and
returns the dataset (or figure) of its stage, in SI. They know nothing of files or of
the workflow manager: the scripts read, call one of these, and write through
`asperity.io`.

Modules: `surface`, `population`, `homogenize`, `friction`, `figures`, `accuracy`,
`uniaxial`, `sliding`.
"""
