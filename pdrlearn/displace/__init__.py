"""Displacement (thesis ch.7.2): ZUPT/ZARU strapdown integration, the white-noise-jerk Kalman filter,
and the PLASYS step rules (terrain -> filter mode, direction -> sign, length class -> clamp, altitude)."""

from pdrlearn.displace._kernels import (
    altitude_change,
    apply_direction,
    bayes_length,
    clamp_length,
    double_integrate,
    error_clock,
    heel_rocker_samples,
    horizontal_part,
    move_reference,
    rotation_pivot,
    strapdown,
    stride_attitude,
    stride_index,
    terrain_distance,
    wnj_displacement,
    wnj_kalman,
    wnj_matrices,
)
from pdrlearn.displace.calibration import (
    LEVEL_DZ_M,
    PRE_L41_CALIBRATION,
    RATE_TOLERANCE,
    calibrate_distance,
    calibrate_streaming,
    distance_gain,
    model_distance_calibration,
    predates_streaming_calibration,
    straight_level_forward,
    streaming_calibration,
)
from pdrlearn.displace.foot import FootDisplacement, force_stance, inertial_stance, rest_to_rest, stance_runs
from pdrlearn.displace.rules import THESIS_STEP_BOUNDS, StepRules, model_length_bounds, parse_bounds

__all__ = [
    "LEVEL_DZ_M", "RATE_TOLERANCE", "calibrate_distance", "calibrate_streaming", "distance_gain",
    "model_distance_calibration", "straight_level_forward", "streaming_calibration", "PRE_L41_CALIBRATION",
    "predates_streaming_calibration",
    "FootDisplacement", "StepRules", "THESIS_STEP_BOUNDS", "altitude_change", "apply_direction", "bayes_length",
    "clamp_length",
    "double_integrate", "error_clock", "force_stance", "heel_rocker_samples", "horizontal_part", "move_reference",
    "rotation_pivot", "inertial_stance", "model_length_bounds", "parse_bounds", "rest_to_rest", "stance_runs",
    "strapdown", "stride_attitude",
    "stride_index", "terrain_distance", "wnj_displacement", "wnj_kalman", "wnj_matrices",
]
