"""Geodetic position update of thesis ch.7.2.1 (eq. 56/57) and the ``--start LAT,LON[,ALT]`` parser."""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.geodetic import EARTH_RADIUS_KM, destination, step_destination

__all__ = ["EARTH_RADIUS_KM", "destination", "geodetic_track", "heading_in_radians", "parse_start", "start_coordinate",
           "step_destination"]


def _checked(lat: float, lon: float, alt: float, shown: str) -> tuple[float, float, float]:
    """The one range check of a start coordinate, the CLI's ``--start`` and the API's ``start=`` alike (decision
    L157): latitude in [-90, 90], longitude in [-180, 180] degrees, a finite altitude (m)."""
    if not (np.isfinite(lat) and np.isfinite(lon) and -90.0 <= lat <= 90.0 and -180.0 <= lon <= 180.0):
        raise DataError(f"{shown}: latitude must be in [-90, 90] and longitude in [-180, 180] degrees")
    if not np.isfinite(alt):
        raise DataError(f"{shown}: the altitude ALT must be a finite number of metres, e.g. 12.5")
    return lat, lon, alt


def parse_start(text: str, *, altitude: bool = False) -> tuple[float, float] | tuple[float, float, float]:
    """``"LAT,LON"`` in decimal degrees -> (lat, lon); a one-line DataError on anything else.

    ``altitude=True`` (the ``--start`` of ``pdrlearn track`` / ``run``, decision L56) also accepts
    ``"LAT,LON,ALT"`` (ALT: the start's altitude in m) and returns ``(lat, lon, alt)``, alt 0.0 when not given.
    """
    parts = str(text).replace(";", ",").split(",")
    form, example = ("LAT,LON[,ALT]", "--start 41.178,-8.608 or 41.178,-8.608,12.5") if altitude else \
        ("LAT,LON", "--start 41.178,-8.608")
    try:
        if len(parts) not in ((2, 3) if altitude else (2,)):
            raise ValueError
        lat, lon, *rest = (float(p) for p in parts)
    except ValueError:
        raise DataError(f"--start '{text}': expected {form} in decimal degrees"
                        + (" (ALT: the start's altitude in m)" if altitude else "") + f", e.g. {example}") from None
    lat, lon, alt = _checked(lat, lon, rest[0] if rest else 0.0, f"--start '{text}'")
    return (lat, lon, alt) if altitude else (lat, lon)


def start_coordinate(start) -> tuple[tuple[float, float] | None, float]:
    """Decision L157: the ``start=`` of the Python pipelines as the CLI's ``--start LAT,LON[,ALT]``:
    ``(lat, lon)`` or ``(lat, lon, alt)`` in degrees (alt in m; a ``"LAT,LON[,ALT]"`` string too) ->
    ``((lat, lon), alt)``; None -> ``(None, 0.0)``. Anything else, or a coordinate out of range, is one
    :class:`DataError` line (the same check as ``--start``, :func:`parse_start`)."""
    if start is None:
        return None, 0.0
    if isinstance(start, str):
        lat, lon, alt = parse_start(start, altitude=True)
        return (lat, lon), alt
    shown = f"start={start!r}"
    try:
        values = [float(v) for v in start]
        if len(values) not in (2, 3):
            raise ValueError
    except (TypeError, ValueError):
        raise DataError(f"{shown}: pass (lat, lon) or (lat, lon, alt): numbers in decimal degrees (alt in m), "
                        "e.g. start=(41.178, -8.608)") from None
    lat, lon, alt = _checked(values[0], values[1], values[2] if len(values) == 3 else 0.0, shown)
    return (lat, lon), alt


def heading_in_radians(value: float, name: str) -> float:
    """Decisions W81, L158: a start heading given to the Python API (every pipeline's ``initial_heading``) is in
    radians; a magnitude above 2 pi is a value in degrees (the CLI's ``--initial-heading DEG``) and is one error
    line naming the unit, not a silent 90 rad."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if not np.isfinite(v) or abs(v) > 2 * np.pi:
        raise DataError(f"{name}={value!r}: the heading is in radians (ENU, counter-clockwise from east; "
                        f"|value| <= 2 pi); for degrees pass math.radians({value!r}) (the CLI's --initial-heading "
                        "takes degrees)")
    return v


def geodetic_track(start: tuple[float, float], length_m: np.ndarray, heading_rad: np.ndarray) -> np.ndarray:
    """Latitude/longitude (degrees, (n + 1, 2)) after each step from a start coordinate (degrees).

    ``length_m`` is the signed step length along ``heading_rad`` (ENU: 0 = east, CCW); the azimuth of
    eq. 56/57 is clockwise from north, ``pi/2 - heading``; a negative length walks the opposite way.
    """
    lat, lon = np.radians(start[0]), np.radians(start[1])
    out = np.empty((len(length_m) + 1, 2))
    out[0] = start
    for k, (d, h) in enumerate(zip(np.asarray(length_m, float), np.asarray(heading_rad, float), strict=True)):
        lat, lon = step_destination(lat, lon, d, h)  # thesis eq. 56/57, the live trackers' step too (W137)
        out[k + 1] = np.degrees(lat), np.degrees(lon)
    return out
