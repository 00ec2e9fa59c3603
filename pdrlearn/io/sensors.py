"""Registry of the PLASYS sensor files (thesis ch.4.3.3) and their units."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class SensorSpec:
    """Static description of one PLASYS sensor file.

    Attributes
    ----------
    name : file stem, e.g. ``"fAccelerometer"``
    placement : ``"foot"`` or ``"waist"``
    kind : ``"accelerometer"``, ``"gyroscope"``, ``"force"``, ``"magnetometer"`` or ``"barometer"``
    n_axes : 3 for vector sensors, 1 for force and barometer (column ``x`` only; thesis ch.4.3.3)
    unit : SI unit of the values in memory and on disk
    """

    name: str
    placement: str
    kind: str
    n_axes: int
    unit: str

    @property
    def columns(self) -> tuple[str, ...]:
        return ("x", "y", "z")[: self.n_axes]

    @property
    def filename(self) -> str:
        return f"{self.name}.csv"


# Thesis ch.4.3.3: the eight files written by the PLASYS Android application.
SENSORS: dict[str, SensorSpec] = {
    s.name: s
    for s in (
        SensorSpec("fAccelerometer", "foot", "accelerometer", 3, "m/s^2"),
        SensorSpec("fGyroscope", "foot", "gyroscope", 3, "rad/s"),
        SensorSpec("fForceA", "foot", "force", 1, "N"),  # heel sensor (thesis Fig. 36)
        SensorSpec("fForceB", "foot", "force", 1, "N"),  # toe/forefoot sensor
        SensorSpec("wAccelerometer", "waist", "accelerometer", 3, "m/s^2"),
        SensorSpec("wGyroscope", "waist", "gyroscope", 3, "rad/s"),
        SensorSpec("wMagneticField", "waist", "magnetometer", 3, "uT"),
        SensorSpec("wBarometer", "waist", "barometer", 1, "hPa"),
    )
}

PLACEMENTS = ("foot", "waist")

#: each unit's accelerometer and gyroscope (the streams its steps, frame and rate are judged on)
UNIT_IMU: dict[str, tuple[str, str]] = {"foot": ("fAccelerometer", "fGyroscope"),
                                        "waist": ("wAccelerometer", "wGyroscope")}

# Bluetooth text protocol sensor types (thesis Table 10).
PROTOCOL_TYPES: dict[int, str] = {1: "fAccelerometer", 2: "fGyroscope", 3: "fForceA", 4: "fForceB"}


def spec(name: str) -> SensorSpec:
    """Return the spec of a sensor file stem, raising a clear error for unknown names."""
    from pdrlearn.errors import DataError

    try:
        return SENSORS[name]
    except KeyError:
        raise DataError(f"unknown sensor '{name}'; known sensors: {', '.join(SENSORS)}") from None


#: units a ``meta.json`` may declare for a sensor file (``"units": {"fAccelerometer": "g"}``, the first word of
#: the text; decision B32): kind -> {unit (lower case) -> factor to the SI unit of :class:`SensorSpec`}.
#: 1 g = 9.80665 m/s^2 (standard gravity, thesis ch.4.2.1.1); 1 gauss = 100 uT. Force files are in N or
#: normalised (README) and take any text.
VALUE_UNITS: dict[str, dict[str, float]] = {
    "accelerometer": {"m/s^2": 1.0, "m/s2": 1.0, "m/s\u00b2": 1.0, "m/s/s": 1.0, "m*s^-2": 1.0,
                      "g": 9.80665, "mg": 9.80665e-3},
    "gyroscope": {"rad/s": 1.0, "deg/s": math.pi / 180, "dps": math.pi / 180, "\u00b0/s": math.pi / 180,
                  "degrees/s": math.pi / 180, "mrad/s": 1e-3},
    "magnetometer": {"ut": 1.0, "\u00b5t": 1.0, "\u03bct": 1.0, "microtesla": 1.0, "nt": 1e-3, "mt": 1e3, "t": 1e6,
                     "gauss": 100.0, "g": 100.0, "mg": 0.1, "milligauss": 0.1},
    "barometer": {"hpa": 1.0, "mbar": 1.0, "millibar": 1.0, "pa": 0.01, "kpa": 10.0, "bar": 1000.0},
}


def _scale_factor(token: str) -> float | None:
    """Decision B100: a positive finite number (``0.0047884``, ``4.79e-3``) or fraction (``1/2048``) that leads a
    declared value unit: the size of one count in that unit; ``None`` when ``token`` is not one."""
    num, _, den = token.partition("/")
    try:
        v = float(num) / (float(den) if den else 1.0)
    except (ValueError, ZeroDivisionError):
        return None
    return v if math.isfinite(v) and v > 0 else None


def parse_value_unit(text: str, kind: str) -> tuple[float, str] | None:
    """Decisions B32, B100, B313: ``(factor to the SI unit, the unit as read)`` of a declared value unit of a
    ``kind`` sensor (``"g"``, ``"deg/s"``: the first word, :data:`VALUE_UNITS`; or the size of one count and a unit,
    ``"1/2048 g"``, ``"0.0047884 m/s^2"``, ``"1/16.4 deg/s"``: ``"1/2048 g"`` back); ``None`` when ``text`` is
    neither. meta.json's ``units`` and ``pdrlearn import``'s ``--acc-unit`` / ``--gyro-unit`` read units with it."""
    table = VALUE_UNITS.get(kind, {})
    words = str(text).strip().split()
    scale = _scale_factor(words[0]) if len(words) > 1 else None  # decision B100: "0.0047884 m/s^2" per count
    if scale is not None:
        words = words[1:]
    word = words[0].strip("(),;:").lower() if words else ""
    if word not in table:
        return None
    if scale is None:
        return table[word], word
    return scale * table[word], f"{str(text).split()[0]} {word}"

