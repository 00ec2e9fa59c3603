"""Fixed-length step windows in a gravity-aligned, heading-aligned frame.

:func:`step_windows` cuts every step of a steps table (``start_s``/``end_s``, labels or detector output)
out of a :class:`~pdrlearn.io.Session`, rotates each unit's signals into the step's levelled frame and
resamples each step to ``n_samples`` points. The result :class:`StepWindows` holds
``X (n_steps, n_channels, n_samples)`` with the fixed channel layout :data:`CHANNELS`; channels of a
sensor the session lacks are NaN (see ``available``).

Step frame (right-handed): x = forward horizontal (direction of the step's line, toes side),
y = left horizontal, z = up. See docs/features.md for the construction; summary:

- foot: tilt from the rest specific force at the stance sample nearest the window's start
  (:func:`pdrlearn.signal.gravity_rotation`), attitude propagated with the gyroscope through the swing,
  the residual tilt seen at the stance near the window's end spread linearly over the step; forward =
  principal horizontal axis of the step's acceleration, signed by the sensor's declared forward axis
  (``session.frames["foot"]``) - so the features do not depend on the mounting pitch/roll/yaw.
- waist: tilt from the mean specific force over the step (the pelvis never rests during walking),
  forward = declared forward axis of the unit projected on the horizontal plane.
- Vertical accelerations are specific force minus the rest |g| measured in the same window
  (gravity removed, m/s^2; + = up); ``foot_acc_norm`` keeps gravity (|specific force|, m/s^2).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError, VerticalAxisError
from pdrlearn.features.batch import batch_applicable, fill_windows_batch
from pdrlearn.io.session import DIRECTION_CLASSES, LENGTH_CLASSES, TERRAIN_CLASSES, Session, session_entry
from pdrlearn.kernels.window import (  # noqa: F401 (the layout and rest rule are part of this module's API)
    BOUNDARIES,
    CHANNEL_INDEX,
    CHANNELS,
    GROUP_STREAMS,
    GROUPS,
    TASK_COLUMNS,
    fill_step_window,
    rest_boundaries,
)

log = logging.getLogger(__name__)

#: Classes of each task (thesis ch. 6.1-6.3) and the steps-table column holding them.
TASK_CLASSES: dict[str, tuple[str, ...]] = {
    "terrain": TERRAIN_CLASSES,
    "direction": DIRECTION_CLASSES,
    "length": LENGTH_CLASSES,
}


@dataclass
class StepWindows:
    """Fixed-length step windows.

    Attributes
    ----------
    X : (n_steps, len(CHANNELS), n_samples) float64; channel ``t_s`` is the time since the step start (s)
    durations_s : (n_steps,) step durations (s)
    channels : the channel names (= :data:`CHANNELS`)
    available : sensor groups (keys of :data:`GROUPS`) the session has; the others are NaN
    steps : the steps table the windows were cut from (index reset)
    session : name of the source session
    gap_steps : unit (``"foot"``/``"waist"``) -> (n_steps,) bool, the steps whose window overlaps a gap
        in that unit's accelerometer/gyroscope stream; their channels of that unit are NaN (decision B11)
    source_rows : (n_steps,) each step's row label in the table given to :func:`step_windows` (its index before
        the reset: a session's steps.csv data row, also after :func:`pdrlearn.classify.labels.clean_steps` left
        rows out; decision C47); None when not known
    """

    X: np.ndarray
    durations_s: np.ndarray
    channels: tuple[str, ...] = CHANNELS
    available: tuple[str, ...] = ()
    steps: pd.DataFrame = field(default_factory=pd.DataFrame)
    session: str = ""
    gap_steps: dict[str, np.ndarray] = field(default_factory=dict)
    source_rows: np.ndarray | None = None

    def __len__(self) -> int:
        return int(self.X.shape[0])

    def channel(self, name: str) -> np.ndarray:
        """Signal of one channel, (n_steps, n_samples)."""
        return self.X[:, CHANNEL_INDEX[name], :]

    def labels(self, task: str) -> tuple[np.ndarray, np.ndarray]:
        """``(y, keep)`` for ``task``: see :func:`task_labels`."""
        y, keep, _ = task_labels(self.steps, task, source=self.session)
        return y, keep

    def subset(self, mask: np.ndarray) -> StepWindows:
        """Windows of the selected steps (boolean mask or index array)."""
        idx = np.flatnonzero(mask) if np.asarray(mask).dtype == bool else np.asarray(mask, dtype=int)
        steps = self.steps.iloc[idx].reset_index(drop=True) if len(self.steps) else self.steps
        return StepWindows(self.X[idx], self.durations_s[idx], self.channels, self.available, steps,
                           self.session, {u: m[idx] for u, m in self.gap_steps.items()},
                           None if self.source_rows is None else self.source_rows[idx])


def task_labels(steps: pd.DataFrame, task: str, *,
                source: str = "steps table") -> tuple[np.ndarray, np.ndarray, int]:
    """Labels of ``task`` and which rows to keep.

    Rows whose label is missing or not one of ``TASK_CLASSES[task]`` (e.g. ``unclear``) are skipped
    and counted, not errors.

    Returns
    -------
    y : (n_kept,) object array of class names
    keep : (n_rows,) boolean mask of the kept rows
    n_skipped : number of labelled rows skipped because their value is not a class of the task
    """
    if task not in TASK_CLASSES:
        raise DataError(f"unknown task '{task}'; choose one of {', '.join(TASK_CLASSES)}")
    col = TASK_COLUMNS[task]
    if steps is None or col not in steps:
        raise DataError(f"{source}: has no '{col}' column, so task '{task}' has no labels; "
                        "label the steps or choose another task")
    vals = steps[col]
    keep = vals.isin(TASK_CLASSES[task]).to_numpy()
    n_skipped = int((vals.notna() & ~vals.isin(TASK_CLASSES[task])).sum())
    if n_skipped:
        others = sorted(set(vals[vals.notna() & ~vals.isin(TASK_CLASSES[task])].astype(str)))
        log.info("%s: skipped %d rows with %s values %s", source, n_skipped, col, others)
    return vals[keep].to_numpy(dtype=object), keep, n_skipped


# -- frames ---------------------------------------------------------------------------------------


def _declared_forward(session: Session, placement: str) -> np.ndarray:
    frame = session.require_frame(placement)
    return frame.matrix().T @ np.array([1.0, 0.0, 0.0])  # sensor vector pointing body-forward


# -- main entry point -----------------------------------------------------------------------------


def _check_steps(steps: pd.DataFrame, session: Session) -> tuple[np.ndarray, np.ndarray]:
    if steps is None or len(steps) == 0:
        raise DataError(f"session '{session.name}': the steps table is empty; detect or label steps first")
    for col in ("start_s", "end_s"):
        if col not in steps:
            raise DataError(f"session '{session.name}': steps table lacks column '{col}' (seconds)")
    start = steps["start_s"].to_numpy(dtype=float)
    end = steps["end_s"].to_numpy(dtype=float)
    bad = ~(np.isfinite(start) & np.isfinite(end) & (end > start))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataError(f"session '{session.name}': step {i} has start_s={start[i]!r}, end_s={end[i]!r}; "
                        "every step needs finite times with end_s > start_s")
    return start, end


#: Sensor groups of each unit and the groups whose stream gaps blank the unit (decision B11).
UNIT_GROUPS: dict[str, tuple[str, ...]] = {"foot": ("foot_acc", "foot_gyr", "force"),
                                           "waist": ("waist_acc", "waist_gyr", "waist_baro")}
GAP_GROUPS: dict[str, tuple[str, ...]] = {"foot": ("foot_acc", "foot_gyr"), "waist": ("waist_acc", "waist_gyr")}


#: decision B46: an interval up to this many nominal periods (one sample missing: 2 periods, with jitter
#: allowance) is bridged by the windows' time interpolation, as the waist pipelines bridge it (W34) and
#: :meth:`Stream.on_uniform_clock` does (B33); only a longer one (two or more samples in a row) is a gap
BRIDGED_PERIODS = 2.5
#: features decision 16: ... and never less than this (s): what B46 bridges at 100 Hz (the rate the features were
#: validated at) is bridged at every higher rate, where two samples missing in a row are a hole of a few ms
BRIDGED_S = 0.025


def window_gaps(stream) -> list:
    """The gaps of ``stream`` that blank a step window (decision B46, features decision 16): intervals longer
    than :data:`BRIDGED_PERIODS` nominal periods and than :data:`BRIDGED_S` seconds (:meth:`Stream.gaps`)."""
    return stream.gaps(max(BRIDGED_PERIODS, BRIDGED_S / stream.period_s))


def gap_steps(session: Session, start: np.ndarray, end: np.ndarray,
              available: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Per unit, the steps ``[start, end]`` (s) overlapping a gap (:func:`window_gaps`: an interval over
    :data:`BRIDGED_PERIODS` nominal periods and :data:`BRIDGED_S`; decision B46, features 16) of the unit's
    accelerometer or gyroscope; only units with such steps."""
    out = {}
    for unit, groups in GAP_GROUPS.items():
        mask = np.zeros(len(start), dtype=bool)
        for g in groups:
            if g not in available:
                continue
            for name in GROUP_STREAMS[g]:
                for gap in window_gaps(session.streams[name]):
                    mask |= (start < gap.start_s + gap.duration_s) & (end > gap.start_s)
        if mask.any():
            out[unit] = mask
    return out


