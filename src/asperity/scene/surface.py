"""A scene's `surface` section as a typed object in SI (report 2.3, 2.4.3).

The section names where the surface comes from (exactly one of a profile, a
set of directional profiles, a map, given statistics, or Greenwood and
Williamson's Gaussian heights) and, for measured data, how it is prepared:

    form:        none | mean | tilt | polynomial (with polynomial_degree)
    filter:      {lambda_c: ..., lambda_s: ...}   ISO 16610-21 / -61 Gaussian, scene length unit
    undefined:   {max_share: 0.5, fill: none | harmonic, islands: drop | keep}
    spectrum:    {window: hann | blackman | none, periodic: false}  (periodic: no window)
    estimator:   sampling | counting | spectral   (which estimate feeds the population)

and, in ``profile`` or ``map``, ``file``, ``unit`` (the length unit of the
file's numbers, where the file does not state it, or to override it),
``spacing`` (scene length unit) and ``channel`` (an instrument file's
channel).  The defaults are those of ``config/schema.yaml``, filled in when
the scene is validated; a section built without them (a library call) asks
for nothing: no form removal, no filter, no fill, no limit on undefined
points, islands of defined points kept, a Hann window, the sampling estimator.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from asperity import units

Config = Mapping[str, Any]

SOURCES = ("profile", "profiles", "map", "statistics", "gaussian_heights")
#: what becomes of the defined points in regions without an interior point
#: (`asperity.surface.islands`): dropped (marked undefined) or kept
ISLANDS = ("drop", "keep")


@dataclass(frozen=True)
class SurfaceScene:
    """The surface section of a scene, lengths in metres."""

    source: str  # one of SOURCES
    section: Mapping[str, Any]  # the source's own subsection, as the scene gives it
    scene_unit: str  # units.length of the scene
    form: str = "none"
    polynomial_degree: int | None = None
    lambda_c: float | None = None
    lambda_s: float | None = None
    max_undefined_share: float = 1.0
    fill: str = "none"
    islands: str = "keep"
    window: str = "hann"
    periodic: bool = False
    estimator: str = "sampling"
    #: the lateral scale of a map's asperities (m): its low pass and its summits
    #: (`asperity.surface.summits`); "auto" for the default rule; None: the pixel's
    scale: float | str | None = None

    @classmethod
    def from_config(cls, surface_cfg: Config, units_cfg: Config) -> "SurfaceScene":
        length = units.length_scale(units_cfg["length"])
        present = [k for k in SOURCES if k in surface_cfg]
        if len(present) != 1:
            raise ValueError(f"surface: exactly one of {', '.join(SOURCES)} is needed; got {present or 'none'}")
        source = present[0]
        filt = surface_cfg.get("filter", {}) or {}
        undefined = surface_cfg.get("undefined", {}) or {}
        spectrum = surface_cfg.get("spectrum", {}) or {}
        kwargs = {}
        if "form" in surface_cfg:
            kwargs["form"] = surface_cfg["form"]
        if surface_cfg.get("form") == "polynomial":
            if "polynomial_degree" not in surface_cfg:
                raise ValueError("key surface.polynomial_degree: form polynomial needs a degree")
            kwargs["polynomial_degree"] = int(surface_cfg["polynomial_degree"])
        for key in ("lambda_c", "lambda_s"):
            if filt.get(key) is not None:
                kwargs[key] = float(filt[key]) * length
        if "max_share" in undefined:
            kwargs["max_undefined_share"] = float(undefined["max_share"])
        if "fill" in undefined:
            kwargs["fill"] = undefined["fill"]
        if "islands" in undefined:
            if undefined["islands"] not in ISLANDS:
                raise ValueError(f"key surface.undefined.islands must be one of {', '.join(ISLANDS)}; "
                                 f"got {undefined['islands']!r}")
            kwargs["islands"] = undefined["islands"]
        if "window" in spectrum:
            kwargs["window"] = spectrum["window"]
        if "periodic" in spectrum:
            kwargs["periodic"] = bool(spectrum["periodic"])
        if kwargs.get("periodic"):  # one period of a periodic surface: the plain periodogram
            kwargs["window"] = "none"
        if "estimator" in surface_cfg:
            kwargs["estimator"] = surface_cfg["estimator"]
        if surface_cfg.get("scale") is not None:
            if source != "map":
                raise ValueError("key surface.scale: a lateral scale applies to a map (surface.map)")
            if filt.get("lambda_s") is not None:
                raise ValueError("key surface.scale: the scale is the map's short-wavelength cut-off; "
                                 "give it or surface.filter.lambda_s, not both")
            value = surface_cfg["scale"]
            kwargs["scale"] = "auto" if value == "auto" else float(value) * length
        scene = cls(source=source, section=surface_cfg[source], scene_unit=units_cfg["length"], **kwargs)
        if scene.lambda_c is not None and scene.lambda_s is not None and not scene.lambda_s < scene.lambda_c:
            raise ValueError("key surface.filter: lambda_s must be shorter than lambda_c")
        return scene

    @property
    def measured(self) -> bool:
        """A profile or map (from a file or generated), as opposed to given statistics."""
        return self.source in ("profile", "map")

    @property
    def generated(self) -> Mapping[str, Any] | None:
        return self.section.get("generate") if self.source in ("profile", "profiles", "map") else None

    @property
    def length(self) -> float:
        """Metres per scene length unit."""
        return units.length_scale(self.scene_unit)

    @property
    def spacing(self) -> float | None:
        """The spacing the scene gives for the file (m), or None; a generated map's own
        (a generated profile's file has its positions)."""
        value = self.section.get("spacing")
        if value is None and self.source == "map" and self.generated:
            value = self.generated["spacing"]
        return None if value is None else float(value) * self.length

    @property
    def file_unit(self) -> str | None:
        """The unit of the file's numbers the scene gives: its own ``unit``; for a surface the
        pipeline generated, the scene's length unit (it was written in it)."""
        if self.generated:
            return self.scene_unit
        return self.section.get("unit")

    @property
    def form_text(self) -> str:
        return {"none": "none", "mean": "mean height", "tilt": "least-squares line or plane (tilt)",
                "polynomial": f"least-squares polynomial of degree {self.polynomial_degree}"}[self.form]

    @property
    def filter_text(self) -> str:
        if self.lambda_c is None and self.lambda_s is None:
            return "none"
        parts = []
        if self.lambda_c is not None:
            parts.append(f"lambda_c = {self.lambda_c:.6g} m")
        if self.lambda_s is not None:
            parts.append(f"lambda_s = {self.lambda_s:.6g} m")
        return "Gaussian filter (ISO 16610-21 profiles, 16610-61 maps), " + ", ".join(parts)
