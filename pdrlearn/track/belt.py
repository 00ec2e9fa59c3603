"""A declared treadmill (decisions L321, L441, L442; docs/frames.md "A treadmill trial").

meta.json ``belt_speed_mps`` declares a belt at constant speed; the foot's strides are belt strides (a belt at
constant speed is an inertial frame, L147). Decision L441: the belt check compares the belt speed with the median
speed of the *belt strides* (:func:`belt_rows`): the steady strides the belt carries - straight in heading, not a side
step, with a stride time, their neighbours such strides too (no start, stop or turn next to them, as the stride-time
CV's steady strides, L104), and at the belt's own grade (level or a constant incline): an inclined belt's strides
rise every stride, so L179's level straight strides, which the check read before, left one start stride on a 10 %
belt (trial s36 T3: -47.7 % from that one stride). No figure from fewer than :data:`MIN_BELT_STRIDES`.

Decision L442: meta.json ``belt_incline_pct`` (with ``belt_speed_mps``) declares the belt's incline. The foot then
still reports the belt's virtual climb (``altitude_change_m``, ``ascent_m``: the belt's frame, L147), but no storeys
(the ``floors_*`` counts are 0, ``floors_note`` says why), no stair flight (stairs.csv holds the header alone) and
the stride-time and stride-length CVs keep the incline's strides (L322's rule,
:func:`~pdrlearn.track.clinical.cv_keeps_ramps`). The declared incline is in force while a session is tracked
(:func:`incline_scope`, a :class:`contextvars.ContextVar`, so the threads of ``track-all --jobs`` do not share it,
as L415's steady-trim).
"""

from __future__ import annotations

import contextvars
import math
from contextlib import contextmanager

import numpy as np
import pandas as pd

#: decision L321: meta.json's declared treadmill belt speed (m/s)
BELT_KEY = "belt_speed_mps"
#: decision L441: the fewest belt strides the belt check gives a figure from - L123's fewest straight strides to
#: judge a walking speed (:data:`pdrlearn.track.gait.MIN_STRAIGHT_FOR_RANGE`, 5)
MIN_BELT_STRIDES = 5
#: decision L442: meta.json's declared belt incline (%, rise over run x 100; + up, - a decline)
INCLINE_KEY = "belt_incline_pct"
#: decision L442 (B365): the declared inclines accepted, %: treadmills reach 15-25 % (a few 40 %) and -3 to -10 %
MAX_INCLINE_PCT = 40.0
_INCLINE = contextvars.ContextVar("pdrlearn_belt_incline", default=None)


def belt_rows(steps: pd.DataFrame) -> np.ndarray:
    """Decision L441: (B,) bool, the belt strides of a foot steps table (in its row order, which is time order):
    a stride (L67 / L97's :func:`~pdrlearn.track.gait.stride_rows`) with a finite speed (:func:`stride_speeds`),
    turning less than L79's 15 deg, not a side step (L228), whose rows before and after are such strides too
    (steady: no start, stop or turn next to it, as L104's CV strides), and whose ``dz_m`` lies within L39's level
    band (0.10 m, :data:`pdrlearn.kernels.distance.LEVEL_DZ_M`) of the median ``dz_m`` of those strides: level on a
    level belt, the belt's constant grade on an inclined one. All False without the gait columns."""
    from pdrlearn.kernels.distance import LEVEL_DZ_M
    from pdrlearn.track.gait import STRAIGHT_MAX_RAD, sideways_rows, stride_rows

    n = len(steps)
    if not n or "turn_angle_rad" not in steps:
        return np.zeros(n, bool)
    speed = stride_speeds(steps)
    turn = pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float)
    with np.errstate(invalid="ignore"):
        ok = stride_rows(steps) & np.isfinite(speed) & (np.abs(turn) < STRAIGHT_MAX_RAD) & ~sideways_rows(steps)
    ok = ok & np.r_[False, ok[:-1]] & np.r_[ok[1:], False]  # steady: its neighbours are belt strides too
    dz = pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float) if "dz_m" in steps else np.zeros(n)
    dz = np.nan_to_num(dz)
    if ok.any():
        ok &= np.abs(dz - float(np.median(dz[ok]))) < LEVEL_DZ_M  # the belt's own grade (L39's level band)
    return ok


