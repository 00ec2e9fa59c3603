"""Decision L365: the force sensors' stance checked against the foot IMU's own rests and swings.

The insoles (``fForceA`` heel, ``fForceB`` toe) time the foot's stance when recorded (``track`` M2/M3, the rests
``steps`` reduces a detector to). They are an optional, separately connected stream: a Bluetooth insole that drops
out reads 0 N or stops, the other foot's insole can be imported beside this foot's IMU, a channel can stick. Each of
these made the force stance override a foot IMU that kept walking (trial 33 T2 findings 1, 2, 4). So every
rest-to-rest stride of the IMU (:func:`~pdrlearn.displace.foot.inertial_stance`, the existing foot rest detector)
whose foot swings is checked: the force must load the foot during the IMU's rests (foot flat lies inside stance) and
unload it for at least the accel-force detector's shortest swing between them (the swing lies between two foot
flats), and must have no gap the IMU does not have.
A stride that fails takes the IMU's stance from the start of its first rest to the end of its second; when at least
:data:`SESSION_FALLBACK_FRAC` of the strides fail, the whole session does (the force is not this foot's).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pdrlearn.kernels.contact import FORCE_MIN_SWING_S
from pdrlearn.kernels.units import FOOT_NO_SWING

#: L365: the share of an IMU rest's samples the force must load. Foot flat (the IMU's rest) lies inside the stance
#: of normal walking (stance ~60 % of the stride, foot flat ~10-45 %: Perry & Burnfield, Gait Analysis, 2nd ed.,
#: 2010, ch. 1, as recalled); half a rest unloaded is an unloaded foot, not a timing difference
REST_LOADED_MIN = 0.5
#: L365: at least this share of the IMU's strides failing = the force is not this foot's: the session's stance from
#: the IMU alone (one insole dropping out for a while leaves the rest of the session on force)
SESSION_FALLBACK_FRAC = 0.5
#: steps 71: loaded runs around dropped lulls must start less than this many of the session's typical strides apart
#: (a lull lies inside one stride; an insole dropout over a real rest spans two; 1.5 is halfway, no document)
LULL_MAX_STRIDES = 1.5
#: Decision B421 (session 42, trial T2 finding F8): a lull may last up to this share of the median loaded rest (the
#: IMU's rest runs the force loads: the foot flats) when that is longer than the accel-force detector's shortest
#: swing. A 2 s step's foot flats last 1.5-1.7 s and its swing lulls 0.15-0.17 s, just over the fixed 0.15 s
#: (thesis ch.5.2), so correct insoles were blamed in 9 of 10 strides; normal walking's 0.3-0.5 s foot flats keep
#: 0.15 s; an insole dropping out over a real rest leaves a whole foot flat unloaded (a share of 1), so it stays
#: blamed. 0.25: between the slow lulls' ~0.1 and 1; not from a document. (Scaling with the stride was tried first:
#: a stride estimate doubled by the very dropout made a 0.4 s dropped-out foot flat a lull, tests/test_paretic_s37.py)
LULL_REST_FRAC = 0.25


@dataclass
class ForceCheck:
    """What :func:`check_force_stance` found: ``bad`` (k, 2) sample spans [a, b) where the IMU's stance replaces the
    force's, ``n_strides`` the IMU's swinging strides checked, ``n_bad`` how many failed, ``session`` True when the
    whole session falls back, ``reasons`` the failures' kinds (flat/unloaded rest, loaded swing, gap)."""

    bad: np.ndarray
    n_strides: int
    n_bad: int
    session: bool
    reasons: list[str] = field(default_factory=list)


