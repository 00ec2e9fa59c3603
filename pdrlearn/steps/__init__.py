"""Step detection (thesis ch.5, seeds 000/001), unit clock alignment, stance-to-stance segmentation and
event-level evaluation. See docs/steps.md."""

from pdrlearn.steps.align import align_events, align_units, apply_alignment
from pdrlearn.steps.base import STEPS_COLUMNS, Event, OnlineStepDetector, StepDetector, StepProcessor, steps_frame
from pdrlearn.steps.detectors import (
    DETECTORS,
    AccelForceStepDetector,
    AccelStepDetector,
    PelvicGyroStepDetector,
    PLLStepDetector,
    get_detector,
    register_detector,
)
from pdrlearn.steps.evaluate import (
    DEFAULT_TOLERANCE_S,
    Reference,
    in_intervals,
    match_events,
    reference_events,
    score_events,
    score_steps,
)
from pdrlearn.steps.segment import segment_steps
from pdrlearn.steps.strides import one_per_stride
from pdrlearn.steps.waist_ic import WaistICStepDetector

__all__ = [
    "STEPS_COLUMNS", "Event", "OnlineStepDetector", "StepDetector", "StepProcessor", "steps_frame",
    "DETECTORS", "AccelStepDetector", "AccelForceStepDetector", "PelvicGyroStepDetector", "PLLStepDetector",
    "WaistICStepDetector", "get_detector", "register_detector", "Reference", "in_intervals", "DEFAULT_TOLERANCE_S",
    "match_events", "one_per_stride", "reference_events", "score_events", "score_steps", "align_units",
    "apply_alignment", "align_events", "segment_steps",
]