def stride_speeds(steps: pd.DataFrame) -> np.ndarray:
    """Decisions L441, L222: (B,) each stride's horizontal speed, m/s: ``speed_mps``, or - a streamed foot table
    without stride times (no ``--contacts``, E51) - :func:`pdrlearn.track.gait.cycle_speeds` (|length| over the time
    to the next stride's start), as ``median_speed_straight_mps`` reads it
    (:func:`pdrlearn.track.gait.range_speeds`)."""
    from pdrlearn.track.gait import range_speeds

    speed = (pd.to_numeric(steps["speed_mps"], errors="coerce").to_numpy(float) if "speed_mps" in steps
             else np.full(len(steps), np.nan))
    return range_speeds(steps, speed)


def belt_speeds(steps: pd.DataFrame) -> np.ndarray:
    """Decision L441: the belt strides' (:func:`belt_rows`) speeds along the belt, m/s: the stride's horizontal
    ``speed_mps`` times sqrt(1 + (dz / length)^2) - an inclined belt runs along its surface (0.5 % more than the
    horizontal speed at 10 %); the horizontal speed itself on a level stride (``dz_m`` 0)."""
    rows = belt_rows(steps)
    speed = stride_speeds(steps)[rows] if rows.any() else np.zeros(0)
    if not rows.any() or "dz_m" not in steps:
        return speed
    dz = np.nan_to_num(pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float)[rows])
    length = np.abs(pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float)[rows])
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = np.where(length > 0, dz / length, 0.0)
    return speed * np.sqrt(1.0 + slope ** 2)


def belt_value(meta: dict | None, where: str) -> float | None:
    """Decision L321: meta.json's ``belt_speed_mps`` (m/s), None without it; a bad value is one line naming it."""
    from pdrlearn.errors import DataError

    v = (meta or {}).get(BELT_KEY)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or not 0 < v <= 10:
        raise DataError(f"{where}/meta.json: {BELT_KEY} {v!r}: give the treadmill's belt speed as a positive number "
                        "of m/s (e.g. 1.0; at most 10), or remove the key (decision L321)")
    return float(v)


def incline_value(meta: dict | None, where: str) -> float | None:
    """Decision L442: meta.json's ``belt_incline_pct`` (%), None without it. Decision B365: a value that is no finite
    number within +-:data:`MAX_INCLINE_PCT`, or one declared without ``belt_speed_mps``, is one line naming it."""
    from pdrlearn.errors import DataError

    v = (meta or {}).get(INCLINE_KEY)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or abs(v) > MAX_INCLINE_PCT:
        raise DataError(f"{where}/meta.json: {INCLINE_KEY} {v!r}: give the treadmill's incline as a number of percent "
                        f"(rise over run x 100, e.g. 10; at most {MAX_INCLINE_PCT:g}, negative for a decline), or "
                        "remove the key (decisions L442, B365)")
    if belt_value(meta, where) is None:
        raise DataError(f"{where}/meta.json: {INCLINE_KEY} {v!r} without {BELT_KEY}: an incline is declared for a "
                        f"treadmill belt; add \"{BELT_KEY}\" (m/s) or remove {INCLINE_KEY} (decisions L442, B365)")
    return float(v)


@contextmanager
def incline_scope(value: float | None = None):
    """Decision L442: a scope in which the tracked session's belt incline (%) is ``value`` (or what
    :func:`set_incline` declares inside it); reset on exit, so the next session of a batch starts undeclared."""
    token = _INCLINE.set(value)
    try:
        yield
    finally:
        _INCLINE.reset(token)


def check_belt_keys(meta: dict | None, where: str) -> None:
    """Decisions L321, B365, L454: meta.json's ``belt_speed_mps`` and ``belt_incline_pct`` checked before tracking
    (``track`` and ``run``): a bad value is one line naming it."""
    belt_value(meta, where)
    incline_value(meta, where)


@contextmanager
def session_incline(session):
    """Decisions L442, L454: the one scope a session's summary and tables are made in - the belt incline meta.json
    declares for ``session`` (:func:`incline_value`; a bad value is one line naming it, B365), or the one an
    enclosing scope declared already (``track`` declares it before tracking). Yields the session's own value
    (None: none declared; ``session`` None: none)."""
    incline = None if session is None else incline_value(session.meta, session_where(session))
    outer = declared_incline()
    with incline_scope(incline if outer is None else outer):
        yield incline


def session_where(session) -> str:
    """The session's folder (its name in memory) as the belt's error lines name it."""
    return str(getattr(session, "folder", None) or session.where)


def set_incline(value: float | None) -> None:
    """Decision L442: the declared belt incline (%) of the session tracked inside :func:`incline_scope`."""
    _INCLINE.set(value)


