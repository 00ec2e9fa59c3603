"""Decisions L388 / L389 / B297: the force insoles' events against the foot IMU's own (session 33, trial T2
findings 7 and 8).

L389: an insole logged on its own clock (a separate Bluetooth device) can run late or early against the foot IMU,
and L365's stance check passes a shift shorter than a rest. The offset is the median, over the force detector's
initial contacts (the accel-force detector's stance onsets, thesis ch.5.2), of the time to the nearest impact of
the accelerometer detector (the IMU's own IC, thesis ch.5.1 / steps decision 14): :func:`clock_offset`.
L388: the force drop-off (the accel-force detector's swing start) is the stride's toe-off: :func:`toe_offs_in`.
"""

from __future__ import annotations

import numpy as np

#: L389: a force IC is paired with an IMU IC at most this far away (s): under a third of the shortest adult stride
#: (steps decision 37's 0.4 s refractory, MIN_STRIDE_S, is a child's; a stride is ~1 s), so no IC pairs with the
#: next stride's
PAIR_MAX_S = 0.3
#: L390: a larger |offset| (s) is warned about: one sample period at the thesis' 20 Hz (thesis ch.4.3), ten times
#: the clean difference of the two toe-offs (trial T2: drop-off -18.6 ms, gyroscope -14 ms against the truth)
L390_OFFSET_MAX_S = 0.05
#: L390 (amended in session 33 by the lead): the bound is at least this many foot sample periods - both events
#: are dated to a whole sample, so a clean 20 Hz session (scenario A, user 1) read +53 ms over the 50 ms bound
OFFSET_MIN_SAMPLES = 2
#: decision B449: the offset is estimated from at least this many forward strides' pairs (L123's fewest straight
#: strides for a speed); T2's turn-on-the-spot session read +269 ms from a median of 4 strides, mostly pivots
MIN_OFFSET_STRIDES = 5


def clock_offset(force_ic, imu_ic, *, max_pair_s: float = PAIR_MAX_S) -> tuple[float, int]:
    """Decision L389 (pure kernel): (median of force IC - nearest IMU IC over the pairs closer than
    ``max_pair_s``, number of pairs); (NaN, 0) without a pair. Both in s on one time axis, any order."""
    f = np.asarray(force_ic, dtype=float)
    f = f[np.isfinite(f)]
    m = np.sort(np.asarray(imu_ic, dtype=float)[np.isfinite(np.asarray(imu_ic, dtype=float))])
    if not len(f) or not len(m):
        return float("nan"), 0
    j = np.searchsorted(m, f)
    left, right = m[np.clip(j - 1, 0, len(m) - 1)], m[np.clip(j, 0, len(m) - 1)]
    near = np.where(np.abs(f - left) <= np.abs(f - right), left, right)
    d = f - near
    d = d[np.abs(d) <= max_pair_s]
    return (float(np.median(d)), int(len(d))) if len(d) else (float("nan"), 0)


def toe_offs_in(off_s, start_s, event_s) -> np.ndarray:
    """Decision L388 (pure kernel): (B,) s, per stride the last force drop-off ``off_s`` inside
    [``start_s``, ``event_s``) (the push-off before the stride's IC), NaN where none lies there."""
    off = np.sort(np.asarray(off_s, dtype=float)[np.isfinite(np.asarray(off_s, dtype=float))])
    st, ev = np.asarray(start_s, dtype=float), np.asarray(event_s, dtype=float)
    out = np.full(len(st), np.nan)
    if not len(off):
        return out
    k = np.searchsorted(off, ev, side="left") - 1  # the last off before the IC
    ok = (k >= 0) & np.isfinite(st) & np.isfinite(ev)
    cand = off[np.maximum(k, 0)]
    ok &= cand >= st
    out[ok] = cand[ok]
    return out


def force_events(session, *, detected=None):
    """The accel-force detector's table on ``session`` (``event_s`` the stance onsets, ``start_s`` the force
    drop-offs before them), None when it cannot run (no force, no strides). ``detected``: that table when the
    caller already ran the default detector on this session (steps decision 55: it is not run again; an empty
    table stands for a detector that failed)."""
    from pdrlearn.errors import DataError
    from pdrlearn.steps import AccelForceStepDetector

    if detected is not None:
        return detected if len(detected) else None
    try:
        df = AccelForceStepDetector().detect(session)
    except DataError:
        return None
    return df if len(df) else None


def offset_check(session, fev, names: list[str], *, table=None, tc_gyro=None, bound: float | None = None,
                 warn: bool = True, forward=None) -> tuple[float | None, str | None]:
    """Decisions L389 / L390 / B297: (the force-to-IMU clock offset in s, rounded to 1 ms, or None; the warning line
    when ``warn`` (on since L390; ``force_offset_s`` is reported either way) and it exceeds ``bound``, else None).
    ``bound`` None: :data:`L390_OFFSET_MAX_S`. ``fev``: :func:`force_events`' table; ``names``: the force streams.
    L390 (adopted): the force drop-offs inside the strides of ``table`` against their gyroscope toe-offs ``tc_gyro``
    (B,). L389's force onsets against the accelerometer detector's impacts were not adopted (two of six clean users
    read -58 / -67 ms) and are removed (decision L584). Decision B449: ``forward`` (B,) bool, the strides W415's kinds
    class forward (None: all), are the only ones paired, and fewer than :data:`MIN_OFFSET_STRIDES` pairs give
    (None, None) (a pivot's push-off is not a forward toe-off)."""
    if fev is None:
        return None, None
    if bound is None:
        bound = L390_OFFSET_MAX_S
        foot = session.streams.get("fAccelerometer")
        if foot is not None and len(foot) >= 2:  # L390 amended: each event is dated to a whole sample of its
            bound = max(bound, OFFSET_MIN_SAMPLES * foot.period_s)  # stream (a clean 20 Hz scenario A read +53 ms)
    if table is None or tc_gyro is None:  # decision L390
        return None, None
    tf = toe_offs_in(fev["start_s"], table["start_s"], table["event_s"])
    if forward is not None:  # decision B449: forward strides only
        tf = np.where(np.asarray(forward, bool), tf, np.nan)
    off, n = clock_offset(tf, tc_gyro)
    what = "force drop-off - gyroscope toe-off, decision L390"
    if n < MIN_OFFSET_STRIDES:  # decision B449 (L390 took any number)
        return None, None
    off = round(off, 3)
    if not warn or abs(off) <= bound:
        return off, None
    files = ", ".join(f"{n_}.csv" for n_ in names)
    line = (f"{files} run {off * 1000:+.0f} ms against the foot IMU's own events (median of {n} forward strides, "
            f"{what}, B449; "
            f"more than {bound * 1000:.0f} ms): the insoles' clock is not the "
            f"IMU's - shift the insole file's timestamps by about {-off * 1000:+.0f} ms and import it again "
            "(`pdrlearn import ... --merge`), or pass --ignore-force; the force data was not shifted (B297)")
    return off, line
