"""Decision L415: a steady-state rule the user sets - the first and last N strides (rows) of each walking bout left
out of the steady measures (``track --steady-trim N``).

The rows of a bout are :func:`pdrlearn.track.clinical.bout_rows`' (the rows between pauses and long data gaps,
the walking bouts ``n_walking_bouts`` counts). With N > 0 the first N and the last N rows of each bout are left out
of the summary's steady gait speed and time (decision L426: ``steady_gait_speed_mps`` / ``steady_time_s`` /
``steady_distance_m``; ``gait_speed_mps`` and ``walking_time_s`` stay the whole walk's), cadence, stride time /
stride length / speed medians
(:func:`pdrlearn.track.gait.gait_summary`, :func:`pdrlearn.track.evaluate.median_stride_length`) and of the CV
strides (:func:`pdrlearn.track.clinical.steady_rows`: ``stride_time_cv_pct``, ``stride_length_cv_pct``,
``n_cv_strides``, the per-bout CVs of bouts.csv). The speed-up from standing and the slow-down to a stop are no
steady walking; steady state is reached within the first few steps (Lindemann et al. 2008, Gait Posture 27:91-96:
about 2.5 m in frail older people; walkway protocols therefore leave out the acceleration and deceleration
strides). Default 0: today's measures unchanged (the CV's strides already need a straight stride with a stride
time on both sides, L104, so each bout's first two and last stride are never CV strides).

The setting is a :class:`contextvars.ContextVar`, so a batch's threads (``track-all --jobs``) do not share it:
``with steady_trim_set(3): ...`` around the summary's computation (``track`` / ``track-all`` do this).
"""

from __future__ import annotations

import contextvars
from contextlib import contextmanager

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError

#: decision L415: the default number of strides left out at each end of each walking bout (0: none, as before)
STEADY_TRIM = 0
_TRIM = contextvars.ContextVar("pdrlearn_steady_trim", default=STEADY_TRIM)


def steady_trim() -> int:
    """The strides left out at each end of each walking bout in force (L415; :data:`STEADY_TRIM` unless set)."""
    return int(_TRIM.get())


def check_steady_trim(n) -> int:
    """``--steady-trim``'s value as a whole number of strides >= 0; one clear line otherwise (decision L415)."""
    try:
        v = float(n)
    except (TypeError, ValueError):
        v = float("nan")
    if not (v >= 0 and v == int(v)):
        raise DataError(f"--steady-trim {n!r}: give a whole number of strides >= 0 (e.g. 2: the first and last 2 "
                        "strides of each walking bout left out of the steady measures; 0: none, the default)")
    return int(v)


@contextmanager
def steady_trim_set(n: int | None):
    """Decision L415: the measures computed inside leave out the first and last ``n`` strides of each walking bout
    (None: :data:`STEADY_TRIM`)."""
    token = _TRIM.set(STEADY_TRIM if n is None else check_steady_trim(n))
    try:
        yield
    finally:
        _TRIM.reset(token)


def trimmed_rows(steps: pd.DataFrame, n: int | None = None) -> np.ndarray:
    """(rows,) bool in the table's own row order: the rows among the first ``n`` or the last ``n`` rows (in
    ``start_s`` order) of a walking bout (:func:`pdrlearn.track.clinical.bout_rows`); ``n`` None: the setting in
    force (:func:`steady_trim`). All False with ``n`` 0 or a table without ``start_s``."""
    n = steady_trim() if n is None else int(n)
    out = np.zeros(len(steps), bool)
    if n <= 0 or not len(steps) or "start_s" not in steps:
        return out
    from pdrlearn.track.clinical import bout_rows

    order = _sorted_order(steps)
    for a, b in bout_rows(steps):
        out[order[a:min(b, a + n)]] = True
        out[order[max(a, b - n):b]] = True
    return out


def _sorted_order(steps: pd.DataFrame) -> np.ndarray:
    """The table's row positions in ``start_s`` order (stable): the order of ``bout_rows`` and ``steady_rows``."""
    return steps["start_s"].reset_index(drop=True).sort_values(kind="stable").index.to_numpy()


def add_steady_column(steps: pd.DataFrame) -> None:
    """Decision L415, in place: ``steps["steady"]`` (:func:`steady_flags`) before L97's tail of a foot table (after
    ``sideways``, else before ``stride_time_s``: the tail stays last, as ``run`` and ``track --streaming`` write it);
    nothing for a table without stride times."""
    from pdrlearn.track.table_columns import place_column

    flags = steady_flags(steps)
    if flags is not None:
        place_column(steps, "steady", flags, after=("sideways",), before=("stride_time_s",))


def steady_flags(steps: pd.DataFrame) -> np.ndarray | None:
    """Decision L415: steps.csv's ``steady`` column - (rows,) bool in the table's own row order, True for the strides
    the stride-time and stride-length CVs are taken over (:func:`pdrlearn.track.clinical.steady_rows` under the
    steady-trim in force), so ``n_cv_strides`` is their count and ``stride_time_cv_pct`` the CV (SD with n - 1) of
    their ``stride_time_s``. None for a table without stride times (a lower-back track: no CV, L104)."""
    if not len(steps) or "stride_time_s" not in steps or "start_s" not in steps:
        return None
    from pdrlearn.track.clinical import steady_rows

    _, steady = steady_rows(steps)
    out = np.zeros(len(steps), bool)
    out[_sorted_order(steps)] = steady
    return out
