"""Step windows and per-task step features (thesis ch. 6).

Public API
----------
- :data:`CHANNELS` - fixed channel layout of a step-window array (``t_s``, foot acc x/y/z/norm, foot gyro
  x/y/z, force a/b, waist acc x/y/z, waist gyro x/y/z, waist baro); x = forward horizontal, y = left
  horizontal, z = up in each step's gravity-aligned frame; see :mod:`pdrlearn.features.windows`.
- :func:`step_windows` (session, steps, n_samples=40) -> :class:`StepWindows` (``X``, ``durations_s``,
  ``channels``, ``available``, ``steps``); :func:`task_labels` and :data:`TASK_CLASSES`.
- Transformers (scikit-learn): :class:`TerrainSVMFeatures` (17), :class:`SegmentFeatures`
  (6 parts x max/min/mean/slope), :class:`DirectionFeatures` (25), :class:`LengthFeatures` (29),
  :class:`RuleFeatures` (the named features of the heuristic rule tables);
  :func:`make_features` (task, unit, kind) picks the thesis transformer.

See docs/features.md for the tables and docs/decisions/features.md for interpretation choices.
"""

from pdrlearn.features.transformers import (
    SIGNALS,
    UNITS,
    DirectionFeatures,
    LengthFeatures,
    SegmentFeatures,
    TerrainSVMFeatures,
    as_windows,
    make_features,
    signal,
)
from pdrlearn.features.windows import (
    CHANNEL_INDEX,
    CHANNELS,
    GROUPS,
    TASK_CLASSES,
    TASK_COLUMNS,
    StepWindows,
    step_windows,
    task_labels,
)

__all__ = [
    "CHANNELS", "CHANNEL_INDEX", "GROUPS", "TASK_CLASSES", "TASK_COLUMNS", "StepWindows", "step_windows",
    "task_labels", "SIGNALS", "UNITS", "as_windows", "signal", "make_features",
    "TerrainSVMFeatures", "SegmentFeatures", "DirectionFeatures", "LengthFeatures",
]
