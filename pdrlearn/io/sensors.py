"""Registry of the PLASYS sensor files (thesis ch.4.3.3) and their units."""

from __future__ import annotations

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
