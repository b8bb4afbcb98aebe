"""Units a scene may declare, and their factors to SI.

Files written by the pipeline are in SI base units (DESIGN.md, netCDF
contract); scenes and input files may use the units of the report
(micrometres, kG/mm^2, N/cm^2, ...).  Conversion happens once, when a
scene or an input file is read.
"""

from __future__ import annotations

LENGTH = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "um": 1e-6,
    "nm": 1e-9,
    "1": 1.0,  # dimensionless scenes (the report's verification examples)
}

PRESSURE = {
    "Pa": 1.0,
    "kPa": 1e3,
    "MPa": 1e6,
    "GPa": 1e9,
    "N/mm^2": 1e6,
    "N/cm^2": 1e4,
    "kG/mm^2": 9.80665e6,  # kilogram-force per square millimetre (report 7.1)
    "1": 1.0,
}

ENERGY_PER_AREA = {"J/m^2": 1.0, "mJ/m^2": 1e-3, "1": 1.0}


def _factor(table: dict[str, float], unit: str, kind: str) -> float:
    try:
        return table[unit]
    except KeyError:
        known = ", ".join(sorted(table))
        raise ValueError(f"unknown {kind} unit {unit!r}; known: {known}") from None


def length_scale(unit: str) -> float:
    """Metres per `unit`."""
    return _factor(LENGTH, unit, "length")


def pressure_scale(unit: str) -> float:
    """Pascals per `unit`."""
    return _factor(PRESSURE, unit, "pressure")


def energy_per_area_scale(unit: str) -> float:
    """J/m^2 per `unit`."""
    return _factor(ENERGY_PER_AREA, unit, "surface energy")


def attrs(units: str, long_name: str) -> dict[str, str]:
    """The attributes every netCDF variable carries (DESIGN.md, netCDF contract)."""
    return {"units": units, "long_name": long_name}