def check_force_stance(t: np.ndarray, loaded: np.ndarray, rest: np.ndarray, gyr_norm: np.ndarray,
                       gap: np.ndarray | None = None, *, rest_loaded_min: float = REST_LOADED_MIN,
                       swing_rate: float = FOOT_NO_SWING, min_swing_s: float = FORCE_MIN_SWING_S,
                       session_frac: float = SESSION_FALLBACK_FRAC) -> ForceCheck:
    """Decision L365 (pure kernel): per rest-to-rest stride of the IMU's ``rest`` mask (runs of
    :func:`~pdrlearn.displace.foot.stance_runs`) whose largest ``gyr_norm`` (rad/s) between the rests reaches
    ``swing_rate`` (B91's :data:`~pdrlearn.kernels.units.FOOT_NO_SWING`: the foot swings), the force's ``loaded``
    mask must be True on at least ``rest_loaded_min`` of each rest's samples and False for at least ``min_swing_s``
    in a row between them (the accel-force detector's shortest swing, thesis ch.5.2 / :data:`FORCE_MIN_SWING_S`),
    and ``gap`` (samples inside a force-only gap) must be False throughout. All arrays (n,) on the times ``t``."""
    from pdrlearn.displace.foot import stance_runs

    t = np.asarray(t, dtype=float)
    loaded = np.asarray(loaded, dtype=bool)
    g = np.asarray(gyr_norm, dtype=float)
    gap = np.zeros(len(t), dtype=bool) if gap is None else np.asarray(gap, dtype=bool)
    rr = swing_lulls_dropped(t, stance_runs(t, np.asarray(rest, dtype=bool)), loaded, rest_loaded_min, min_swing_s)
    bad, reasons, n = [], [], 0
    for k in range(len(rr) - 1):
        s0, s1 = rr[k, 1], rr[k + 1, 0]  # the swing between rest k and rest k + 1
        if s1 <= s0:
            continue
        pk = s0 + int(np.argmax(g[s0:s1]))
        if not g[pk] >= swing_rate:
            continue  # a shuffle or weight shift, not a stride
        n += 1
        a, b = rr[k, 0], rr[k + 1, 1]
        why = ("a gap" if gap[a:b].any() else
               "no load in the foot's rest" if min(loaded[rr[k, 0]:rr[k, 1]].mean(),
                                                   loaded[rr[k + 1, 0]:rr[k + 1, 1]].mean()) < rest_loaded_min else
               "no unloaded swing" if _longest_false_s(t[s0:s1], loaded[s0:s1]) < min_swing_s else None)
        if why is not None:
            bad.append((a, b))
            reasons.append(why)
    whole = n > 0 and len(bad) >= session_frac * n
    spans = np.array([(0, len(t))] if whole else bad, dtype=np.int64).reshape(-1, 2)
    return ForceCheck(spans, n, len(bad), whole, reasons)


def swing_lulls_dropped(t: np.ndarray, rr: np.ndarray, loaded: np.ndarray, rest_loaded_min: float = REST_LOADED_MIN,
                        min_swing_s: float = FORCE_MIN_SWING_S) -> np.ndarray:
    """Decision steps 70 (pure kernel): the IMU's rest runs ``rr`` (k, 2) without those that lie in the force's swing.
    A slow swing's lulls pass the IMU's rest test (steps 61, S77: under even the fixed 0.4 rad/s) and split a
    paretic stride in two; the insoles, unloaded there, were then blamed (L365). Runs the force loads on less than
    ``rest_loaded_min`` of their samples (one or several in a row) are lulls, not rests, when the force loads the
    runs on both sides at least that much and stays unloaded from its load in the run before to its load in the run
    after (one unbroken swing of the force's holds them), and each lasts less than ``min_swing_s`` (the accel-force
    detector's shortest swing, thesis ch.5.2, :data:`FORCE_MIN_SWING_S`; decision B421: or than
    :data:`LULL_REST_FRAC` of the median loaded rest, when longer): a pause shorter than any swing the force would count
    is a lull of the swing. Decision steps 71: and the loaded runs on both sides start less than
    :data:`LULL_MAX_STRIDES` of the session's typical stride apart (:func:`_typical_stride`; fewer than two loaded
    runs: nothing dropped), decision B421: or end less than that apart (the first stride after a
    standstill). A real foot flat can be as short as a lull (gaitmap MS: 0.01-0.15 s), but
    an insole that drops out over it leaves the loaded runs two strides apart, and L365 still blames the insole."""
    t = np.asarray(t, dtype=float)
    loaded = np.asarray(loaded, dtype=bool)
    rr = np.asarray(rr, dtype=np.int64).reshape(-1, 2)
    full = np.array([b > a and loaded[a:b].mean() >= rest_loaded_min for a, b in rr], dtype=bool)
    keep = np.ones(len(rr), dtype=bool)
    stride = _typical_stride(t[rr[:, 0]], full)
    # decision B421: the longest lull grows with a slow walker's long foot flats (none loaded: min_swing_s alone)
    flats = t[rr[full, 1] - 1] - t[rr[full, 0]]
    lull_max = max(min_swing_s, LULL_REST_FRAC * float(np.median(flats))) if len(flats) else min_swing_s
    k = 1
    while k < len(rr) - 1:
        if full[k] or not full[k - 1]:
            k += 1
            continue
        j = k
        while j < len(rr) and not full[j]:
            j += 1  # runs k .. j-1 unloaded, j the next loaded run (if any)
        if j < len(rr):
            last = rr[k - 1, 0] + np.flatnonzero(loaded[rr[k - 1, 0]:rr[k, 0]])[-1]
            first = rr[j - 1, 1] + np.flatnonzero(loaded[rr[j - 1, 1]:rr[j, 1]])[0]
            short = all(t[e - 1] - t[s] < lull_max for s, e in rr[k:j])
            one = t[rr[j, 0]] - t[rr[k - 1, 0]] < LULL_MAX_STRIDES * stride  # steps 71 (NaN: False)
            # decision B421: or they end less than that apart - the first stride after a standstill, whose loaded
            # run before started seconds earlier (a dropout over a real rest leaves both two strides apart)
            one = one or t[rr[j, 1] - 1] - t[rr[k - 1, 1] - 1] < LULL_MAX_STRIDES * stride
            if short and one and not loaded[last + 1:first].any():
                keep[k:j] = False
        k = j
    return rr[keep]


