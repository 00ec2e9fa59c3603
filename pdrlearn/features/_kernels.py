"""Pure numerical kernels of :mod:`pdrlearn.features` (no classes, no sessions).

They live in the numpy-only package :mod:`pdrlearn.kernels` so that the streaming runtime runs the very
same functions (issue 7: no mirror between training and runtime); this module re-exports them under
their historical names.
"""

from pdrlearn.kernels.stats import (  # noqa: F401
    correct_tilt_drift,
    force_stats,
    half_balance,
    heading_rotation,
    interp_rows,
    peak_stats,
    positive_net_rotation,
    prefix_products,
    principal_horizontal_axis,
    propagate_attitude,
    rest_index,
    row_gradient,
    segment_bounds,
    segment_stats,
    step_probability,
    yaw_stats,
)
