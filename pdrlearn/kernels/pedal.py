"""Foot strides that are pedalling, not walking: a closed vertical loop (decisions L611 / L612 in
docs/decisions/localization.md), numpy only.

A crank takes the foot up and down a circle with no travel; a rest-to-rest segmentation cuts it into half or whole
turns whose raw height changes (the stride integrator's, before any levelling or class rule) flip sign every one or
two "strides" (trial T3: +-0.1 to +-0.9 m), where a level walking stride's raw height stays within a few cm and a stair
stride's keeps its sign along the flight. Offline (``track``) and streamed (``track --streaming``) tracks call the same
functions.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.units import STANDARD_GRAVITY

#: decision L611: a raw height change at least this large (m) has a sign that counts (a level stride's raw height stays
#: within a few cm; T3's pedalling strides changed 0.07-0.9 m)
REVERSAL_MIN_DZ_M = 0.05
#: decision L611 (third rule): a reversing stride rises or falls at least this fraction of its horizontal travel (real
#: level walking's raw height wanders 0.06-0.10 of a 1.4 m stride, gaitmap_level_right; a crank's "strides" 0.8-20)
STEEP = 0.3
#: decision L621: a reversing stride counts only when it travels less than this (m, raw horizontal) or is unrested (the
#: crank "strides" of tests/test_pedal_s43_l611.py travel 0.012-0.254 m; a stair stride 0.56-0.58 m; review R2 F4)
TRAVEL_MAX_M = 0.3
#: decision L611: two strides belong to one chain when the second starts at most this long (s) after the first ends
CHAIN_PAUSE_S = 1.0
#: decision L611: a stride's neighbourhood: itself and up to this many strides of its chain before and after it
NEIGHBOURS = 2
#: decision L611: a stride is pedalling with at least this many reversals in its neighbourhood (a curb up and down or a
#: stair flight up then down is one)
MIN_REVERSALS = 2
#: decision L611 (second rule): a stride end's rest reads the foot accelerometer within this long (s) of it
REST_WINDOW_S = 0.1
#: decision L611 (second rule): a rest whose median | |acc| - g | is at least this (m/s^2) is no rest (simulated walks'
#: mid-stance 0.01-0.09, the real gaitmap recordings' at most 0.43; a crank at 40-95 rpm 1.7-10.3 in the median)
UNRESTED_MPS2 = 1.0
#: decision L611 (second rule): a stride is pedalling when this many strides of its neighbourhood are unrested
MIN_UNRESTED = 3
#: decision L611: pedalling spans closer than this (s) are named as one in the warning line
MERGE_SPANS_S = 10.0
#: decision L639: an offline rest-to-rest stride longer than this many of the foot's stride caps (L605's
#: ``kernels.contact.stride_cap_s``: L80's 3 s at a normal rhythm) is a ride, not walking: three strides' time without
#: one rest of the foot (I5's S99 bike ride made one 57.5 s "stride" of 24.59 m)
RIDE_STRIDE_CAPS = 3.0


def unrested_strides(t: np.ndarray, acc: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
                     g_rest: float = STANDARD_GRAVITY) -> np.ndarray:
    """Decision L611 (second rule): (B,) bool, the strides whose two ends both lack a rest: the median of
    | |acc| - g_rest | over the foot accelerometer's samples (``t`` s, ``acc`` (n, 3) m/s^2) within
    :data:`REST_WINDOW_S` of the end is at least :data:`UNRESTED_MPS2` (an end without samples is a rest: nothing to
    judge). ``g_rest``: the accelerometer's own rest reading (decision L621: a mis-scaled one, B201, reads 1.2 g)."""
    t = np.asarray(t, dtype=float)
    dev = np.abs(np.linalg.norm(np.asarray(acc, dtype=float)[:, :3], axis=1) - float(g_rest))

    def moving(x: np.ndarray) -> np.ndarray:
        a = np.searchsorted(t, np.asarray(x, dtype=float) - REST_WINDOW_S, side="left")
        b = np.searchsorted(t, np.asarray(x, dtype=float) + REST_WINDOW_S, side="right")
        return np.array([b_ > a_ and float(np.median(dev[a_:b_])) >= UNRESTED_MPS2
                         for a_, b_ in zip(a, b, strict=True)], dtype=bool)

    return moving(start_s) & moving(end_s)