def _typical_stride(starts: np.ndarray, full: np.ndarray) -> float:
    """Decision steps 71: the median start-to-start time (s) of loaded rest runs next to each other (no unloaded run
    between: a lull or a dropout doubles no interval of these); when there is no such pair (a foot that lulls in
    every stride), of successive loaded runs with the unloaded ones skipped; NaN with fewer than two loaded runs."""
    pair = np.flatnonzero(full[:-1] & full[1:])
    if len(pair):
        return float(np.median(starts[pair + 1] - starts[pair]))
    s = starts[full]
    return float(np.median(np.diff(s))) if len(s) > 1 else float("nan")


def _longest_false_s(t: np.ndarray, mask: np.ndarray) -> float:
    """The longest run of False in ``mask`` (s, first to last sample of the run plus one sample period)."""
    from pdrlearn.signal.conditioning import runs

    r = runs(~mask)
    if not len(t) or not len(r):
        return 0.0
    dt = float(np.median(np.diff(t))) if len(t) > 1 else 0.0
    return max(float(t[b - 1] - t[a]) + dt for a, b in r)


def spans_text(t: np.ndarray, spans: np.ndarray, *, most: int = 3) -> str:
    """``12.3-15.6 s, 20.1-22.0 s`` of sample spans [a, b) merged where they touch (at most ``most`` named)."""
    merged: list[list[int]] = []
    for a, b in np.asarray(spans, dtype=np.int64).reshape(-1, 2):
        if merged and a <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append([int(a), int(b)])
    parts = [f"{t[a]:.1f}-{t[min(b, len(t)) - 1]:.1f} s" for a, b in merged[:most]]
    return ", ".join(parts) + (f" and {len(merged) - most} more" if len(merged) > most else "")


_NO_SPANS = np.zeros((0, 2))

#: L366: the switch's name on the command line and in the API, as the lines name it
IGNORE_FORCE = "--ignore-force (ignore_force=True)"


def reads_force_refusal(steps) -> str | None:
    """Decision B299: the one line refusing ``ignore_force=True`` (L366) with a foot detector that reads the force
    sensors (``steps``: a registered detector's name, ``"NAME:key=value,..."``, or a
    :class:`~pdrlearn.steps.StepDetector`; it reads them when its ``input_columns`` name a force channel), else None.
    Without it ``--ignore-force --detector accel-force`` still took its strides from the insoles (review R2,
    finding 5)."""
    import pdrlearn.steps as steps_mod

    if isinstance(steps, str):
        name = steps.split(":", 1)[0].strip()
        steps = steps_mod.DETECTORS.get(name)
    cols = getattr(steps, "input_columns", ()) if steps is not None and not isinstance(steps, str) else ()
    if not any(str(c).startswith("force") for c in cols):
        return None
    return (f"{IGNORE_FORCE} leaves the force sensors out, and the detector {steps.name} (--detector / steps=) reads "
            f"fForceA/fForceB; use --detector accel (steps='accel') or drop --ignore-force (decision B299)")


