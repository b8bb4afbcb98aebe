"""A scene's sections as typed objects in SI (DESIGN.md: the library, by stage).

A scene file (config/scenes/<name>.yaml) writes its values in its own units; the
workflow validates it against config/schema.yaml, which fills in every default (the
defaults live there and nowhere else). This package turns each section into a
frozen dataclass in SI, once, so that the physics packages take objects and never
read a scene's dictionaries:

- `units`: `Units` (the scene's length and pressure units);
- `materials`: `Material` from the ``material`` section, and `build`, the one place a
  material becomes the `asperity.fe` body (elastic, J2, Bodner-Partom; 3.2), with
  `kinematics`, the body's small or finite strain;
- `population`: `Population`, `Asperity`, `Adhesion` and `effects` (2.4, 8.2, 3.16);
- `interface`: `Homogenization` (2.5), `Friction` (9.1), `Laws` (section 10);
- `uniaxial`: `UniaxialTest`, one material-point test (5, 6.3.1, 8.2.1);
- `sliding`: `Sliding`, the 3-D asperity pressed and slid (9.2);
- `plane_strain`: `PlaneStrain`, a plane-strain asperity pressed by the flat (6.3.2, 6.3.3).

`checks`: `SceneError` (``<file>: <key>: <what> (<fix>)``), and `check_scene`, the
checks the schema cannot make (an FE asperity's geometry, sizes that say a unit is
wrong), which the typed objects above also make. The `surface` section is read by
`asperity.stages.surface`.
"""

from asperity.scene.checks import SceneError, check_scene
from asperity.scene.interface import Friction, Homogenization, Laws
from asperity.scene.materials import Material, build, kinematics
from asperity.scene.plane_strain import PlaneStrain
from asperity.scene.population import Adhesion, Asperity, Population, effects
from asperity.scene.sliding import Sliding
from asperity.scene.uniaxial import UniaxialTest
from asperity.scene.units import Units, length_factor

__all__ = ["Adhesion", "Asperity", "Friction", "Homogenization", "Laws", "Material", "PlaneStrain",
           "Population", "SceneError", "Sliding", "UniaxialTest", "Units", "build", "check_scene", "effects", "kinematics",
           "length_factor"]