def travelling_strides(dz: np.ndarray, travel: np.ndarray | None, stride_travel_m: float | None) -> np.ndarray:
    """Decision L799: (B,) bool, the level strides that travel: raw horizontal ``travel`` (m) at least
    ``stride_travel_m`` and raw height change ``dz`` (m) under L611's :data:`REVERSAL_MIN_DZ_M` - a stride, not a pedal
    stroke (a crank's "strides" travel 0.012-0.254 m and rise or fall 0.07-0.9 m, L611 / L621). None: none."""
    dz = np.asarray(dz, dtype=float)
    if travel is None or stride_travel_m is None:
        return np.zeros(len(dz), dtype=bool)
    return (np.abs(np.asarray(travel, dtype=float)) >= float(stride_travel_m)) & (np.abs(dz) < REVERSAL_MIN_DZ_M)


def closed_loop_strides(dz: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
                        unrested: np.ndarray | None = None, travel: np.ndarray | None = None, *,
                        stride_travel_m: float | None = None) -> np.ndarray:
    """Decision L611: (B,) bool, the strides whose neighbourhood (:data:`NEIGHBOURS` strides of their chain either
    side) holds :data:`MIN_REVERSALS` or more height reversals: two consecutive strides of one chain (the next starting
    within :data:`CHAIN_PAUSE_S` of the previous's end) whose raw height changes ``dz`` (m) have opposite signs, each at
    least :data:`REVERSAL_MIN_DZ_M` and (third rule) at least :data:`STEEP` of its horizontal ``travel`` (m), and
    (decision L621) each ``unrested`` or travelling less than :data:`TRAVEL_MAX_M`; or
    (second rule) :data:`MIN_UNRESTED` or more ``unrested`` strides
    (:func:`unrested_strides`). Decision L640: and a stride chained to one of those that travels under
    :data:`TRAVEL_MAX_M` or whose own ``dz`` passes the reversal test (a mount's or a dismount's pedal stroke).
    Decision L799: with ``stride_travel_m`` (m; None: L611 as before) a level stride travelling that far
    (:func:`travelling_strides`) is not unrested for the second rule, makes no reversal and is never marked (a running
    stance too short for the foot to rest at the stride's ends)."""
    dz = np.asarray(dz, dtype=float)
    start_s, end_s = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    n = len(dz)
    if n < 3:
        return np.zeros(n, dtype=bool)
    chained = start_s[1:] - end_s[:-1] <= CHAIN_PAUSE_S  # (B-1,) pair i, i+1 in one chain
    going = travelling_strides(dz, travel, stride_travel_m)  # decision L799: a level stride that travels
    still = np.zeros(n, dtype=bool) if unrested is None else np.asarray(unrested, dtype=bool) & ~going
    big = np.abs(dz) >= REVERSAL_MIN_DZ_M
    if travel is not None:
        travel = np.abs(np.asarray(travel, dtype=float))
        big &= np.abs(dz) >= STEEP * travel
        big &= still | (travel < TRAVEL_MAX_M)  # decision L621: a stride that travels and rests is walking (a stile)
    rev = chained & big[:-1] & big[1:] & (np.sign(dz[:-1]) != np.sign(dz[1:]))  # pair i, i+1 reverses
    out = np.zeros(n, dtype=bool)
    for i in range(n):
        lo, hi = i, i  # the stride's neighbourhood within its chain: pairs lo..hi-1
        while lo > 0 and i - lo < NEIGHBOURS and chained[lo - 1]:
            lo -= 1
        while hi < n - 1 and hi - i < NEIGHBOURS and chained[hi]:
            hi += 1
        out[i] = int(rev[lo:hi].sum()) >= MIN_REVERSALS or int(still[lo:hi + 1].sum()) >= MIN_UNRESTED
    # decision L640 (second rule): a stride chained to a pedalling stride that travels under L621's TRAVEL_MAX_M or
    # whose own height passes the reversal test (the mount's and the dismount's strokes: one end rests, one pedalling
    # neighbour) is pedalling too; one pass, no spreading
    edge = np.zeros(n, dtype=bool)
    edge[1:] |= chained & out[:-1]
    edge[:-1] |= chained & out[1:]
    short = big if travel is None else big | (travel < TRAVEL_MAX_M)
    return (out | (edge & short)) & ~going


