"""A reference recorded on another clock (decisions steps 56, B333, B334).

``ref_offset_s`` is the reference clock minus the IMU clock (s): a label at ``t`` on the reference clock is at
``t - ref_offset_s`` on the session's clock (a Vicon clock that reads the IMU clock + 5 s: ``ref_offset_s=5``).
:func:`shifted_labels` moves a session's labels by it; :func:`offset_check` slides the reference against the
detections to say when the clocks look offset.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.plasys import DEFAULT_TIME_COLUMNS
from pdrlearn.io.session import Session

#: decision steps 56: the reference is slid against the detections over +- this many seconds
SCAN_S = 10.0
#: decision steps 56: a quarter of the matching tolerance (half a step): the tight window of the scan and the
#: largest shift taken for the detector's own bias
TIGHT_FRAC = 0.25
#: decision steps 69: the shift must also pass this fraction of the matching tolerance (half of it): a shift every match
#: absorbs is the detector's own bias and scatter (clean simulated walks: -0.06 +- 0.045 s at the foot's 0.25 s)
MIN_SHIFT_FRAC = 0.5
#: decision steps 56: the gain in tight matches that names an offset: at least this many reference events ...
MIN_GAIN = 3
#: ... and at least this fraction of them
MIN_GAIN_FRAC = 0.1
#: the scan's distance matrix is built this many elements at a time (memory, not a result)
CHUNK = 1_000_000
#: label time columns moved by the offset: the steps table's (D1) and the extras' (bouts, ics_untimed)
TIME_COLUMNS = (*DEFAULT_TIME_COLUMNS, "after_s", "before_s")


def check_ref_offset(value, where: str = "ref_offset_s") -> float:
    """Decision B333: the reference clock offset as a finite float (s); else one line naming ``where``."""
    try:
        off = float(value)
    except (TypeError, ValueError):
        off = math.nan
    if not math.isfinite(off):
        raise DataError(f"{where} {value!r}: give the reference clock minus the IMU clock in seconds, e.g. 5 or "
                        "-0.12 (decision B333)")
    return off


def _shift(df, offset_s: float, scale: float = 1.0):
    """``df`` with its label times ``t`` moved to ``t * scale - offset_s``."""
    if df is None:
        return None
    out = df.copy()
    for col in TIME_COLUMNS:
        if col in out:
            out[col] = out[col] * scale - offset_s
    return out


def waist_clock_labels(session: Session) -> Session:
    """Decision W380: ``session`` with its labels (steps.csv, ics.csv, bouts.csv ...: kept on the foot clock) moved
    onto the waist clock of a simulated session whose ``meta.json`` gives one (the simulator's ``clock_offset_s`` and
    ``clock_drift_ppm``: ``waist = foot * (1 + drift) + offset``), for scoring the lower back's steps; its meta then
    holds 0 for both, so a second call moves nothing. The session itself when both are 0 or absent (bit for bit)."""
    meta = session.meta or {}
    off, ppm = float(meta.get("clock_offset_s") or 0.0), float(meta.get("clock_drift_ppm") or 0.0)
    if off == 0 and ppm == 0:
        return session
    out = copy.copy(session)
    scale = 1.0 + ppm * 1e-6  # the simulator's waist clock (pdrlearn.sim.simulate: t_out * (1 + drift) + offset)
    out.steps = _shift(session.steps, -off, scale)
    out.extras = {k: _shift(v, -off, scale) for k, v in session.extras.items()}
    out.meta = {**meta, "clock_offset_s": 0.0, "clock_drift_ppm": 0.0}
    return out


def shifted_labels(session: Session, offset_s: float, *, tolerance_s: float = 0.0,
                   where: str = "ref_offset_s") -> Session:
    """``session`` with every label time moved to ``t - offset_s`` (the streams untouched; decision steps 56).
    Decision B334: refused when no reference event then lies inside the recording (+- ``tolerance_s``)."""
    offset_s = check_ref_offset(offset_s, where)
    if offset_s == 0:
        return session
    out = copy.copy(session)
    out.steps = _shift(session.steps, offset_s)
    out.extras = {k: _shift(v, offset_s) for k, v in session.extras.items()}
    if any(len(st) for st in session.streams.values()):
        t0, t1 = session.t_start, session.t_end
        given = _label_times(session)
        moved = given - offset_s
        if given.size and not np.any((moved >= t0 - tolerance_s) & (moved <= t1 + tolerance_s)):
            ms = given - offset_s / 1000.0
            hint = (f"; it looks like milliseconds: {offset_s:g} ms is {offset_s / 1000:g} s"
                    if np.any((ms >= t0) & (ms <= t1)) else "")
            raise DataError(f"{where} {offset_s:g}: moves every reference event out of the recording "
                            f"({t0:.1f}-{t1:.1f} s; the labels span {given.min():.1f}-{given.max():.1f} s on their "
                            f"clock){hint}; give the reference clock minus the IMU clock in s (decision B334)")
    return out


def _label_times(session: Session) -> np.ndarray:
    """Every finite event time of the session's labels (steps.csv, ics.csv)."""
    parts = []
    if session.steps is not None:
        parts += [session.steps[c].to_numpy(float) for c in ("ic_s", "start_s") if c in session.steps]
    ics = session.extras.get("ics")
    if ics is not None and "ic_s" in ics:
        parts.append(ics["ic_s"].to_numpy(float))
    t = np.concatenate(parts) if parts else np.zeros(0)
    return t[np.isfinite(t)]


