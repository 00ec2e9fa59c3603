"""Tracking pipelines: session -> per-step table + trajectory.

Pipelines register themselves in :data:`PIPELINES` (see :mod:`pdrlearn.track.base`); ``pdrlearn track
--pipeline NAME`` looks them up there.
"""

from pdrlearn.track.base import PIPELINES, TrackResult, get_pipeline, register_pipeline

__all__ = ["PIPELINES", "TrackResult", "get_pipeline", "register_pipeline"]
