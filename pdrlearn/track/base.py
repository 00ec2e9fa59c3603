"""The common result type of every tracking pipeline and the pipeline registry."""

from __future__ import annotations

import difflib
import inspect
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import pandas as pd

from pdrlearn.errors import DataError

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
        PIPELINES[name] = fn
        return fn

    return deco


def keyword_names(fn: Callable, *, exclude: Iterable[str] = ()) -> list[str]:
    """The keyword arguments of ``fn`` (its keyword-only and positional-or-keyword parameters after the first,
    the session), without ``**`` catch-alls and the names in ``exclude``."""
    params = list(inspect.signature(fn).parameters.values())[1:]
    kinds = (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    return [p.name for p in params if p.kind in kinds and p.name not in set(exclude)]


def check_keywords(pipeline: str, given: Mapping | Iterable[str], valid: Iterable[str]) -> None:
    """Raise ``TypeError`` (as Python does for an unknown keyword) when ``given`` holds a name that is not in
    ``valid``, naming it, the closest valid name (``difflib``) and every valid one (decision L43)."""
    valid = list(valid)
    unknown = [k for k in given if k not in valid]
    if not unknown:
        return
    parts = []
    for k in unknown:
        close = difflib.get_close_matches(str(k), valid, n=1)
        parts.append(f"{k!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
    word = "argument" if len(unknown) == 1 else "arguments"
    raise TypeError(f"{pipeline} pipeline: unexpected keyword {word} {', '.join(parts)}; its keyword arguments "
                    f"are {', '.join(valid)}")


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
