"""The common result type of every tracking pipeline and the pipeline registry."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.session import session_entry

#: Per-step table columns every pipeline fills (others may be added).
STEP_TABLE_COLUMNS = ("start_s", "end_s", "event_s", "length_m", "heading_rad", "dz_m")
#: Trajectory columns: local ENU metres (x east, y north, z up); lat/lon when a start coordinate is given.
TRAJECTORY_COLUMNS = ("t", "x", "y", "z")


@dataclass
class TrackResult:
    """Output of a tracking pipeline.

    Attributes
    ----------
    steps : one row per detected step: ``start_s``, ``end_s``, ``event_s`` (s), ``length_m`` (m, signed
        horizontal displacement along the heading; negative = backward), ``heading_rad`` (ENU, 0 = east,
        counter-clockwise), ``dz_m`` (altitude change), and where known ``terrain``, ``direction``,
        ``length_class``, ``confidence``.
    trajectory : ``t``, ``x``, ``y``, ``z`` (+ ``lat``, ``lon``) — position after each step (first row = start).
    info : pipeline name, method, parameters used, warnings (e.g. "no model: M3 unavailable").
    """

    steps: pd.DataFrame
    trajectory: pd.DataFrame
    info: dict = field(default_factory=dict)

    @property
    def distance_m(self) -> float:
        return float(self.steps["length_m"].abs().sum()) if len(self.steps) else 0.0


Pipeline = Callable[..., TrackResult]
PIPELINES: dict[str, Pipeline] = {}


def register_pipeline(name: str) -> Callable[[Pipeline], Pipeline]:
    """Decorator: ``@register_pipeline("waist-pll")`` on ``fn(session, **options) -> TrackResult``."""

    def deco(fn: Pipeline) -> Pipeline:
        # decision B49/B51: the session (or a folder path) is checked once, at the outermost entry point
        wrapped = session_entry(fn, caller=f"pipeline '{name}'")
        PIPELINES[name] = wrapped
        return wrapped

    return deco


def resolve_pipeline(name: str, session) -> str:
    """``"auto"`` (the CLI default, decision L36): ``plasys`` for a session with a foot unit, else
    ``waist-pendulum`` (the lower-back pipeline with the best step F1 and distance on the real recordings,
    docs/waist.md); any other name is returned as given."""
    if name != "auto":
        return name
    if session.has("fAccelerometer") or not session.has("wAccelerometer"):
        return "plasys"
    return "waist-pendulum"


def get_pipeline(name: str) -> Pipeline:
    import pdrlearn.track.pipelines  # noqa: F401  (imports every module that registers a pipeline)

    try:
        return PIPELINES[name]
    except KeyError:
        raise DataError(f"unknown pipeline '{name}'; choose one of {', '.join(sorted(PIPELINES))}") from None