def _blank_units(X: np.ndarray, lost: dict[str, np.ndarray], available: tuple[str, ...]) -> None:
    """NaN the unit's channels of the steps (bool masks) in ``lost``."""
    for unit, mask in lost.items():
        for g in UNIT_GROUPS[unit]:
            if g in available:
                X[np.ix_(mask, [CHANNEL_INDEX[c] for c in GROUPS[g]])] = np.nan


def _posture_steps(X: np.ndarray, gaps: dict[str, np.ndarray], bad: list[int], start, end,
                   available: tuple[str, ...], where: str) -> None:
    """Decision B131: the steps whose foot rests with its declared forward axis (nearly) vertical after steps whose
    frame was fine (kneeling, crawling) lose the foot unit as a gap step does (B11: the waist classifies them)."""
    if not bad:
        return
    mask = np.zeros(len(X), dtype=bool)
    mask[bad] = True
    _blank_units(X, {"foot": mask}, available)
    gaps["foot"] = gaps.get("foot", np.zeros(len(X), dtype=bool)) | mask
    log.warning("%s: %d step(s) in %.2f-%.2f s: the foot rested with its declared forward axis (nearly) vertical "
                "(kneeling, crawling or a foot pitched far from level; the steps before had a level frame): their "
                "foot channels are missing (NaN) and they are classified without the foot unit (decision B131)",
                where, len(bad), float(start[bad[0]]), float(end[bad[-1]]))


