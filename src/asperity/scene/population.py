"""A scene's asperity population: the ``population``, ``asperity``, ``effects`` and
``adhesion`` sections in SI (report 2.4, 2.5.1, 3.3.3, 8.2, 8.3)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Mapping

from asperity.scene.checks import SceneError, require_geometry
from asperity.scene.units import Units, parses

Config = Mapping[str, Any]

#: what a scene may ask for (config/schema.yaml, `effects`)
EFFECTS = ("plasticity", "damage", "adhesion", "unloading", "friction", "sliding", "finite_strain")
NM = 1e-9


def effects(section: Iterable[str]) -> frozenset[str]:
    """A scene's ``effects``: the physics it calls for, and nothing else (DESIGN.md)."""
    out = frozenset(section)
    unknown = sorted(out - set(EFFECTS))
    if unknown:
        raise SceneError("effects", f"unknown {unknown}", f"known: {', '.join(EFFECTS)}")
    return out


@dataclass(frozen=True)
class Population:
    """How the population is sampled (report 2.4, 2.5.1).

    density: ``nayak``, ``fixed_curvature`` or ``sampled`` (None: the one the surface
    implies); support_threshold: of the effective support; height_range [m] and
    curvature_range [1/m]: the sampling rectangle instead of the support (None: the
    support); histogram_bins of a sampled density; heights, curvatures,
    interferences: the sample counts.
    """

    density: str | None
    support_threshold: float
    height_range: tuple[float, float] | None
    curvature_range: tuple[float, float] | None
    histogram_bins: tuple[int, int]
    heights: int
    curvatures: int
    interferences: int

    @classmethod
    @parses("population")
    def from_section(cls, section: Config, units: Units) -> "Population":
        return cls(
            density=section.get("density"),
            support_threshold=section["support_threshold"],
            height_range=length_range(section.get("height_range"), units),
            curvature_range=curvature_range(section.get("curvature_range"), units),
            histogram_bins=tuple(section["histogram_bins"]),
            heights=section["samples"]["height"],
            curvatures=section["samples"]["curvature"],
            interferences=section["samples"]["interference"],
        )


def length_range(values, units: Units) -> tuple[float, float] | None:
    """A range of heights or separations given in the length unit, in m."""
    if values is None:
        return None
    length = units.length_factor
    lo, hi = (v * length for v in values)
    return lo, hi


def curvature_range(values, units: Units) -> tuple[float, float] | None:
    """A range of curvatures given in 1/(length unit), in 1/m."""
    if values is None:
        return None
    length = units.length_factor
    lo, hi = (v / length for v in values)
    return lo, hi


@dataclass(frozen=True)
class Asperity:
    """The response of one asperity (report 2.6.2, 6.1, 2.5.1, 8.2, 8.3).

    model: ``hertz``, ``constant`` or ``fe``; value: X of the ``constant`` check;
    geometry: ``sphere``, ``paraboloid``, ``cosine`` or ``elliptic`` (fe); mapping:
    ``representative`` or ``coupled`` (cosine); width_to_height: of the
    representative hill (None: from the surface's rms slope); levels: interference
    levels of an elastic FE job; contact: ``penalty`` or ``exact``;
    max_height_fraction, max_radius_fraction: how deep an FE job presses a hill or a
    sphere; velocity [m/s] of the flat (None: not given); unloading_levels,
    unloading_smallest, unloading_check: the computed unloading paths (8.3); scaling:
    ``auto``, ``self_similar`` or ``none``; reference_curvature [1/m] of the computed
    member of a self-similar family (None: the geometric mean of the grid); aspects,
    aspect_check: the FE jobs of the coupled hill's family of aspects (2.5.1, 8.2.2);
    edge_band: inelastic jobs refine their mesh where the plastic contact edge goes
    (the preset's `asperity.fe.presets.EDGE_SIZE`); None (not set): at standard for a
    rate-independent body, and at fine for every body
    (`asperity.population.kinds.inelastic.wants_band`); ratios, yield_multiple: the 3-D
    jobs of elliptic summits (``geometry: elliptic``), how many curvature ratios and how far
    each presses, in interferences of first yield (`asperity.population.kinds.elliptic`).
    """

    model: str
    value: float
    geometry: str | None
    mapping: str
    width_to_height: float | None
    levels: int
    contact: str
    max_height_fraction: float
    max_radius_fraction: float
    velocity: float | None
    unloading_levels: int
    unloading_smallest: float
    unloading_check: bool
    scaling: str
    reference_curvature: float | None
    aspects: int = 6
    aspect_check: bool = False
    edge_band: bool | None = None
    ratios: int = 3
    yield_multiple: float = 1000.0

    @classmethod
    @parses("asperity")
    def from_section(cls, section: Config, units: Units) -> "Asperity":
        length = units.length_factor
        velocity = section.get("velocity")
        reference = section.get("reference_curvature")
        asperity = cls(
            model=section["model"], value=section["value"], geometry=section.get("geometry"),
            mapping=section["mapping"], width_to_height=section.get("width_to_height"),
            levels=section["levels"], contact=section["contact"],
            max_height_fraction=section["max_height_fraction"],
            max_radius_fraction=section["max_radius_fraction"],
            velocity=None if velocity is None else float(velocity) * length,
            unloading_levels=section["unloading_levels"],
            unloading_smallest=section["unloading_smallest"],
            unloading_check=section["unloading_check"], scaling=section["scaling"],
            reference_curvature=reference / length if reference else None,
            aspects=section.get("aspects", 6), aspect_check=section.get("aspect_check", False),
            edge_band=section.get("edge_band"), ratios=section.get("ratios", 3),
            yield_multiple=section.get("yield_multiple", 1000.0),
        )
        require_geometry(section)  # after the keys: a missing one is named first
        return asperity

    @property
    def coupled(self) -> bool:
        """A cosine hill whose amplitude is the sample's peak height (2.5.1)."""
        return self.geometry == "cosine" and self.mapping == "coupled"

    @property
    def aspect_family(self) -> bool:
        """A coupled hill whose samples are scaled from FE jobs at a few aspects
        q = kappa z_p (``scaling: self_similar``; 2.5.1, 8.2.2)."""
        return self.coupled and self.scaling == "self_similar"

    @property
    def shift_invariant(self) -> bool:
        """The response depends on the interference only, not on the peak height."""
        return not self.coupled


@dataclass(frozen=True)
class Adhesion:
    """The Lennard-Jones law of report 3.16, 3.17 in SI: dgamma [J/m^2] the work of
    adhesion, d [m] the equilibrium spacing, cutoff the separation s_c / d beyond
    which the law is dropped. A scene gives the spacing in nm whatever its length
    unit (a molecular length)."""

    dgamma: float
    d: float
    cutoff: float

    @classmethod
    @parses("adhesion")
    def from_section(cls, section: Config) -> "Adhesion":
        return cls(dgamma=float(section["work_of_adhesion"]), d=float(section["spacing"]) * NM,
                   cutoff=float(section["cutoff"]))

    def spec(self) -> dict[str, float]:
        """The law as a sample job's spec holds it."""
        return {"dgamma": self.dgamma, "d": self.d, "cutoff": self.cutoff}
