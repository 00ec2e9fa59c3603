"""The streaming tracker's input checks on the values (numpy only): units and plausibility on the first seconds of
each stream (decision B119, offline's :mod:`pdrlearn.kernels.units` checks) and frozen sensors (decision B120).

``pdrlearn run`` / ``track`` refuse a session file whose accelerometer reads ~1 g instead of ~9.81 m/s^2 at rest,
or whose gyroscope turns faster than a 2000 deg/s sensor in rad/s; :class:`pdrlearn.runtime.Tracker` pushes did
not (a foot accelerometer in g: 9.15 m for 89.75 m, no word). :class:`UnitGuard` holds the first
:data:`GUARD_S` seconds of each accelerometer and gyroscope stream the tracker uses and runs the same checks on
them, once per stream, before the push that completes them is taken (a refused push changes nothing, E29);
the foot and waist gyroscopes together are checked for B91's swapped units. :class:`FrozenWatch` follows each
3-axis stream for runs of bit-identical samples (:data:`pdrlearn.kernels.units.FROZEN_S`); :class:`FrozenFootWatch`
judges B203's frozen foot IMU beside stepping force sensors on blocks of stream time (decision B213).
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.frozen_foot import LIVE_BLOCK_S, force_reference, frozen_foot_evidence, frozen_foot_reason
from pdrlearn.kernels.handedness import MIN_SEGMENTS, mirror_log_ratios, mirrored, mirrored_pair_line
from pdrlearn.kernels.units import (
    FROZEN_PARTNER,
    FROZEN_S,
    GYRO_RAD_S_MAX,
    WALKING_ACC_STD,
    check_units,
    frozen_message,
    gyro_in_deg,
    identical_runs,
    moving_norm,
    moving_samples,
    swapped_units,
    swing_rate,
)
from pdrlearn.runtime.clip_watch import take_before

#: decision B119: seconds of a stream the unit checks judge (5 s: a few strides of foot-flats for B78's quietest
#: windows, B91's swing needs walking; the steps of these seconds are emitted before the check, so short)
GUARD_S = 5.0
#: B91's movement test waits for the accelerometer to reach this close (s) to the end of its gyroscope's window:
#: a foot whose accelerometer arrives later than its gyroscope (another Bluetooth link) is not taken as moving and
#: its still gyroscope's ~0 rad/s does not make the waist's first fast turn look like swapped units (review 2)
ACC_COVER_S = 0.25
#: the sensors whose units are checked (the streamed tracker's IMUs; the kind check_units judges each by)
GUARDED = {"fAccelerometer": "accelerometer", "fGyroscope": "gyroscope", "wAccelerometer": "accelerometer",
           "wGyroscope": "gyroscope"}
#: decision B129: the foot strides the live mirrored-pair test (D11) decides on, once: twice D11's least
#: :data:`~pdrlearn.kernels.handedness.MIN_SEGMENTS` (a median over 8 strides, ~10 s of walking, before the
#: track has gone far wrong; offline's verdicts rest on 19-76 strides of the first 300 s)
LIVE_STRIDES = 2 * MIN_SEGMENTS
#: the 3-axis streams watched for frozen samples (decision B120)
WATCHED = ("fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope", "wMagneticField")


class _Kind:
    """What :func:`pdrlearn.kernels.units.check_units` reads of a sensor spec (``pdrlearn.io.sensors`` imports
    pandas; the runtime numpy only)."""

    __slots__ = ("kind", "name")

    def __init__(self, name: str, kind: str):
        self.name, self.kind = name, kind


def as_arrays(tv) -> tuple[np.ndarray, np.ndarray]:
    """A pushed ``(t, values)`` (checked by the tracker) as float64 ``(n,)`` and ``(n, k)`` arrays."""
    t = np.asarray(tv[0], dtype=np.float64).reshape(-1)
    v = np.asarray(tv[1], dtype=np.float64)
    return t, v.reshape(len(t), -1)


class UnitGuard:
    """Decision B119: the first :data:`GUARD_S` seconds of each accelerometer, checked once; each gyroscope's
    windows of :data:`GUARD_S` seconds for as long as it streams (a rate beyond a 2000 deg/s gyroscope in rad/s
    can not be rad/s: a waist in deg/s shows it at its first turn, not in a straight line); B91's swapped units on
    the first gyroscope window in which its unit's accelerometer shows movement (B37's |acc| sd over
    :data:`~pdrlearn.kernels.units.WALKING_ACC_STD`; a window its accelerometer does not cover yet,
    :data:`ACC_COVER_S`, is left to a later one)."""

    def __init__(self, used, who: str = "Tracker"):
        self.who = who  # the class named in the lines (the foot Tracker, a WaistTracker)
        self.held: dict[str, list] = {n: [] for n in GUARDED if n in set(used)}
        self.judged: set[str] = set()  # accelerometers checked; gyroscopes seen in motion (B91 judged)
        self.rates: dict[str, float] = {}  # B91's swing rate of each gyroscope judged in motion (rad/s)
        self._wanted = self._still_wanted()

    def wanted(self) -> list[str]:
        """The streams whose pushed samples :meth:`check` still reads: every gyroscope (B119 judges each of its
        windows for as long as it streams); an accelerometer until it is checked and its gyroscope has been seen in
        motion (B91's movement test reads it). Worked out when a judgement changes it, not per push (E71)."""
        return self._wanted

    def _still_wanted(self) -> list[str]:
        return [n for n in self.held if GUARDED[n] == "gyroscope" or n not in self.judged
                or (FROZEN_PARTNER[n] in self.held and FROZEN_PARTNER[n] not in self.judged)]

    @staticmethod
    def _joined(chunks, t0: float = -math.inf, t1: float = math.inf):
        if not chunks:
            return None
        t = np.concatenate([c[0] for c in chunks])
        v = np.concatenate([c[1] for c in chunks])
        keep = (t >= t0) & (t <= t1)
        return t[keep], v[keep]

    def check(self, arrays: dict[str, tuple[np.ndarray, np.ndarray]]) -> tuple[dict, dict]:
        """Raise a one-line :class:`DataError` when a stream whose held samples plus ``arrays[name]`` (this push's)
        complete a window of :data:`GUARD_S` fails the checks; returns those windows and the swing rates of the
        gyroscopes among them seen in motion for the first time (for :meth:`take`). Changes nothing."""
        ready = {}
        for name, chunks in self.held.items():
            tv = arrays.get(name)
            if (name in self.judged and GUARDED[name] == "accelerometer") or tv is None or not len(tv[0]):
                continue
            t0 = float((chunks[0] if chunks else tv)[0][0])
            if float(tv[0][-1]) - t0 >= GUARD_S:
                ready[name] = self._joined([*chunks, tv], t0, t0 + GUARD_S)
            elif GUARDED[name] == "gyroscope" and float(np.max(np.abs(tv[1]))) > GYRO_RAD_S_MAX:
                self._early(name, *self._joined([*chunks, tv]))  # decision E298: deg/s at its first swing
        moving = set()
        for name, (t, _) in ready.items():
            if GUARDED[name] == "gyroscope" and name not in self.judged:
                acc = FROZEN_PARTNER[name]
                chunks = [*self.held.get(acc, ()), arrays[acc]] if acc in arrays else self.held.get(acc, ())
                if acc in self.held and (not chunks or float(chunks[-1][0][-1]) < float(t[-1]) - ACC_COVER_S):
                    continue  # its accelerometer has not arrived for this window yet (a later window judges B91)
                a = self._joined(chunks, float(t[0]), float(t[-1]))
                if a is None or len(a[0]) < 3 or float(np.std(np.linalg.norm(a[1], axis=1))) > WALKING_ACC_STD:
                    moving.add(name)
        return ready, self._judge(ready, moving)

    def finish(self) -> None:
        """The end of a stream (``flush``): the windows begun, checked on what they have (at least 10 samples, as
        offline's checks; no B91 without movement)."""
        ready = {n: self._joined(c) for n, c in self.held.items() if sum(len(x[0]) for x in c) >= 10
                 and not (n in self.judged and GUARDED[n] == "accelerometer")}
        self._judge(ready, set())
        self.held.clear()
        self._wanted = []

    def units_first(self, name: str, tv) -> None:
        """Decision B435: before a push's value beyond any sensor's range is refused, B119's unit checks on the
        window the guard holds of ``name`` with this push's samples ``tv`` (however short), so that a stream in
        another unit (counts read as m/s^2: 2048 at rest; deg/s as rad/s) keeps its wrong-unit line, as B425 runs
        the unit checks before its range line; a few corrupt samples move neither medians nor the checks. Nothing
        for a stream the guard no longer reads (an accelerometer judged) or does not guard. Changes nothing."""
        if name not in self._wanted:
            return
        t, v = self._joined([*self.held[name], tv])
        with np.errstate(over="ignore", invalid="ignore"):  # the corrupt values' squares may overflow (B425)
            self._check(name, t, v)
            if GUARDED[name] == "gyroscope":
                self._early(name, t, v)  # decision E298

    def _early(self, name: str, t: np.ndarray, v: np.ndarray) -> None:
        """Decision E298: a gyroscope's window so far refused as deg/s before it is whole (:func:`gyro_in_deg`)."""
        why = gyro_in_deg(v)
        if why:
            raise DataError(f"{name} (its samples of {float(t[0]):.1f}-{float(t[-1]):.1f} s pushed to the {self.who}, "
                            f"decision B119): {why}")

    def _check(self, name: str, t: np.ndarray, v: np.ndarray) -> None:
        """B119's unit checks of one window of ``name`` (one line naming the stream and the seconds judged)."""
        span = float(t[-1] - t[0])
        what = (f"its first {span:.1f} s" if name not in self.judged
                else f"its samples of {float(t[0]):.1f}-{float(t[-1]):.1f} s")
        check_units(_Kind(name, GUARDED[name]), v, f"{name} ({what} pushed to the {self.who}, decision B119)",
                    declare="", t=t)

    def _judge(self, ready: dict, moving: set) -> dict[str, float]:
        """The checks of the ``ready`` windows; returns B91's swing rate of each gyroscope in ``moving``."""
        for name, (t, v) in ready.items():
            self._check(name, t, v)
        new = {n: swing_rate(ready[n][1]) for n in moving}
        rates = {**self.rates, **new}
        f99, w99 = rates.get("fGyroscope", math.nan), rates.get("wGyroscope", math.nan)
        if moving and swapped_units(f99, w99):
            raise DataError(
                f"fGyroscope, wGyroscope: the foot and waist streams look swapped: the foot unit turns at "
                f"{np.degrees(f99):.0f} deg/s (99th percentile of |gyro| over its first seconds) while the waist unit "
                f"swings at {np.degrees(w99):.0f} deg/s, as a foot does (decisions B91, B119); push the foot unit's "
                "samples as fAccelerometer / fGyroscope and the waist unit's as wAccelerometer / wGyroscope (check "
                "which Bluetooth id is which unit)")
        return new

    def take(self, arrays: dict, judged: tuple[dict, dict]) -> None:
        """Hold the pushed samples; an accelerometer checked is dropped, a gyroscope's next window begun; keep an
        accelerometer's samples while its gyroscope has not been seen in motion (the movement test reads them)."""
        ready, rates = judged
        for name, tv in arrays.items():
            if name in self.held and len(tv[0]):
                self.held[name].append(tv)
        self.rates.update(rates)  # B91's rates of the gyroscopes seen in motion, worked out once by check
        judged_now = [n for n in ready if (GUARDED[n] == "accelerometer" or n in rates) and n not in self.judged]
        if judged_now:
            self.judged.update(judged_now)
            self._wanted = self._still_wanted()
        for name, (t, _) in ready.items():
            if GUARDED[name] == "gyroscope":
                self.held[name] = [c for c in self.held[name] if c[0][-1] > t[-1]]
        for name, chunks in self.held.items():  # an accelerometer's samples: for its own window or its gyroscope's
            if GUARDED[name] != "accelerometer":
                continue
            gyro = FROZEN_PARTNER[name]
            users = [n for n in (name, gyro) if n in self.held and n not in self.judged]
            start = min([float(self.held[n][0][0][0]) for n in users if self.held[n]], default=math.inf)
            self.held[name] = [c for c in chunks if c[0][-1] >= start] if users else []


_NONE = np.zeros(0)


class FrozenWatch:
    """Decision B120: one warning per run of bit-identical consecutive samples of a 3-axis stream lasting
    :data:`~pdrlearn.kernels.units.FROZEN_S` or more while the unit's other sensor shows movement (:meth:`note`;
    a quantised sensor at rest repeats too), given by the push in which both hold (the streamed form of
    ``pdrlearn.io.plasys.warn_frozen``)."""

    def __init__(self):
        #: stream -> (first time of its current run of identical samples, samples in it, the sample, warned)
        self.run: dict[str, tuple[float, int, list, bool]] = {}
        #: stream -> (its last moving sample before its latest chunk, the latest chunk's moving times): the unit's
        #: movement evidence for its other sensor (B120 amended)
        self.moved: dict[str, tuple[float, np.ndarray]] = {}

    def note(self, name: str, t: np.ndarray, v: np.ndarray) -> None:
        """The movement evidence of a pushed chunk of ``name`` (call for every watched stream of a push before
        :meth:`feed`)."""
        last, now = self.moved.get(name, (-math.inf, _NONE))
        self.moved[name] = (max(last, float(now[-1])) if len(now) else last, t[moving_samples(name, v)])

    def note1(self, name: str, t: float, vals: list) -> None:
        """:meth:`note` of one sample on Python floats (decision E17)."""
        last, now = self.moved.get(name, (-math.inf, _NONE))
        if len(now):
            last = max(last, float(now[-1]))
        self.moved[name] = (last, np.array([t]) if moving_norm(name, math.hypot(*vals)) else _NONE)

    def _moves(self, name: str, first: float, last: float) -> bool:
        """Whether the unit of ``name`` moved between ``first`` and ``last`` by its other sensor (True when that
        sensor is not streamed: the run alone decides, as before)."""
        m = self.moved.get(FROZEN_PARTNER.get(name, ""))
        if m is None:
            return True
        return m[0] >= first or bool(np.any((m[1] >= first) & (m[1] <= last)))

    def feed1(self, name: str, t: float, vals: list) -> str | None:
        """:meth:`feed` of one sample on Python floats (the tracker's one-sample path, decision E17)."""
        r = self.run.get(name)
        if r is None or r[2] != vals:
            self.run[name] = (t, 1, vals, False)
            return None
        first, n, warned = r[0], r[1] + 1, r[3]
        msg = None
        if not warned and t - first >= FROZEN_S and self._moves(name, first, t):
            msg, warned = frozen_message(name, first, t, n, vals, ongoing=True), True
        self.run[name] = (first, n, vals, warned)
        return msg

    def feed(self, name: str, t: np.ndarray, v: np.ndarray) -> str | None:
        """The warning line for ``name`` when one of its runs of identical samples reaches the limit in this push
        (the first such run; each run is warned about once). The runs are those of
        :func:`~pdrlearn.kernels.units.identical_runs` (offline's splitting), the first one joined to the run the
        previous push ended in when its first sample repeats that run's (decision E71: no loop over the runs)."""
        if not len(t):
            return None
        prev = self.run.get(name)
        starts, ends = identical_runs(v)
        first, count, last = t[starts], ends - starts + 1, t[ends]
        warned = np.zeros(len(starts), dtype=bool)
        if prev is not None and prev[2] == v[0].tolist():  # the run held before this push goes on
            first = first.copy()
            first[0], count[0], warned[0] = prev[0], count[0] + prev[1], prev[3]
        msg, hit = None, -1
        for k in np.flatnonzero(~warned & (last - first >= FROZEN_S)).tolist():  # runs of 2 s or more: few
            if self._moves(name, float(first[k]), float(last[k])):
                hit = k
                msg = frozen_message(name, float(first[k]), float(last[k]), int(count[k]), v[ends[k]],
                                     ongoing=k == len(starts) - 1)
                break
        k = len(starts) - 1
        self.run[name] = (float(first[k]), int(count[k]), v[-1].tolist(), bool(warned[k]) or hit == k)
        return msg

    def push(self, arrays: dict, fast: dict | None = None) -> list[str]:
        """One push of the watched streams (:data:`WATCHED`): ``arrays`` name -> ``(t (n,), values (n, 3))``, and
        ``fast`` name -> ``(t, values)`` of one sample on Python floats (the tracker's one-sample path, decision
        E17); a stream in neither is not in this push. The movement evidence of every stream first (a run is frozen
        only while the unit's other sensor moves, B120), then the runs; returns the warning lines."""
        fast = fast or {}
        names = [n for n in WATCHED if n in fast or n in arrays]
        for name in names:
            f = fast.get(name)
            if f is not None:
                self.note1(name, *f)
            else:
                self.note(name, *arrays[name])
        out = []
        for name in names:
            f = fast.get(name)
            msg = self.feed1(name, *f) if f is not None else self.feed(name, *arrays[name])
            if msg:
                out.append(msg)
        return out


#: decision B213: the streams :class:`FrozenFootWatch` reads (the foot IMU and its force sensors)
FOOT_WATCHED = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB")
_FORCES = ("fForceA", "fForceB")


class FrozenFootWatch:
    """Decision B213: B203's test (:func:`~pdrlearn.kernels.frozen_foot.frozen_foot_evidence`, offline's) on
    consecutive blocks of :data:`~pdrlearn.kernels.frozen_foot.LIVE_BLOCK_S` of stream time from the first foot
    accelerometer sample: one warning, for the first block in which the force sensors load 3 times or more while
    the foot IMU does not move (from the start, or after it stopped moving mid-walk). A block is judged once every
    watched stream pushed so far has a sample at or after its end (or one stream is a whole block past it: a stalled
    stream does not hold the samples), so the verdict does not depend on how the samples were cut into pushes; its
    force reference is the largest 95th percentile of the blocks so far (an unloaded foot's noise is no load once
    the foot has stood). Memory: the samples of the open blocks only; none after the warning."""

    def __init__(self, block_s: float = LIVE_BLOCK_S):
        self.block_s = float(block_s)
        self.start: float | None = None  # the first foot accelerometer time (block 0 starts there)
        self.k = 0  # the open block
        self.items: dict[str, list] = {n: [] for n in FOOT_WATCHED}  # (t, values) arrays or one (t, list) sample
        self.last: dict[str, float] = {}  # each stream's latest time
        self.refs: dict[str, float] = {}  # decision B213: each force sensor's largest block reference so far
        self.done = False

    def push(self, arrays: dict, fast: dict | None = None) -> str | None:
        """One push (``arrays`` name -> ``(t, values)``, ``fast`` name -> one ``(t, values)`` sample on Python
        floats, as :meth:`FrozenWatch.push`); the warning line when a block closed by it is frozen."""
        if self.done:
            return None
        fast = fast or {}
        newest = -math.inf
        for name in FOOT_WATCHED:
            f = fast.get(name)
            if f is not None:
                self.items[name].append(f)
                self.last[name] = f[0]
                newest = max(newest, f[0])
            elif name in arrays:
                t, v = arrays[name]
                if len(t):
                    self.items[name].append((t, v))
                    self.last[name] = float(t[-1])
                    newest = max(newest, float(t[-1]))
        if self.start is None:
            first = self.items["fAccelerometer"][:1]
            if not first:
                return None
            t = first[0][0]
            self.start = float(t if isinstance(t, float) else t[0])
        if newest < self.start + (self.k + 1) * self.block_s:  # the common case: no block ends in this push
            return None
        return self._close(final=False)

    def flush(self) -> str | None:
        """The end of the stream: the open block judged on what it holds."""
        return None if self.done or self.start is None else self._close(final=True)

    def _close(self, *, final: bool) -> str | None:
        while True:
            begin = self.start + self.k * self.block_s
            end = begin + self.block_s
            seen = [self.last[n] for n in FOOT_WATCHED if n in self.last]
            if not final and not (min(seen) >= end or max(seen) >= end + self.block_s):
                return None
            block = {n: self._take(n, end) for n in FOOT_WATCHED}
            self.k += 1
            msg = self._judge(block, begin, min(end, max(seen)))
            if msg is not None:
                self.done, self.items = True, {n: [] for n in FOOT_WATCHED}
                return msg
            if final and not any(self.items.values()):
                return None

    def _take(self, name: str, end: float) -> tuple[np.ndarray, np.ndarray]:
        """The samples of ``name`` before ``end`` (removed from the watch) as ``(t, values)`` arrays."""
        self.items[name], t, v = take_before(self.items[name], end)
        return t, v

    def _judge(self, block: dict, begin: float, end: float) -> str | None:
        """B203's test on the samples of the block from ``begin`` to ``end`` s; the warning line or None."""
        (ta, acc), (_, gyr) = block["fAccelerometer"], block["fGyroscope"]
        names = [n for n in _FORCES if len(block[n][0]) >= 2]
        if len(ta) < 4 or not names:
            return None
        forces = [np.interp(ta, block[n][0], block[n][1][:, 0]) for n in names]
        for n, f in zip(names, forces, strict=True):
            self.refs[n] = max(self.refs.get(n, -math.inf), force_reference(f))
        found = frozen_foot_evidence(acc, gyr, forces, [self.refs[n] for n in names])
        if found is None:
            return None
        return (f"the foot IMU did not move from {begin:.1f} to {end:.1f} s: "
                + frozen_foot_reason(", ".join(names), *found, imu="fAccelerometer, fGyroscope")
                + "; its strides from then on move 0 m or are not found: check the IMU and its link (decision B213)")


class MirrorWatch:
    """Decision B129: D11's mirrored-pair test (:mod:`pdrlearn.kernels.handedness`, the one ``pdrlearn info`` and
    ``track`` run) on the first :data:`LIVE_STRIDES` foot strides of a stream, decided once: the warning line when
    the foot gyroscope's sign is reversed against its accelerometer (or the data are mirrored in one axis)."""

    def __init__(self, who: str = "Tracker"):
        self.who = who
        self.ratios: list[float] = []  # the per-stride log ratios so far (> 0: right-handed)

    def stride(self, t_acc: np.ndarray, acc: np.ndarray, t_gyr: np.ndarray, gyr: np.ndarray) -> str | None:
        """One rest-to-rest stride's foot samples (the gyroscope interpolated on the accelerometer's clock, as
        offline); the warning when this stride completes the :data:`LIVE_STRIDES` and their median says mirrored."""
        if len(t_acc) < 3 or len(t_gyr) < 2:
            return None
        g = np.column_stack([np.interp(t_acc, t_gyr, gyr[:, j]) for j in range(3)])
        dt = float(np.median(np.diff(t_acc)))
        self.ratios.append(float(mirror_log_ratios(acc, g, dt, np.array([0]), np.array([len(t_acc) - 1]))[0]))
        if len(self.ratios) != LIVE_STRIDES:
            return None
        med = float(np.median(self.ratios))
        if not mirrored(med, len(self.ratios)):
            return None
        return (mirrored_pair_line("foot", "fAccelerometer", "fGyroscope", med, len(self.ratios),
                                   "the end-of-stride velocity error of the ZUPT integration",
                                   of=f" strides pushed to the {self.who}", decision="decisions D11, B129")
                + "; the gyroscope's sign looks reversed against the accelerometer's (another axis convention, a "
                "mirrored mount or export): negate the gyroscope's three values before pushing (or, for data "
                "mirrored in one axis, that axis in both sensors); until then the track turns and climbs wrong")
