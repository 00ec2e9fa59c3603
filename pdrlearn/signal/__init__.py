"""Signal conditioning: filters, magnitude, resampling, frames, standstill detection and calibration.

Rates in Hz, windows in seconds, arrays along axis 0 = time. See docs/steps.md.
"""

from pdrlearn.signal.conditioning import (
    UNIT_STREAMS,
    G,
    StandstillCalibration,
    UnitCalibration,
    apply_calibration,
    calibrate_standstill,
    resample_stream,
    runs,
    standstill_mask,
)
from pdrlearn.signal.filters import (
    CausalLowpass,
    butter_sos,
    gravity_rotation,
    interp_rows,
    lowpass,
    lowpass_delay_s,
    magnitude,
    uniform_grid,
)

__all__ = [
    "G", "UNIT_STREAMS", "StandstillCalibration", "UnitCalibration", "apply_calibration",
    "calibrate_standstill", "resample_stream", "runs", "standstill_mask",
    "CausalLowpass", "butter_sos", "gravity_rotation", "interp_rows", "lowpass", "lowpass_delay_s",
    "magnitude", "uniform_grid",
]
