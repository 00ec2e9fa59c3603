"""Waist-only pedestrian dead reckoning (seeds 000, 001, 003): AHRS to a navigation frame, motion gate,
initial/final contacts, step-length models, harmonic and gyroscope heading, per-user calibration.

The pipelines ``waist-pll`` and ``waist-pendulum`` live in :mod:`pdrlearn.track.waist`; see docs/waist.md.
:class:`WaistTracker` (:mod:`pdrlearn.waist.live`) tracks a live stream (docs/waist.md "Live tracking").
"""

from pdrlearn.lazy import lazy_attributes

#: decision E262: imported on first access, so that a module that needs one waist module (``track.bouts`` needs
#: ``gait_quality``'s column names) does not import scikit-learn (``heading``) and the rest of the package
_LAZY = {
    **dict.fromkeys(("WaistIMU", "body_data", "waist_imu"), "pdrlearn.waist.ahrs"),
    **dict.fromkeys(("InitialContactDetector", "steps_from_events", "walking_gate"), "pdrlearn.waist.events"),
    **dict.fromkeys(("TurnClassifier", "gyro_headings", "harmonic_headings"), "pdrlearn.waist.heading"),
    **dict.fromkeys(("LiveStep", "WaistTracker"), "pdrlearn.waist.live"),
    **dict.fromkeys(("WaistParams", "default_params", "load_params", "resolve_params"), "pdrlearn.waist.params"),
}

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())

__all__ = [
    "WaistIMU", "body_data", "waist_imu", "InitialContactDetector", "steps_from_events", "walking_gate",
    "TurnClassifier", "gyro_headings", "harmonic_headings", "WaistParams", "default_params", "load_params",
    "resolve_params", "WaistTracker", "LiveStep",
]
