"""Waist-only pedestrian dead reckoning (seeds 000, 001, 003): AHRS to a navigation frame, motion gate,
initial/final contacts, step-length models, harmonic and gyroscope heading, per-user calibration.

The pipelines ``waist-pll`` and ``waist-pendulum`` live in :mod:`pdrlearn.track.waist`; see docs/waist.md.
:class:`WaistTracker` (:mod:`pdrlearn.waist.live`) tracks a live stream (docs/waist.md "Live tracking").
"""

from pdrlearn.waist.ahrs import WaistIMU, body_data, waist_imu
from pdrlearn.waist.events import InitialContactDetector, steps_from_events, walking_gate
from pdrlearn.waist.heading import TurnClassifier, gyro_headings, harmonic_headings
from pdrlearn.waist.live import LiveStep, WaistTracker
from pdrlearn.waist.params import WaistParams, default_params, load_params, resolve_params

__all__ = [
    "WaistIMU", "body_data", "waist_imu", "InitialContactDetector", "steps_from_events", "walking_gate",
    "TurnClassifier", "gyro_headings", "harmonic_headings", "WaistParams", "default_params", "load_params",
    "resolve_params", "WaistTracker", "LiveStep",
]
