"""The step detectors' kernels: :mod:`pdrlearn.kernels.step_events` (numpy only, shared with the lean runtime's
clock check, decision L177), re-exported under their former module."""

from pdrlearn.kernels.step_events import (  # noqa: F401
    BurstParams,
    BurstState,
    Event,
    ForceParams,
    ForceState,
    GateState,
    PelvicParams,
    PelvicState,
    PLLParams,
    PLLState,
    burst_flush,
    burst_kernel,
    centred_variance,
    force_kernel,
    last_impact,
    motion_gate_flush,
    motion_gate_kernel,
    peak_time,
    pelvic_flush,
    pelvic_kernel,
    pelvic_score,
    pll_flush,
    pll_kernel,
    trailing_window_std,
)
