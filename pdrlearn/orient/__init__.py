"""Orientation (thesis ch.7.1, 7.2.1): waist heading (tilt-compensated compass + complementary filter)
and foot attitude (accelerometer angles + 2-state Kalman filter)."""

from pdrlearn.orient._kernels import (
    angle_kalman,
    complementary_filter,
    deadband,
    phi_for_rate,
    tilt_compensated_heading,
    tilt_from_accel,
    wrap_angle,
    yaw_rate,
)
from pdrlearn.orient.filters import FootAttitude, UnitData, WaistHeading, noise_from_standstill, unit_data

__all__ = [
    "FootAttitude", "UnitData", "WaistHeading", "angle_kalman", "complementary_filter", "deadband",
    "noise_from_standstill", "phi_for_rate", "tilt_compensated_heading", "tilt_from_accel", "unit_data",
    "wrap_angle", "yaw_rate",
]