def _blank_gap_steps(X: np.ndarray, gaps: dict[str, np.ndarray], available: tuple[str, ...],
                     session: str) -> None:
    """NaN the unit's channels of the steps in ``gaps`` (no interpolated values across a gap, B11)."""
    _blank_units(X, gaps, available)
    # one line for every unit (B34): a gap in both units' streams was two lines
    same: dict[bytes, list[str]] = {}  # units whose gaps hit the same steps: one phrase
    for u, m in gaps.items():
        same.setdefault(np.asarray(m, dtype=bool).tobytes(), []).append(u)
    counts = ", ".join(f"{int(gaps[us[0]].sum())} of {len(gaps[us[0]])} steps overlap a gap in the "
                       + (f"{' and '.join(us)} units' streams" if len(us) > 1 else f"{us[0]} unit's streams")
                       for us in same.values())
    if counts:
        log.warning("%s: %s; their %s channels are missing (NaN)", session, counts, " and ".join(gaps))


@session_entry  # decision B49: units and clock checked once (io.validate.check_session), as read_session does
def step_windows(session: Session, steps: pd.DataFrame | None = None, *, n_samples: int = 40,
                 heading: str = "pca", rest_search_s: float = 0.3, batch: bool = True,
                 boundaries: str = "given") -> StepWindows:
    """Cut, level and resample every step of ``steps`` to ``n_samples`` points.

    Parameters
    ----------
    session : the recording (or its folder's path); sensors it lacks give NaN channels (see
        ``StepWindows.available``); checked as :func:`pdrlearn.io.read_session` checks files (decision B49)
    steps : DataFrame with ``start_s``/``end_s`` (s; stance-to-stance windows); default ``session.steps``
    n_samples : samples per resampled step (40 ~ a 1 s step at the PLASYS 20 Hz plus margin)
    heading : ``"pca"`` (principal horizontal axis of the foot's acceleration, signed by the declared
        forward axis: independent of the mounting yaw) or ``"declared"`` (declared forward axis only)
    rest_search_s : the foot's rest sample is searched within this many seconds (at most a quarter of
        the window) from each end of the step
    batch : process all steps at once (:mod:`pdrlearn.features.batch`, equal to the per-step kernel to
        rounding) when each unit's gyroscope shares its accelerometer's clock; False = step by step
    boundaries : ``"given"`` cuts at ``start_s``/``end_s``; ``"rest"`` first moves each boundary to the
        foot's quietest sample within ``rest_search_s`` (:func:`rest_boundaries`, decision 13), so steps
        labelled at other gait phases become rest-to-rest windows; the times used are in
        ``steps["window_start_s"/"window_end_s"]``. Needs the foot gyroscope; without it (waist-only
        sessions) the given boundaries are kept.

    Raises
    ------
    DataError : empty/invalid steps table, a step outside a present stream, NaN samples, no frame
    """
    if heading not in ("pca", "declared"):
        raise DataError(f"step_windows: heading must be 'pca' or 'declared', not {heading!r}")
    if n_samples < 6:
        raise DataError(f"step_windows: n_samples={n_samples} is too small; use at least 6")
    if boundaries not in BOUNDARIES:
        raise DataError(f"step_windows: boundaries must be one of {', '.join(BOUNDARIES)}, not {boundaries!r}")
    if steps is None:
        steps = session.steps
    start, end = _check_steps(steps, session)
    available = tuple(g for g, names in GROUP_STREAMS.items() if session.has(*names))
    if "foot_acc" not in available and "waist_acc" not in available:
        from pdrlearn.errors import MissingSensorError

        raise MissingSensorError(f"session '{session.name}' has neither fAccelerometer nor wAccelerometer; "
                                 "step windows need at least one accelerometer")
    for g in available:
        for name in GROUP_STREAMS[g]:
            s = session.streams[name]
            if len(s) < 2:
                raise DataError(f"session '{session.name}': stream {name} has fewer than 2 samples")
            if not np.all(np.isfinite(s.values)):
                raise DataError(f"session '{session.name}': stream {name} contains NaN/inf values; "
                                "clean or interpolate it first")
            if start.min() < s.t[0] - 0.5 or end.max() > s.t[-1] + 0.5:
                raise DataError(f"session '{session.name}': steps span {start.min():.2f}-{end.max():.2f} s "
                                f"but {name} covers {s.t[0]:.2f}-{s.t[-1]:.2f} s; align the clocks or "
                                "drop the steps outside the recording")
    fwd_foot = _declared_forward(session, "foot") if "foot_acc" in available else None
    fwd_waist = _declared_forward(session, "waist") if "waist_acc" in available else None
    out_steps = steps.reset_index(drop=True).copy()
    if boundaries == "rest":
        if "foot_gyr" in available:
            gyro = session.streams["fGyroscope"]
            start, end = rest_boundaries(gyro.t, gyro.values, start, end, search_s=rest_search_s)
        else:
            log.info("session '%s': no foot gyroscope; step windows keep the given boundaries", session.name)
        out_steps["window_start_s"], out_steps["window_end_s"] = start, end

    n = len(start)
    X = np.full((n, len(CHANNELS), n_samples), np.nan)
    streams = {name: (s.t, s.values) for name, s in session.streams.items()}
    forward = {p: f for p, f in (("foot", fwd_foot), ("waist", fwd_waist)) if f is not None}
    gaps = gap_steps(session, start, end, available)
    per_step = not (batch and batch_applicable(streams, available))
    if not per_step:  # all steps at once (pdrlearn.features.batch)
        try:
            fill_windows_batch(X, streams, start, end, channel_index=CHANNEL_INDEX, available=available,
                               forward=forward, rest_search_s=rest_search_s, heading=heading)
        except VerticalAxisError:  # decision B131: step by step, to tell a posture from a wrong frame
            per_step = True
        except DataError as exc:
            raise DataError(f"session '{session.name}': {exc}") from None
    posture: list[int] = []
    if per_step:
        for i in range(n):
            t0, t1 = float(start[i]), float(end[i])
            try:
                fill_step_window(X[i], streams, t0, t1, channel_index=CHANNEL_INDEX, available=available,
                                 forward=forward, rest_search_s=rest_search_s, heading=heading)
            except VerticalAxisError as exc:
                if i == len(posture):  # B131: no step before had a level frame: the frame cannot be judged
                    raise DataError(f"session '{session.name}', step {i} ({t0:.2f}-{t1:.2f} s): {exc}") from None
                X[i] = np.nan  # the waist's channels again, the foot's left NaN
                fill_step_window(X[i], streams, t0, t1, channel_index=CHANNEL_INDEX, forward=forward,
                                 available=tuple(g for g in available if g not in UNIT_GROUPS["foot"]),
                                 rest_search_s=rest_search_s, heading=heading)
                posture.append(i)
            except DataError as exc:
                raise DataError(f"session '{session.name}', step {i} ({t0:.2f}-{t1:.2f} s): {exc}") from None
    _blank_gap_steps(X, gaps, available, session.where)
    _posture_steps(X, gaps, posture, start, end, available, session.where)
    return StepWindows(X=X, durations_s=end - start, channels=CHANNELS, available=available,
                       steps=out_steps, session=session.name, gap_steps=gaps,
                       source_rows=np.asarray(steps.index) if steps.index.dtype.kind in "iu" else None)