def _force_only_gaps(session, t: np.ndarray, names: list[str]) -> np.ndarray:
    """(n,) True at the times ``t`` inside a gap of a force stream that the foot IMU does not share."""
    def mask(stream_names) -> np.ndarray:
        m = np.zeros(len(t), dtype=bool)
        for n in stream_names:
            s = session.streams.get(n)
            for gp in (s.gaps() if s is not None and len(s) >= 2 else ()):
                m |= (t > gp.start_s) & (t < gp.start_s + gp.duration_s)
        return m

    return mask(names) & ~mask(("fAccelerometer", "fGyroscope"))


def _disagreement(session, foot, rest: np.ndarray):
    """Decision L365's check (shared with L406): the force streams' names and :func:`check_force_stance`'s result of
    their load against the IMU's rests ``rest``, its swings and the force-only gaps."""
    from pdrlearn.displace.foot import force_stance

    names = [n for n in ("fForceA", "fForceB") if n in session.streams and len(session.streams[n]) >= 2]
    loaded = force_stance(session, foot.t)  # the load alone, without the gyro's calm test
    return names, check_force_stance(foot.t, loaded, rest, np.linalg.norm(np.asarray(foot.gyr, float), axis=1),
                                     _force_only_gaps(session, np.asarray(foot.t, float), names))


def streamed_insole_line(session, command: str) -> str | None:
    """Decision L406: L365's check for a streamed foot track (``track --streaming``, ``pdrlearn run``), whose
    contacts read the force as recorded (E50): one line when the insoles (tared as offline, B284) disagree with the
    foot IMU, naming the files, the strides, the spans and the way out (the offline track takes the IMU's stance
    there, L365); None when they agree, without force or without a usable foot unit. Nothing is changed."""
    from pdrlearn.displace.foot import force_stance, inertial_stance
    from pdrlearn.errors import DataError
    from pdrlearn.orient import unit_data

    try:
        foot = unit_data(session, "foot", purpose=f"{command}'s insole check")
    except DataError:
        return None
    session, _ = tared(session, foot)
    if force_stance(session, foot.t, foot.gyr) is None:
        return None
    names, chk = _disagreement(session, foot, inertial_stance(foot.acc, foot.gyr, foot.fs))
    if not chk.n_bad:
        return None
    where = "the whole session" if chk.session else spans_text(foot.t, chk.bad)
    return (f"{', '.join(f'{n}.csv' for n in names)} disagree with the foot IMU in {chk.n_bad} of {chk.n_strides} "
            f"strides ({where}: {', '.join(sorted(set(chk.reasons)))}): {command}'s streamed contacts read the force "
            "as recorded (decision L406) - check the insoles, or track offline (`pdrlearn track DIR`, which takes the "
            "IMU's stance there, L365; --ignore-force leaves the insoles out)")


