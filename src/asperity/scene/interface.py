"""What a scene asks of its interface: the ``homogenization`` (report 2.5, 8.3),
``friction`` (9.1) and ``laws`` (section 10) sections in SI."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from asperity import units as units_
from asperity.scene.checks import SceneError
from asperity.scene.population import curvature_range, length_range
from asperity.scene.units import Units, parses

Config = Mapping[str, Any]


@dataclass(frozen=True)
class Homogenization:
    """The expectation integrals (2.5): rule (``trapezoid``, ``gauss``, ``peaks``),
    cells (heights x curvatures), height_range [m] and curvature_range [1/m] (None: the
    density's support), area [m^2] the nominal area A_0; the separations ``start``,
    ``stop``, ``count`` in ``separation_unit`` (``sigma``: of the surface's height
    deviation; ``length``: the scene's length unit, ``length`` m each; ``bearing``:
    material ratios, `separation_values`), and
    unloading_from (in that unit; None: the smallest separation)."""

    rule: str
    cells: tuple[int, int]
    height_range: tuple[float, float] | None
    curvature_range: tuple[float, float] | None
    area: float
    start: float
    stop: float
    count: int
    separation_unit: str
    length: float
    unloading_from: float | None

    @classmethod
    @parses("homogenization")
    def from_section(cls, section: Config, units: Units) -> "Homogenization":
        sep = section["separations"]
        return cls(
            rule=section["rule"], cells=tuple(section["cells"]),
            height_range=length_range(section.get("height_range"), units),
            curvature_range=curvature_range(section.get("curvature_range"), units),
            area=section["area"] * units.length_factor ** 2,
            start=sep["start"], stop=sep["stop"], count=sep["count"], separation_unit=sep["unit"],
            length=units.length_factor, unloading_from=section.get("unloading_from"),
        )

    def separation_scale(self, height_scale: float) -> float:
        """Metres per unit of the separations: `height_scale` (the surface's height
        deviation) in ``sigma``, else the length unit."""
        if self.separation_unit == "bearing":
            raise SceneError("homogenization.unloading_from", "has no scale in separations of unit "
                             "bearing (material ratios)", "give the separations in sigma or length")
        return height_scale if self.separation_unit == "sigma" else self.length

    def separations(self, height_scale: float, heights_at_ratios=None) -> np.ndarray:
        """The separations [m] of the interface (`separation_values`)."""
        return separation_values({"start": self.start, "stop": self.stop, "count": self.count,
                                  "unit": self.separation_unit}, height_scale, self.length,
                                 heights_at_ratios, "homogenization.separations")


def separation_values(section: Config, height_scale: float, length: float, heights_at_ratios=None,
                      key: str = "separations") -> np.ndarray:
    """The separations [m] of a ``separations`` section: ``count`` from ``start`` to
    ``stop``, evenly in ``sigma`` (`height_scale`, the height deviation of the prepared
    surface) or in the length unit (`length` m each); in ``bearing``, start and stop are
    material ratios (the share of the prepared map above the flat, 0 < r <= 1) spaced
    geometrically, each separation the height above which that share lies
    (`heights_at_ratios`, from the map's bearing-area curve): a plateau, a spike or a
    skewed map then has its light-load contact inside the separations, wherever it lies
    in sigma."""
    start, stop, count, unit = section["start"], section["stop"], section["count"], section["unit"]
    if unit != "bearing":
        return np.linspace(start, stop, count) * (height_scale if unit == "sigma" else length)
    if not (0 < start <= 1 and 0 < stop <= 1):
        raise SceneError(key, f"in unit bearing, start and stop are material ratios in (0, 1]; "
                              f"got {start!r} and {stop!r}", "e.g. start: 0.3, stop: 1.0e-4")
    if heights_at_ratios is None:
        raise SceneError(key, "unit bearing needs the bearing-area curve of a measured map "
                              "(surface.nc: bearing_height)", "give the separations in sigma or length")
    return np.asarray(heights_at_ratios(np.geomspace(start, stop, count)), dtype=float)


def check_positive(h, section: Config, heights_at_ratios=None, key: str = "separations") -> None:
    """A periodic interface's mean gap equals its separation: every separation `h` [m] of
    the ``separations`` `section` must be above 0 (the map's mean plane). The error says
    where to start: above 0, or in unit ``bearing`` below the material ratio of the mean
    plane."""
    if np.min(h) > 0:
        return
    fix = "start above 0"
    if section["unit"] == "bearing" and heights_at_ratios is not None:
        ratios = np.geomspace(1e-6, 1.0, 601)
        heights = np.asarray(heights_at_ratios(ratios), dtype=float)
        mean_plane = float(np.interp(0.0, heights[::-1], ratios[::-1]))
        fix = f"start below {mean_plane:.3g}, the material ratio of the map's mean plane"
    raise SceneError(key, "a periodic interface's mean gap equals the separation and cannot be zero "
                          "or negative (full contact)", fix)


@dataclass(frozen=True)
class Measurement:
    """A measured coefficient of friction: label, value, uncertainty, nominal_pressure
    [Pa] of the test (None: not given), and where it is reported."""

    label: str
    value: float
    uncertainty: float | None
    nominal_pressure: float | None
    source: str


@dataclass(frozen=True)
class FrictionEstimate:
    """The report's own estimate, for comparison: shear, interlocking and total
    coefficients, at nominal_pressure [Pa] (None: not given), and where it stands."""

    shear: float | None
    interlocking: float | None
    total: float | None
    nominal_pressure: float | None
    source: str


@dataclass(frozen=True)
class Friction:
    """The static coefficient of friction (9.1): junction_shear_strength tau_s [Pa]
    (None: from the yield stress), interlocking (``mean_absolute_slope``,
    ``rms_slope``, ``none`` or a value), measured coefficients, the report's, and
    the sliding direction(s) [rad from the x axis of the surface] (None: the
    direction-free average; one value, or the ``count`` values of a sweep from
    ``start`` to ``stop``, both included)."""

    junction_shear_strength: float | None
    interlocking: str | float
    measured: tuple[Measurement, ...]
    report: FrictionEstimate | None
    direction: tuple[float, ...] | None = None

    @classmethod
    @parses("friction")
    def from_section(cls, section: Config, units: Units) -> "Friction":
        p = units.pressure_factor

        def pressure(value):
            return None if value is None else float(value) * p

        def number(value):
            return None if value is None else float(value)

        tau = section.get("junction_shear_strength")
        report = section.get("report")
        direction = sliding_directions(section.get("direction"))
        return cls(
            junction_shear_strength=pressure(tau),
            interlocking=section["interlocking"],
            measured=tuple(Measurement(
                label=str(m["label"]), value=float(m["value"]), uncertainty=number(m.get("uncertainty")),
                nominal_pressure=pressure(m.get("nominal_pressure")), source=str(m["source"]))
                for m in section.get("measured") or ()),
            report=None if not report else FrictionEstimate(
                shear=number(report.get("shear")), interlocking=number(report.get("interlocking")),
                total=number(report.get("total")),
                nominal_pressure=pressure(report.get("nominal_pressure")),
                source=str(report["source"])),
            direction=direction,
        )


def sliding_directions(value: Any) -> tuple[float, ...] | None:
    """``friction.direction`` in radians: None (absent);
    a number of degrees; or ``{start, stop, count}`` in degrees, ``count`` >= 1
    directions equally spaced from start to stop, both included (numpy.linspace).
    A non-finite angle, a count below 1 or a sweep of several directions with
    stop == start is a `SceneError` naming the key."""
    key = "friction.direction"
    if value is None:
        return None
    if isinstance(value, Mapping):
        missing = [k for k in ("start", "stop", "count") if k not in value]
        if missing:
            raise SceneError(key, f"a sweep needs start, stop and count; {', '.join(missing)} missing")
        try:
            start, stop = float(value["start"]), float(value["stop"])
            count_f = float(value["count"])
        except (TypeError, ValueError):
            raise SceneError(key, f"start, stop and count must be numbers; got {dict(value)}") from None
        if not (np.isfinite(start) and np.isfinite(stop)):
            raise SceneError(key, f"start {start} and stop {stop} must be finite (degrees)")
        if not np.isfinite(count_f) or count_f != int(count_f) or count_f < 1:
            raise SceneError(key, f"count {value['count']} must be a whole number >= 1")
        count = int(count_f)
        if count > 1 and start == stop:
            raise SceneError(key, f"a sweep of {count} directions needs stop != start (both {start})")
        return tuple(float(t) for t in np.radians(np.linspace(start, stop, count)))
    if isinstance(value, bool):
        raise SceneError(key, f"{value!r}: give degrees, or {{start, stop, count}}")
    try:
        angle = float(value)
    except (TypeError, ValueError):
        raise SceneError(key, f"{value!r}: give degrees, or {{start, stop, count}}") from None
    if not np.isfinite(angle):
        raise SceneError(key, f"{angle} degrees: the direction must be finite")
    return (float(np.radians(angle)),)


#: the laws a scene may fit (section 10)
LAWS = ("oden_martins", "exponential")


@dataclass(frozen=True)
class ApproachOrigin:
    """Where the approach a = h0 - h is zero: at ``separation`` [m], or where the
    loading curve reaches ``pressure`` [Pa]; ``given`` is the value as the scene
    wrote it, ``described`` how the scene put it."""

    separation: float | None
    pressure: float | None
    given: float
    described: str


@dataclass(frozen=True)
class LawsReport:
    """The report's fitted laws (never used in a fit): their parameters in SI by law,
    as printed (in the report's units), and where they stand."""

    values: Mapping[str, Mapping[str, float]]
    printed: str
    source: str


@dataclass(frozen=True)
class Laws:
    """Analytic laws fitted to the loading curve (section 10): which, the residual
    (``absolute``: 10.43; ``log``), the fit window pressure_range [Pa] (None: every
    positive pressure), approach_origin (None: the largest separation), the gap g
    of 10.42 fixed [m] (None: fitted), and the report's fits."""

    laws: tuple[str, ...]
    residual: str
    pressure_range: tuple[float, float] | None
    approach_origin: ApproachOrigin | None
    gap: float | None
    report: LawsReport | None

    @classmethod
    @parses("laws")
    def from_section(cls, section: Config, units: Units) -> "Laws":
        window = section.get("pressure_range")
        gap = (section.get("oden_martins") or {}).get("gap")
        return cls(
            laws=tuple(section["laws"]), residual=section["residual"],
            pressure_range=None if window is None else tuple(
                np.asarray(window, float) * units.pressure_factor),
            approach_origin=_origin(section.get("approach_origin"), units),
            gap=None if gap is None else float(gap) * units.length_factor,
            report=_report(section.get("report")),
        )


def _origin(origin: Config | None, units: Units) -> ApproachOrigin | None:
    if origin is None:
        return None
    if "separation" in origin:
        given = origin["separation"]
        return ApproachOrigin(separation=float(given) * units.length_factor, pressure=None,
                              given=given, described=f"separation {given} {units.length}")
    given = origin["pressure"]
    return ApproachOrigin(separation=None, pressure=float(given) * units.pressure_factor, given=given,
                          described=f"where the pressure reaches {given} {units.pressure}")


def _report(report: Config | None) -> LawsReport | None:
    """The report's fits in SI, from values in its own units."""
    if not report:
        return None
    ru = report["units"]
    ps, ls = units_.pressure_scale(ru["pressure"]), units_.length_scale(ru["length"])
    scale = {"c": ps, "g": ls, "m": 1.0, "decay_length": ls}
    unit_of = {"c": ru["pressure"], "g": ru["length"], "m": "", "decay_length": ru["length"]}
    laws = [law for law in LAWS if law in report]
    printed = [f"{law}: " + ", ".join(f"{k} = {v} {unit_of.get(k, '')}".rstrip()
                                      for k, v in report[law].items()) for law in laws]
    return LawsReport(
        values={law: {k: float(v) * scale[k] for k, v in report[law].items() if k in scale}
                for law in laws},
        printed="; ".join(printed), source=str(report["source"]))
