"""The geodetic position update of thesis ch.7.2.1 (eq. 56/57), one step at a time: shared by the offline
``lat``/``lon`` columns (:func:`pdrlearn.track.geodetic.geodetic_track`) and the live waist trackers (decision W137)."""

from __future__ import annotations

import numpy as np

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