def offset_check(detected, reference, tolerance_s: float, given_s: float = 0.0) -> dict:
    """Decision steps 56: slide the ``reference`` event times (s, already moved by ``given_s``) against the
    ``detected`` ones over +-:data:`SCAN_S` in steps of half the tight window (:data:`TIGHT_FRAC` x
    ``tolerance_s``). The best shift matches the most reference events within ``tolerance_s`` (a walk is periodic:
    a shift by one stride loses the walk's first or last), then the most within the tight window, then the one
    closest to 0; the median detected - reference error of its tight matches refines it.

    Returns ``ref_offset_estimate_s`` (``given_s`` minus the refined shift: the ``ref_offset_s`` that puts the median
    error at 0, so it includes the detector's own timing bias), ``tight_window_s``, ``tight_matches_as_given``,
    ``tight_matches_at_estimate`` and ``ref_offset_suspect`` (the rule of decision steps 56, with steps 69's half
    tolerance); empty with fewer than 3 events on either side."""
    d = np.sort(np.asarray(detected, dtype=float))
    r = np.sort(np.asarray(reference, dtype=float))
    if d.size < 3 or r.size < 3:
        return {}
    win = TIGHT_FRAC * float(tolerance_s)
    k = int(np.ceil(SCAN_S / (win / 2)))
    grid = np.arange(-k, k + 1) * (win / 2)
    rows = max(1, CHUNK // r.size)  # grid rows at a time: an hour's 7000 contacts x 1281 shifts in pieces
    key = np.concatenate([_scan_key(r, d, grid[i:i + rows], tolerance_s, win) for i in range(0, grid.size, rows)])
    best = np.flatnonzero(key == key.max())
    g = float(grid[best[np.argmin(np.abs(grid[best]))]])
    j = np.clip(np.searchsorted(d, r + g), 1, d.size - 1)
    near = np.where(np.abs(d[j] - r - g) < np.abs(d[j - 1] - r - g), d[j], d[j - 1])  # each one's nearest detection
    err = near - r
    tight = np.abs(err - g) <= win
    shift = float(np.median(err[tight])) if tight.any() else g
    now, at = _near(r, d, win), _near(r + shift, d, win)
    # decision steps 56, and steps 69: past half the tolerance
    past = abs(shift) > max(win, MIN_SHIFT_FRAC * float(tolerance_s))
    suspect = past and at - now >= max(MIN_GAIN, MIN_GAIN_FRAC * r.size)
    return {"ref_offset_estimate_s": float(given_s - shift), "tight_window_s": win,
            "tight_matches_as_given": now, "tight_matches_at_estimate": at, "ref_offset_suspect": bool(suspect)}


def _scan_key(r: np.ndarray, d: np.ndarray, grid: np.ndarray, tolerance_s: float, win: float) -> np.ndarray:
    """For each shift of ``grid``: the reference events ``r`` matched within ``tolerance_s``, times (n + 1), plus those
    within ``win`` (the ranking of :func:`offset_check`)."""
    from pdrlearn.kernels.align import nearest_distance

    dist = nearest_distance(r[None, :] + grid[:, None], d)  # (n_grid, n_ref)
    return (dist <= tolerance_s).sum(axis=1) * (r.size + 1) + (dist <= win).sum(axis=1)


def _near(r: np.ndarray, d: np.ndarray, win: float) -> int:
    """How many reference events ``r`` have a detection of ``d`` (sorted) within ``win`` s."""
    from pdrlearn.kernels.align import nearest_distance

    return int((nearest_distance(r, d) <= win).sum())


def offset_line(check: dict, reference_count: int, tolerance_s: float, option: str = "--ref-offset") -> str | None:
    """Decision steps 56: the one warning line when :func:`offset_check` finds the reference offset, else None."""
    if not check.get("ref_offset_suspect"):
        return None
    est = check["ref_offset_estimate_s"]
    return (f"the reference looks offset from the IMU clock: {check['tight_matches_at_estimate']} of "
            f"{reference_count} reference events lie within {check['tight_window_s']:.3f} s (a quarter of the "
            f"{tolerance_s:g} s tolerance) of a detection at {option} {est:.2f}, {check['tight_matches_as_given']} "
            f"as given; check the synchronisation, or score with {option} {est:.2f} (the reference clock minus the "
            "IMU clock, s; the estimate includes the detector's own timing bias; decision steps 56)")
