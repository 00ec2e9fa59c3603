"""The geodetic position update of thesis ch.7.2.1 (eq. 56/57), one step at a time: shared by the offline
``lat``/``lon`` columns (:func:`pdrlearn.track.geodetic.geodetic_track`) and the live waist trackers (decision W137);
and the one check of a start coordinate, ``--start LAT,LON[,ALT]`` and the API's ``start=`` alike (decision L157;
here, numpy only, so the lean runtime's waist tracker shares it, decision W147)."""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError

EARTH_RADIUS_KM = 6371.0  # thesis ch.7.2.1 (R = 6371 km)


def destination(lat_rad: float, lon_rad: float, azimuth_rad: float,
                distance_km: float) -> tuple[float, float]:
    """New latitude/longitude (rad) after ``distance_km`` along ``azimuth_rad`` (clockwise from north).

    Thesis eq. 56/57 on a sphere of radius 6371 km.
    """
    delta = distance_km / EARTH_RADIUS_KM  # angular distance d / R
    lat2 = np.arcsin(np.sin(lat_rad) * np.cos(delta)
                     + np.cos(lat_rad) * np.sin(delta) * np.cos(azimuth_rad))  # thesis eq. 56
    lon2 = lon_rad + np.arctan2(np.sin(azimuth_rad) * np.sin(delta) * np.cos(lat_rad),
                                np.cos(delta) - np.sin(lat_rad) * np.sin(lat2))  # thesis eq. 57
    return float(lat2), float((lon2 + np.pi) % (2 * np.pi) - np.pi)


def step_destination(lat_rad: float, lon_rad: float, length_m: float, heading_rad: float) -> tuple[float, float]:
    """Latitude/longitude (rad) after one step of signed ``length_m`` along ``heading_rad`` (ENU: 0 = east, CCW):
    the azimuth of eq. 56/57 is clockwise from north, ``pi/2 - heading``; a negative length walks the opposite way."""
    d = float(length_m)
    az = np.pi / 2 - float(heading_rad) + (np.pi if d < 0 else 0.0)
    return destination(lat_rad, lon_rad, az, abs(d) / 1000.0)


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


def start_has_altitude(text: str | None) -> bool:
    """Whether a ``--start`` text (checked by :func:`parse_start`) gave the start's altitude, ``LAT,LON,ALT``: the
    z column is then an elevation, written as track.gpx's ``<ele>`` (decision L362)."""
    return text is not None and len(str(text).replace(";", ",").split(",")) == 3


def start_coordinate(start, name: str = "start") -> tuple[tuple[float, float] | None, float]:
    """Decision L157: the ``start=`` of the Python pipelines as the CLI's ``--start LAT,LON[,ALT]``:
    ``(lat, lon)`` or ``(lat, lon, alt)`` in degrees (alt in m; a ``"LAT,LON[,ALT]"`` string too) ->
    ``((lat, lon), alt)``; None -> ``(None, 0.0)``. Anything else, or a coordinate out of range, is one
    :class:`DataError` line (the same check as ``--start``, :func:`parse_start`); ``name``: the keyword it names."""
    if start is None:
        return None, 0.0
    if isinstance(start, str):
        lat, lon, alt = parse_start(start, altitude=True)
        return (lat, lon), alt
    shown = f"{name}={start!r}"
    try:
        values = [float(v) for v in start]
        if len(values) not in (2, 3):
            raise ValueError
    except (TypeError, ValueError):
        raise DataError(f"{shown}: pass (lat, lon) or (lat, lon, alt): numbers in decimal degrees (alt in m), "
                        f"e.g. {name}=(41.178, -8.608)") from None
    lat, lon, alt = _checked(values[0], values[1], values[2] if len(values) == 3 else 0.0, shown)
    return (lat, lon), alt