def checked_stance(session, foot, *, use_force: bool = True, fix: str = f"pass {IGNORE_FORCE} to track without them"
                   ) -> tuple[np.ndarray, str, list[str], np.ndarray]:
    """Decisions L365 / L366: the foot unit's zero-velocity samples on ``foot.t`` (a
    :class:`~pdrlearn.orient.UnitData`), their source, the warning lines and the (k, 2) start/end times (s) of the
    spans whose stance is the IMU's in a force stance (where a force detector's strides are not to be trusted).
    ``use_force`` False (L366's switch, ``--ignore-force``) or no usable force sensor: the IMU's
    :func:`~pdrlearn.displace.foot.inertial_stance` ("inertial"). Else
    :func:`~pdrlearn.displace.foot.force_stance` checked by :func:`check_force_stance`: the failing strides take
    the IMU's stance ("force"), or the whole session does ("inertial (force disagrees)"), with one line naming the
    force files, the spans, why and the fix (``fix``: the command's way out)."""
    from pdrlearn.displace.foot import force_stance, inertial_stance

    rest = inertial_stance(foot.acc, foot.gyr, foot.fs)
    if not use_force:
        return rest, "inertial", [], _NO_SPANS
    stance = force_stance(session, foot.t, foot.gyr)
    if stance is None:
        return rest, "inertial", [], _NO_SPANS
    names, chk = _disagreement(session, foot, rest)
    if not chk.n_bad:
        return stance, "force", [], _NO_SPANS
    files = ", ".join(f"{n}.csv" for n in names)
    why = ", ".join(sorted(set(chk.reasons)))
    if chk.session:
        line = (f"{files} disagree with the foot IMU in {chk.n_bad} of {chk.n_strides} strides ({why}): the whole "
                f"session's stance is the IMU's (decision L365) - the insoles may be the other foot's, stuck or "
                f"unloaded; check them, or {fix}")
        return rest, "inertial (force disagrees)", [line], _NO_SPANS
    out = stance.copy()
    for a, b in chk.bad:
        out[a:b] = rest[a:b]
    line = (f"{files} disagree with the foot IMU in {chk.n_bad} of {chk.n_strides} strides "
            f"({spans_text(foot.t, chk.bad)}: {why}): the stance there is the IMU's (decision L365) - an insole "
            f"that dropped out or lost its connection; check it, or {fix}")
    t = np.asarray(foot.t, dtype=float)
    return out, "force", [line], np.column_stack([t[chk.bad[:, 0]], t[np.minimum(chk.bad[:, 1], len(t)) - 1]])


