"""A plane-strain asperity pressed by a rigid flat (report 6.3.2, 6.3.3): a scene's
``plane_strain`` section in SI, with its ``material`` and ``effects``, and the
`asperity.fe` objects it describes."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from asperity.scene.materials import Material, build, kinematics
from asperity.scene.units import Units, parses

Config = Mapping[str, Any]

SHAPES = ("cylinder", "truncated_v")
#: the effects a plane-strain study simulates (`plasticity` required: it compares the
#: inelastic body with its elastic twin; `unloading` takes the flat back after the load)
EFFECTS = ("plasticity", "damage", "finite_strain", "unloading")


@dataclass(frozen=True)
class PlaneStrain:
    """The section (``shape`` ``cylinder``: ``radius`` [m] and the cap's half angle
    ``cap_angle`` [deg]; ``truncated_v``: V grooves of included angle ``groove_angle``
    [deg] at ``pitch`` [m], the ridges between them truncated to a flat top
    ``top_width`` [m] wide), pressed ``max_interference`` [m] at ``velocity`` [m/s];
    ``points`` interference levels; ``meshes``: name -> accuracy preset overrides;
    ``test_load`` [N/m], the experiment's load per unit length of one asperity (drawn
    for comparison, None: not drawn); the scene's ``material`` and ``effects``."""

    shape: str
    radius: float | None
    cap_angle: float
    pitch: float | None
    groove_angle: float
    top_width: float | None
    max_interference: float
    velocity: float
    points: int
    meshes: Mapping[str, Mapping[str, Any]]
    test_load: float | None
    material: Material
    effects: tuple[str, ...]

    def __post_init__(self):
        if self.shape not in SHAPES:
            raise ValueError(f"plane_strain.section.shape must be one of {SHAPES}, "
                             f"got {self.shape!r}")
        if self.shape == "truncated_v" and not self.top_width < self.pitch:
            raise ValueError("plane_strain.section: top_width must be smaller than the pitch")
        other = [e for e in self.effects if e not in EFFECTS]
        if other or "plasticity" not in self.effects:
            raise ValueError(f"effects: a plane_strain scene presses an inelastic body "
                             f"(`plasticity`, with {EFFECTS[1:]} if asked); "
                             f"got {list(self.effects)}")

    @classmethod
    @parses("plane_strain")
    def from_scene(cls, scene: Config) -> "PlaneStrain":
        """The ``plane_strain``, ``material``, ``units`` and ``effects`` of a validated scene."""
        units = Units.from_section(scene["units"])
        length = units.length_factor
        section = scene["plane_strain"]
        s = section["section"]
        return cls(
            shape=s["shape"],
            radius=s["radius"] * length if "radius" in s else None,
            cap_angle=float(s["cap_angle"]),
            pitch=s["pitch"] * length if "pitch" in s else None,
            groove_angle=float(s["groove_angle"]),
            top_width=s["top_width"] * length if "top_width" in s else None,
            max_interference=section["max_interference"] * length,
            velocity=section["velocity"] * length,
            points=int(section["points"]),
            meshes={str(k): dict(v or {}) for k, v in section["meshes"].items()},
            test_load=float(section["test_load"]) if "test_load" in section else None,
            material=Material.from_scene(scene["material"], units),
            effects=tuple(scene["effects"]),
        )

    @property
    def sharp_ridge_height(self) -> float:
        """Height of the untruncated ridge between two V grooves at the pitch [m]."""
        return 0.5 * self.pitch / math.tan(math.radians(0.5 * self.groove_angle))

    def geometry(self):
        """The `Cylinder` (a circular cap of ``cap_angle`` on the block) or the
        `TruncatedV` ridge: half width ``top_width / 2`` on top, flanks at half the
        groove angle from the vertical reaching the neighbouring grooves' bottom half a
        pitch from the axis."""
        from asperity.fe.discretization.geometry import Cylinder, TruncatedV

        if self.shape == "cylinder":
            return Cylinder(self.radius, cap_angle_deg=self.cap_angle)
        half = 0.5 * self.top_width
        height = (0.5 * self.pitch - half) / math.tan(math.radians(0.5 * self.groove_angle))
        return TruncatedV(half, height, included_angle_deg=self.groove_angle)

    def body(self):
        """The body under the scene's effects (`asperity.scene.materials.build`)."""
        return build(self.material, self.effects)

    @property
    def kinematics(self) -> str:
        """The inelastic body's kinematics under the scene's effects (`kinematics`)."""
        return kinematics(self.effects)

    def elastic(self):
        """The elastic twin: the material's E and nu, no inelastic mechanism."""
        return build(self.material, ())

    @property
    def unloading(self) -> bool:
        """Whether the flat goes back after the load (effect ``unloading``)."""
        return "unloading" in self.effects

    def history(self):
        """Loading at ``velocity`` from first touch to ``max_interference``; with the
        effect ``unloading`` the flat then goes back at the same speed (towards zero
        interference: the run stops where the force has returned to zero,
        `asperity.fe.solve_asperity_history`)."""
        from asperity.fe.drivers.inelastic import History

        if self.unloading:
            return History.load_unload(self.max_interference, self.velocity)
        return History.loading(self.max_interference, self.velocity)

    def presets(self, accuracy: str) -> dict[str, dict]:
        """Mesh name -> the accuracy preset `accuracy` with the mesh's overrides."""
        return {name: {"base": accuracy, **overrides} for name, overrides in self.meshes.items()}