def declared_incline() -> float | None:
    """Decision L442: the belt incline (%) declared for the session being tracked; None: none declared."""
    return _INCLINE.get()


#: decision L442: the storey counts a declared inclined belt sets to 0
FLOOR_KEYS = ("floors_up", "floors_down", "storeys_changed", *(f"floors_{d}_{k}" for d in ("up", "down")
                                                               for k in ("stairs", "ramps", "rides")))


def belt_floors(out: dict) -> None:
    """Decision L442, in place: on a declared inclined belt (:func:`declared_incline`) the :data:`FLOOR_KEYS` that
    were counted are 0 and ``floors_note`` says why; nothing otherwise."""
    incline = declared_incline()
    if incline is None:
        return
    for key in FLOOR_KEYS:
        if out.get(key) is not None:
            out[key] = 0
    out["floors_note"] = (f"a treadmill belt at {incline:g} % (meta.json {INCLINE_KEY}): its climb is the belt's "
                          "virtual climb, no storeys and no stair flight (decision L442)")


def belt_walk_tests(meta: dict | None, out: dict) -> None:
    """Decision L445, in place: on a declared treadmill (meta.json ``belt_speed_mps``) the walkway tests - the 10 m
    walk (L312) and the timed 25-foot walk (L387), :data:`pdrlearn.track.walk_test.KEYS` / ``T25FW_KEYS`` - are not
    timed: each times a walk overground from standing, and on a belt the walk's speed is the belt's; their notes say
    so. Nothing without the key (its value is checked by :func:`belt_value` elsewhere)."""
    v = (meta or {}).get(BELT_KEY)
    if v is None or isinstance(v, bool) or not isinstance(v, int | float):
        return
    from pdrlearn.track.own_test import clear_walkway_tests

    clear_walkway_tests(out, f"a treadmill belt (meta.json {BELT_KEY} {float(v):g} m/s): a walkway test times a walk "
                        "overground, and on the belt the walking speed is the belt's; not timed (decision L445)")


def belt_summary(meta: dict | None, summary: dict, where: str, steps: pd.DataFrame | None = None) -> dict:
    """Decision L321: a declared treadmill (meta.json ``belt_speed_mps``, a positive number of m/s): the belt speed
    and, decision L441, the belt strides of ``steps`` (:func:`belt_rows`: ``n_belt_strides``, their median speed along
    the belt ``median_speed_belt_mps``) against it (``belt_speed_error_pct``), given from at least
    :data:`MIN_BELT_STRIDES` belt strides; with fewer, ``belt_check_note`` says why instead. No new physics: a belt
    at constant speed is an inertial frame (docs/frames.md, L147), so the foot's strides are belt strides and its
    path and distance are the belt's, not travel. Empty without the key; a bad value is one line naming it."""
    v = belt_value(meta, where)
    if v is None:
        return {}
    out: dict = {BELT_KEY: v}
    incline = incline_value(meta, where)  # decision L442
    if incline is not None:
        out[INCLINE_KEY] = incline
    speeds = belt_speeds(steps) if steps is not None else np.zeros(0)
    out["n_belt_strides"] = int(len(speeds))
    out["median_speed_belt_mps"] = float(np.median(speeds)) if len(speeds) else None
    if len(speeds) >= MIN_BELT_STRIDES:
        out["belt_speed_error_pct"] = 100.0 * (out["median_speed_belt_mps"] - v) / v
    else:
        out["belt_check_note"] = (f"{len(speeds)} steady straight strides at the belt's grade, {MIN_BELT_STRIDES} "
                                  "needed: no belt speed check (decision L441)")
    return out


def belt_line(summary: dict) -> str | None:
    """Decisions L321, L441: the console line of a declared treadmill."""
    v = summary.get(BELT_KEY)
    if v is None:
        return None
    err = summary.get("belt_speed_error_pct")
    incline = summary.get(INCLINE_KEY)
    return (f"treadmill belt {float(v):.2f} m/s (meta.json {BELT_KEY}"
            + (f", at {float(incline):g} % incline ({INCLINE_KEY}: no storeys or stair flights, L442)"
               if incline is not None else "") + "): "
            + (f"the foot's {summary['n_belt_strides']} steady straight strides at the belt's grade "
               f"{float(summary['median_speed_belt_mps']):.2f} m/s ({err:+.1f} %)" if err is not None
               else summary.get("belt_check_note") or "no belt strides to compare")
            + f"; {float(summary.get('distance_m', 0.0)):.2f} m is belt distance and the path is the belt's, not "
            "travel (docs/frames.md, decisions L147, L321)")
