"""A scene's ``units`` section: the length and pressure units its values are written in."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Mapping

from asperity import units
from asperity.scene.checks import SceneError


def parses(section: str):
    """Decorator of a section's parser: a key the section lacks raises `SceneError` (a
    ValueError) naming the section and the key (the workflow validates every section against
    config/schema.yaml, which fills in the defaults, before the library sees it)."""

    def wrap(parse):
        @functools.wraps(parse)
        def parse_section(*args, **kwargs):
            try:
                return parse(*args, **kwargs)
            except KeyError as err:
                raise SceneError(f"{section}.{err.args[0]}",
                                 f"scene section `{section}`: no key {err.args[0]!r}",
                                 "validate the scene against config/schema.yaml: it gives every "
                                 "default") from None

        return parse_section

    return wrap


@dataclass(frozen=True)
class Units:
    """The units a scene writes its values in (`asperity.units` gives their factors).

    ``length`` is None for a section that has only pressures (the Bodner-Partom
    accuracy study of config/config.yaml)."""

    length: str | None
    pressure: str

    @classmethod
    @parses("units")
    def from_section(cls, section: Mapping[str, Any]) -> "Units":
        return cls(length=section.get("length"), pressure=section["pressure"])

    @property
    def length_factor(self) -> float:
        """Metres per length unit."""
        if self.length is None:
            raise ValueError("units: no length unit given")
        return units.length_scale(self.length)

    @property
    def pressure_factor(self) -> float:
        """Pascals per pressure unit."""
        return units.pressure_scale(self.pressure)


def length_factor(section: Mapping[str, Any]) -> float:
    """Metres per length unit of a scene's ``units`` section."""
    return units.length_scale(section["length"])