def seated_strides(start_s: np.ndarray, end_s: np.ndarray, transfers) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Decision L612: (B,) bool, the strides lying wholly inside a seated span of the chair ``transfers`` (rows with
    ``kind``, ``start_s``, ``end_s``, in time order: W182's), and the spans: from a stand-to-sit's end to the next
    transfer's start when that is a sit-to-stand."""
    start_s, end_s = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    rows = sorted(transfers or [], key=lambda r: float(r["start_s"]))
    spans = [(float(a["end_s"]), float(b["start_s"])) for a, b in zip(rows[:-1], rows[1:], strict=True)
             if a.get("kind") == "stand-to-sit" and b.get("kind") == "sit-to-stand" and b["start_s"] > a["end_s"]]
    out = np.zeros(len(start_s), dtype=bool)
    for a, b in spans:
        out |= (start_s >= a) & (end_s <= b)
    return out, spans


def add_span(spans: list[list], start_s: float, end_s: float) -> None:
    """One more marked stride into ``spans`` (``[start s, end s, strides]`` lists, in time order): it extends the last
    span when it starts under :data:`MERGE_SPANS_S` after that span's end."""
    if spans and float(start_s) - spans[-1][1] < MERGE_SPANS_S:
        spans[-1][1], spans[-1][2] = float(end_s), spans[-1][2] + 1
    else:
        spans.append([float(start_s), float(end_s), 1])


def ride_strides(start_s: np.ndarray, end_s: np.ndarray, cap_s: float) -> np.ndarray:
    """Decision L639: (B,) bool, the strides longer than :data:`RIDE_STRIDE_CAPS` x ``cap_s`` (s, the foot's stride
    cap, L605): no walking stride lasts that long without a rest of the foot (a bike ride, a foot never at rest)."""
    return np.asarray(end_s, dtype=float) - np.asarray(start_s, dtype=float) > RIDE_STRIDE_CAPS * float(cap_s)


def spans_of(mask: np.ndarray, start_s: np.ndarray, end_s: np.ndarray) -> list[tuple[float, float, int]]:
    """The marked strides' spans (start s, end s, strides), merged when under :data:`MERGE_SPANS_S` apart."""
    out: list[list] = []
    for i in np.flatnonzero(mask):
        add_span(out, start_s[i], end_s[i])
    return [(a, b, k) for a, b, k in out]


#: decision L611: what the track does with the pedalling strides, for the line
TRACK_REMOVED = "removed from the track (no row, 0 m)"


def loop_part(spans) -> str:
    """Decision L611's part of the warning line: the closed-loop strides' ``spans`` ((start s, end s, strides))."""
    where = ", ".join(f"{a:.2f}-{b:.2f} s ({k})" for a, b, k in spans)
    return (f"{sum(k for _, _, k in spans)} stride(s) at {where} went round a closed loop without rests or travel "
            "(cycling? decision L611)")


#: decisions L611 / L612: how the track's warning line starts (the live tracker's too, decision E280)
REMOVED = f"not walking, {TRACK_REMOVED}: "


def pedal_line(loop: np.ndarray, seated: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
               seats: list[tuple[float, float]] | None = None, ride: np.ndarray | None = None,
               cap_s: float | None = None, removed: str = TRACK_REMOVED) -> str | None:
    """Decisions L611 / L612 / L639: the one warning line naming the removed strides' spans and why, or None
    (``ride``: L639's strides, ``cap_s`` the stride cap they were judged on; not counted as pedalling or seated);
    ``removed`` says what was done with them (decision L625: ``pdrlearn steps`` leaves them out of its count or counts
    them)."""
    parts = []
    if ride is not None and ride.any():
        where = ", ".join(f"{a:.2f}-{b:.2f} s" for a, b in zip(start_s[ride], end_s[ride], strict=True))
        parts.append(f"{int(ride.sum())} stride(s) at {where} lasted longer than {RIDE_STRIDE_CAPS * cap_s:g} s "
                     f"({RIDE_STRIDE_CAPS:g} of the foot's {cap_s:g} s stride cap) without a rest of the foot "
                     "(a ride? decision L639)")
        loop, seated = loop & ~ride, seated & ~ride
    if loop.any():
        parts.append(loop_part(spans_of(loop, start_s, end_s)))
    only_seated = seated & ~loop
    if only_seated.any():
        where = ", ".join(f"{a:.2f}-{b:.2f} s ({k})" for a, b, k in spans_of(only_seated, start_s, end_s))
        seat = "; ".join(f"stand-to-sit at {a:.2f} s, sit-to-stand at {b:.2f} s" for a, b in (seats or [])
                         if (only_seated & (start_s >= a) & (end_s <= b)).any())
        parts.append(f"{int(only_seated.sum())} stride(s) at {where} lie in a span the lower-back unit calls seated "
                     f"({seat}; cycling or a foot moving while seated? decision L612)")
    if not parts:
        return None
    return f"not walking, {removed}: " + "; ".join(parts)


#: decision E280: the live rest reading (L621's ``g_rest``) is the standard gravity until this many still foot samples
#: were read (B201's minimum of rest samples, ``track.foot_rest.MIN_REST_SAMPLES``)
LIVE_REST_MIN_SAMPLES = 20
#: decision E280: the live rest reading is the median of the last this many strides' readings (bounded state)
LIVE_REST_STRIDES = 200


def unjudged_row(t0: float, t1: float) -> tuple:
    """Decision E280: a :class:`LiveLoops` row in its chain that is never judged (no dz, no missing rest)."""
    return (float(t0), float(t1), 0.0, False, 0.0, False)


class LiveRest:
    """Decision E280: L621's ``g_rest`` (the foot accelerometer's own rest reading) and L611's second rule, causally
    and numpy only, for a live tracker: each stride adds the median |acc| of its foot samples that the shared still
    test (:func:`pdrlearn.kernels.waist.still_from_magnitudes`, magnitudes only: a mis-scaled unit's rest is still)
    marks still; the reading is the median of the last :data:`LIVE_REST_STRIDES` strides' (the standard gravity until
    :data:`LIVE_REST_MIN_SAMPLES` still samples). ``track --streaming`` reads the whole recording's foot-flats instead
    (``track.foot_rest.foot_rest_gravity``, which the runtime cannot import)."""

    def __init__(self) -> None:
        self.readings: list[float] = []
        self.n_still = 0

    @property
    def g_rest(self) -> float:
        return float(np.median(self.readings)) if self.n_still >= LIVE_REST_MIN_SAMPLES else STANDARD_GRAVITY

    def unrested(self, stream, t0: float, t1: float) -> bool:
        """The stride ``[t0, t1]`` (s) adds its reading, then L611's second rule (:func:`unrested_strides`) on the
        foot accelerometer ``stream("fAccelerometer")`` with the reading so far. False without the stream."""
        from pdrlearn.kernels.waist import still_from_magnitudes

        try:
            t, acc = stream("fAccelerometer")
            tg, gyr = stream("fGyroscope")
        except KeyError:
            return False
        t = np.asarray(t, dtype=float)
        a, b = np.searchsorted(t, t0 - REST_WINDOW_S, side="left"), np.searchsorted(t, t1 + REST_WINDOW_S, side="right")
        if b - a >= 3 and len(tg) >= 2:
            ts = t[a:b]
            am = np.linalg.norm(np.asarray(acc, dtype=float)[a:b, :3], axis=1)
            g = np.asarray(gyr, dtype=float)[:, :3]
            gm = np.linalg.norm(np.column_stack([np.interp(ts, tg, g[:, k]) for k in range(3)]), axis=1)
            period = float(np.median(np.diff(ts)))
            still = still_from_magnitudes(am, gm, 1.0 / period) if period > 0 else np.zeros(len(ts), dtype=bool)
            if still.any():
                self.readings = (self.readings + [float(np.median(am[still]))])[-LIVE_REST_STRIDES:]
                self.n_still += int(still.sum())
        return bool(unrested_strides(t, acc, np.array([t0]), np.array([t1]), self.g_rest)[0])


#: decisions E280 / L640: how many strides of its chain either side a stride's verdict reads: L611's
#: :data:`NEIGHBOURS`, and one more for L640's second rule (a stride's verdict reads its neighbours' verdicts)
REACH = NEIGHBOURS + 1


class LiveLoops:
    """Decision E280: L611's verdict (:func:`closed_loop_strides`, the same call) for strides that arrive one at a
    time, as a live tracker measures them. A stride's verdict reads up to :data:`REACH` strides of its chain
    after it, so :meth:`add` holds a stride until it is final and releases the strides in order, each with its
    verdict: final when :data:`REACH` later strides are known, or the next one is known and starts over
    :data:`CHAIN_PAUSE_S` after it (its chain ends), or when no stride to come can make it pedalling: the kernel says
    so with :data:`REACH` worst-case strides appended (chained, reversing, unrested, no travel: no real stride
    adds more reversals or unrested strides), which releases a walking stride at once (no look-ahead, no latency).
    :meth:`flush` (the end of a recording) releases the rest, judged on what is known, as ``track --streaming`` judges
    its last strides. ``history`` keeps the last :data:`REACH` released rows (their verdicts' neighbours).

    A row is ``(start s, end s, raw dz m, unrested, raw horizontal travel m, judged)``; an unjudged row (a stride
    across a foot gap or bridged samples, a posture) is in its chain but has dz 0, no missing rest and is never
    pedalling (the lead's amendment of L611, as ``track --streaming``'s ``unjudged``).

    ``judge=False`` (decision E304, ``pdrlearn run --no-cycling``: an activity without bicycles) judges nothing: every
    row is released at once as walking (no hold, as ``track --no-cycling`` removes no stride)."""

    def __init__(self, judge: bool = True) -> None:
        self.judge = bool(judge)
        self.history: list[tuple] = []
        self.held: list[tuple[tuple, object]] = []  # (row, payload)
        self.seen = 0

    def add(self, row: tuple, payload) -> list[tuple[object, bool]]:
        """Hold ``row`` (with the caller's ``payload``); returns the ``(payload, pedalling)`` now final, in order."""
        self.seen += 1
        self.held.append((tuple(row), payload))
        return self._release(final=False)

    def flush(self) -> list[tuple[object, bool]]:
        """Every held row's ``(payload, pedalling)``, judged on the rows known (the recording's end)."""
        return self._release(final=True)

    def expire(self, now: float, quiet_s: float) -> list[tuple[object, bool]]:
        """Every held row's ``(payload, pedalling)`` when the data reach ``now`` (s) over ``quiet_s`` after the last
        held row's end with no stride after it: none to come can join its chain (the caller knows how long a stride
        takes to be detected); else none."""
        if self.held and now - self.held[-1][0][1] > quiet_s:
            return self._release(final=True)
        return []

    def _release(self, final: bool) -> list[tuple[object, bool]]:
        out = []
        while self.held:
            rows = self.history + [r for r, _ in self.held]
            i = len(self.history)  # the first held row
            after = len(rows) - 1 - i
            ended = after >= 1 and rows[i + 1][0] - rows[i][1] > CHAIN_PAUSE_S
            if not self.judge:  # decision E304: no pedalling check, no hold
                pedal = False
            elif final or ended or after >= REACH:
                pedal = self._verdict(rows, i)
            elif not self._verdict(rows + self._worst(rows[-1]), i):
                pedal = False
            else:
                break
            row, payload = self.held.pop(0)
            self.history = (self.history + [row])[-REACH:]
            out.append((payload, pedal))
        return out

    @staticmethod
    def _worst(last: tuple) -> list[tuple]:
        """:data:`REACH` strides chained after ``last`` that reverse each other (and ``last``), unrested, not
        travelling: no real stride to come adds more to a verdict."""
        sign = -1.0 if last[2] > 0 else 1.0
        t = last[1]
        return [(t, t, sign * (-1.0) ** k, True, 0.0, True) for k in range(REACH)]

    @staticmethod
    def _verdict(rows: list[tuple], i: int) -> bool:
        lo, hi = max(0, i - REACH), min(len(rows), i + REACH + 1)  # the verdict reads no row outside
        w = rows[lo:hi]
        judged = np.array([r[5] for r in w], dtype=bool)
        col = [np.array([r[k] for r in w], dtype=float) for k in range(5)]
        loop = closed_loop_strides(np.where(judged, col[2], 0.0), col[0], col[1],
                                   (col[3] > 0) & judged, col[4])  # decision L621: the travel
        return bool(loop[i - lo] and judged[i - lo])
