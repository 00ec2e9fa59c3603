"""Decisions L69, C28: the height warnings of a foot track. The one implementation is
:mod:`pdrlearn.kernels.altitude_check` (numpy only, so that the streaming runtime runs it too, decision E47);
this module re-exports it for the offline and ``--streaming`` pipelines."""

from pdrlearn.kernels.altitude_check import (
    CONFLICT_MIN_FRACTION,
    CONFLICT_MIN_STRIDES,
    FLAT_ALTITUDE_M,
    LEVEL_ALTITUDE_PER_100M_MAX_M,
    LEVEL_STRIDE_DZ_MAX_M,
    integrated_altitude_check,
    steep_stride_check,
    terrain_dz_check,
)

__all__ = ["CONFLICT_MIN_FRACTION", "CONFLICT_MIN_STRIDES", "FLAT_ALTITUDE_M", "LEVEL_ALTITUDE_PER_100M_MAX_M",
           "LEVEL_STRIDE_DZ_MAX_M", "integrated_altitude_check", "steep_stride_check",
           "terrain_dz_check"]
