"""Small local tangent-plane conversion between WGS-84 lat/lon and local ENU metres.

Valid for the extent of a walk (a few km): the error of the local-plane approximation is below
1 mm per km near the origin and grows with the square of the distance. (The localization engineer's
``pdrlearn.track.geodetic`` did not exist when this was written; see docs/decisions/aided.md.)
"""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError

WGS84_A = 6378137.0  # semi-major axis (m), WGS-84
WGS84_E2 = 6.69437999014e-3  # first eccentricity squared, WGS-84


def _radii(lat0_rad: float) -> tuple[float, float]:
    """Meridian (north) and prime-vertical (east) radii of curvature (m) at latitude ``lat0_rad``."""
    s2 = np.sin(lat0_rad) ** 2
    rn = WGS84_A / np.sqrt(1.0 - WGS84_E2 * s2)
    rm = WGS84_A * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * s2) ** 1.5
    return float(rm), float(rn)


def _check_origin(lat0: float, lon0: float) -> None:
    if not (np.isfinite(lat0) and np.isfinite(lon0) and -90.0 < lat0 < 90.0 and -180.0 <= lon0 <= 360.0):
        raise DataError(f"start coordinate ({lat0}, {lon0}) is not a valid latitude/longitude in degrees")


def geodetic_to_enu(lat_deg, lon_deg, lat0_deg: float, lon0_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Latitude/longitude (degrees) -> local east/north (m) around the origin ``(lat0_deg, lon0_deg)``."""
    _check_origin(lat0_deg, lon0_deg)
    lat0 = np.radians(lat0_deg)
    rm, rn = _radii(lat0)
    dlat = np.radians(np.asarray(lat_deg, dtype=float) - lat0_deg)
    dlon = np.radians((np.asarray(lon_deg, dtype=float) - lon0_deg + 180.0) % 360.0 - 180.0)
    return dlon * rn * np.cos(lat0), dlat * rm


def enu_to_geodetic(east_m, north_m, lat0_deg: float, lon0_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Local east/north (m) -> latitude/longitude (degrees); inverse of :func:`geodetic_to_enu`."""
    _check_origin(lat0_deg, lon0_deg)
    lat0 = np.radians(lat0_deg)
    rm, rn = _radii(lat0)
    lat = lat0_deg + np.degrees(np.asarray(north_m, dtype=float) / rm)
    lon = lon0_deg + np.degrees(np.asarray(east_m, dtype=float) / (rn * np.cos(lat0)))
    return lat, lon


def haversine_m(lat1_deg, lon1_deg, lat2_deg, lon2_deg) -> np.ndarray:
    """Great-circle distance (m) on a sphere of radius 6371008.8 m (seed 001 ref. [9], Haversine)."""
    r = 6371008.8  # mean Earth radius (m)
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dp = p2 - p1
    dl = np.radians(np.asarray(lon2_deg) - np.asarray(lon1_deg))
    a = np.sin(dp / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    return 2 * r * np.arcsin(np.sqrt(np.clip(a, 0.0, 1.0)))