def stitch_rows(force: np.ndarray, imu: np.ndarray, force_in: np.ndarray, imu_in: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """Decision L397 (pure kernel): which rows of a force detector's table (``force`` (n, 2) start/end s) to keep and
    which of the accelerometer detector's (``imu`` (m, 2)) to take, given whose event lies where the force
    disagrees (``force_in`` (n,), ``imu_in`` (m,) bool). Rows of both tables that overlap in time are the same
    swing (a chain of overlaps one group); a group with a row flagged takes all its IMU rows and none of its
    force rows, any other group keeps its force rows. So a swing at the seam of a force span and an IMU span is
    counted once, whichever side of the seam each table puts its event (L365 had lost it when the force's clock
    ran late: neither event fell on its own side)."""
    f = np.asarray(force, dtype=float).reshape(-1, 2)
    m = np.asarray(imu, dtype=float).reshape(-1, 2)
    rows = np.concatenate([f, m])
    flag = np.concatenate([np.asarray(force_in, dtype=bool), np.asarray(imu_in, dtype=bool)])
    order = np.argsort(rows[:, 0], kind="stable")
    group = np.empty(len(rows), dtype=np.int64)
    g, end = -1, -np.inf
    for i in order:  # a row that starts before the group's latest end overlaps it
        if rows[i, 0] >= end:
            g += 1
        group[i] = g
        end = rows[i, 1] if rows[i, 0] >= end else max(end, rows[i, 1])
    bad = np.isin(group, group[flag])
    return ~bad[:len(f)], bad[len(f):]


def imu_strides_in(session, strides, spans: np.ndarray):
    """Decision L365: a force detector's ``strides`` table with its rows where the force disagrees with the IMU
    (``spans`` (k, 2) s) replaced by the accelerometer detector's rows there (an insole that reads 0 N or stops
    finds no stride where the foot walks on). A row is there when its event (``event_s``, else ``end_s``) lies in a
    span, and with it every row of either table that overlaps it (:func:`stitch_rows`, decision L397). Decision
    L405: when rows of both detectors remain, ``contact_source`` says which timed each row's contact (``force`` /
    ``imu``; the stride-time CV takes no stride time from one to the other)."""
    import pandas as pd

    from pdrlearn.steps import AccelStepDetector

    def inside(table) -> np.ndarray:
        ev = np.asarray(table["event_s"] if "event_s" in table else table["end_s"], dtype=float)
        return np.any((ev[:, None] >= spans[:, 0]) & (ev[:, None] <= spans[:, 1]), axis=1)

    def windows(table) -> np.ndarray:
        return table[["start_s", "end_s"]].to_numpy(dtype=float)

    imu = AccelStepDetector().detect(session)
    if not len(imu):
        return strides
    keep, take = stitch_rows(windows(strides), windows(imu), inside(strides), inside(imu))
    force_rows, imu_rows = strides[keep], imu[take]
    if len(force_rows) and len(imu_rows):  # decision L405: a stitched table says whose contact each row has
        force_rows, imu_rows = force_rows.assign(contact_source="force"), imu_rows.assign(contact_source="imu")
    out = pd.concat([force_rows, imu_rows], ignore_index=True)
    return out.sort_values("start_s", kind="stable").reset_index(drop=True)


def swing_floor(t: np.ndarray, f: np.ndarray, rest: np.ndarray, gyr_norm: np.ndarray, *,
                swing_rate: float = FOOT_NO_SWING) -> float:
    """Decision B284 (pure kernel): a force channel's unloaded reading: the median over the IMU's swinging strides
    (rest to rest, largest ``gyr_norm`` at least ``swing_rate``) of the channel's lowest value between the two
    rests (the insole carries no load in the swing). NaN without a swinging stride (standing: no unloaded moment)."""
    from pdrlearn.displace.foot import stance_runs

    rr = stance_runs(np.asarray(t, dtype=float), np.asarray(rest, dtype=bool))
    g = np.asarray(gyr_norm, dtype=float)
    lows = [float(np.min(f[a:b])) for a, b in zip(rr[:-1, 1], rr[1:, 0], strict=True)
            if b > a and np.max(g[a:b]) >= swing_rate]
    return float(np.median(lows)) if lows else float("nan")


def force_offsets(session, foot) -> dict[str, float]:
    """Decision B284: stream name -> the unloaded offset to subtract from ``fForceA`` / ``fForceB``: the channel's
    :func:`swing_floor` when it exceeds the accel-force detector's off level (``FORCE_OFF_FRAC`` of its 95th
    percentile: the detector would never see a swing; raw ADC counts of FSR insoles read ~250 unloaded), else
    nothing (a channel near 0 N is left bit for bit). ``foot``: the foot unit's :class:`~pdrlearn.orient.UnitData`."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.kernels.contact import FORCE_OFF_FRAC

    names = [n for n in ("fForceA", "fForceB") if n in session.streams and len(session.streams[n]) >= 2]
    if not names:
        return {}
    t = np.asarray(foot.t, dtype=float)
    rest = inertial_stance(foot.acc, foot.gyr, foot.fs)
    g = np.linalg.norm(np.asarray(foot.gyr, dtype=float), axis=1)
    out = {}
    for n in names:
        s = session.streams[n]
        f = np.interp(t, s.t, s.values[:, 0])
        floor = swing_floor(t, f, rest, g)
        if np.isfinite(floor) and floor > FORCE_OFF_FRAC * float(np.percentile(s.values[:, 0], 95)):
            out[n] = floor
    return out


def offset_line(offsets: dict[str, float], *, suffix: str = ".csv",
                fix: str = "tare the insole or subtract its unloaded reading before `pdrlearn import`") -> str | None:
    """Decision B284's warning: the channels whose unloaded offset was subtracted, and how to avoid it (``suffix``
    after each channel's name, ``fix`` the advice: steps decision 73's online detector names its columns)."""
    if not offsets:
        return None
    parts = ", ".join(f"{n}{suffix} never drops below ~{v:.4g} in the foot's swings" for n, v in offsets.items())
    return (f"{parts} (an unloaded offset: raw ADC counts of an FSR insole?): subtracted before the force thresholds "
            f"(decision B284); {fix} to silence this")


def tared(session, foot):
    """Decision B284: ``session`` with the offsets of :func:`force_offsets` subtracted from its force streams (a
    shallow copy; the same session when there is none) and the warning line (None without)."""
    import copy

    offsets = force_offsets(session, foot)
    if not offsets:
        return session, None
    out = copy.copy(session)
    out.streams = dict(session.streams)
    for n, v in offsets.items():
        s = session.streams[n]
        out.streams[n] = type(s)(s.name, s.t, np.maximum(s.values - v, 0.0))
    return out, offset_line(offsets)
