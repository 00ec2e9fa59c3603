"""Geodetic position update of thesis ch.7.2.1 (eq. 56/57) and the ``--start LAT,LON[,ALT]`` parser."""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.geodetic import (  # noqa: F401 (L157 checks: in the kernel, numpy only, for the runtime W147)
    EARTH_RADIUS_KM,
    destination,
    parse_start,
    start_coordinate,
    start_has_altitude,
    step_destination,
)

__all__ = ["EARTH_RADIUS_KM", "destination", "geodetic_track", "heading_in_radians", "parse_start", "start_coordinate",
           "start_has_altitude", "step_destination"]


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
