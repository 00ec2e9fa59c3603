"""What a live Bluetooth link does to a two-unit Tracker's timestamps (session 40, trial T4 findings 1-3).

Two pods that count from power-on start seconds apart (decision E223: named, not blamed on a stopped sensor); a
waist stream that pauses and resumes on every packet repeats E115's lines (E224: counted, a line at most every
:data:`REPEAT_WARN_S` of stream time); a packet sent twice, a late one and a pod whose clock restarted at a reconnect
are refused with what they most likely are (E225, E227). Plain Python and numpy: the lean runtime's import set.
"""

from __future__ import annotations

import math

from pdrlearn.errors import ClockWentBack, DataError
from pdrlearn.kernels.counter_wrap import live_wrap
from pdrlearn.kernels.order import reorder_hint

#: decision E224 (ours, not from a document): a repeated E115 pause / resume line is written at most once per this many
#: seconds of stream time (5 min: an hour's waist pausing on every packet writes about 24 lines, not 20 000); every
#: occurrence is counted in ``Tracker.warning_counts``
REPEAT_WARN_S = 300.0

#: decision E236 (ours): a repeated line held back by E224 is written after all once its cause has lasted this many
#: seconds of stream time (a waist paused and not back 10 s later is gone, not pausing on every packet: T4's flapping
#: waist came back within a packet, 0.2 s)
STILL_S = 10.0

UNITS = {"f": "foot", "w": "waist"}


def unit_of(name: str) -> str | None:
    """The body unit of a sensor stream (``fAccelerometer`` -> ``"foot"``), None for another name."""
    return UNITS.get(str(name)[:1])


def _per_unit(pushed: dict) -> dict[str, tuple[float, float]]:
    """unit -> (first, last) time (s) over the streams of ``pushed`` (sensor -> (first, last))."""
    out: dict[str, tuple[float, float]] = {}
    for name, (a, b) in pushed.items():
        u = unit_of(name)
        if u is not None:
            a0, b0 = out.get(u, (math.inf, -math.inf))
            out[u] = (min(a0, a), max(b0, b))
    return out


class StartClocks:
    """Decision E223: whether the two units' clocks disagree by more than ``max_lag_s`` from the start.

    At the first push that holds a sample of both units, the gap between the new unit's newest sample and the other
    unit's newest (``contact``, s, waist minus foot; decision E242: its newest, not its first, which lies a packet or a
    held-back burst before) is how far apart the clocks read at the same wall time, whatever the order the pods
    connected in (a unit switched on later on the same clock ends its first push beside the other's newest: no
    gap). Decision E238: the offset named is ``offset``: the difference of the units' first samples when it is within
    the other unit's latest push of ``contact`` (pods that connected together: exact), else ``contact`` (a pod that
    joined later: its first samples' difference is not the clocks'). The times are those of every push that passed
    E29's checks, refused by the lag check or not (a unit whose pushes are all refused still shows its clock; a
    diagnostic, no tracking state); nothing more is noted once both units are seen. Decision E255: the other unit's
    newest includes the joining push (both pods' packets of a slice in one push)."""

    __slots__ = ("first", "newest", "contact", "offset", "max_lag_s", "_pushed", "_joined")

    def __init__(self, max_lag_s: float):
        self.max_lag_s = float(max_lag_s)
        self.first: dict[str, float] = {}
        self.newest: dict[str, float] = {}
        self.contact: float | None = None
        self.offset: float | None = None
        self._pushed: dict[str, float] = {}  # unit -> the first sample of its latest push
        self._joined: str | None = None  # the unit that joined the other (None: both in one push, or together)

    def seen(self, pushed: dict) -> None:
        """Note a push's times (sensor -> (first, last) s, on the tracker's clock) until both units are seen."""
        if self.contact is not None:
            return
        per = _per_unit(pushed)
        if "foot" in per and "waist" in per and not self.newest:  # both in one push
            self.contact = per["waist"][0] - per["foot"][0]
        # decision E242: a joining unit's newest sample against the other's newest (each unit's latest time known
        # when the push arrives), not its first: a push of one packet (its span, 0.15 s at 0.2 s packets) or a burst
        # the pod held back put its first sample that much before the other's newest
        # decision E255: the other unit's newest including this push (a phone that gathers both pods' packets of a
        # slice into one push after one pod connected alone), and the units' first samples (the other's first ever)
        elif "waist" in per and "foot" in self.newest and "waist" not in self.newest:  # the waist joins the foot
            self.contact, self._joined = per["waist"][1] - self._newest_with(per, "foot"), "waist"
        elif "foot" in per and "waist" in self.newest and "foot" not in self.newest:  # the foot joins the waist
            self.contact, self._joined = self._newest_with(per, "waist") - per["foot"][1], "foot"
        if self.contact is not None:
            other = {"waist": "foot", "foot": "waist"}.get(self._joined)
            span = 0.0 if other is None else self._newest_with(per, other) - self._pushed[other]
            w = (per["waist"][0] if other != "waist" else self.first["waist"]) - (
                per["foot"][0] if other != "foot" else self.first["foot"])
            together = abs(w - self.contact) <= span + 1e-6
            self.offset = w if together else self.contact  # decision E238
            self._joined = None if together else self._joined  # the pods connected together: named so
        for u, (a, b) in per.items():
            self.first[u] = min(self.first.get(u, math.inf), a)
            self.newest[u] = max(self.newest.get(u, -math.inf), b)
            self._pushed[u] = a

    def _newest_with(self, per: dict, unit: str) -> float:
        """``unit``'s newest sample including the push ``per`` (unit -> (first, last) s)."""
        return max(self.newest[unit], per[unit][1]) if unit in per else self.newest[unit]

    def note(self, name: str, given_s: float, taken: bool = True) -> str:
        """The clause naming the start-up offset when the lagging stream ``name`` is of the unit whose clock reads
        behind, or was never taken (``taken`` False) though its unit's pushes came (refused), else ''. ``given_s``:
        the tracker's ``waist_clock_offset_s`` (the samples are already moved by it)."""
        contact, off = self.contact, self.offset
        if contact is None or abs(contact) <= self.max_lag_s:
            return ""
        behind = "waist" if contact < 0 else "foot"
        if taken and unit_of(name) != behind:  # decision E238: no test of the first samples' sign
            return ""
        first, joined = self.first, self._joined
        if joined is None:  # the pods connected together
            seen = f"the units' first samples at {first['foot']:.2f} s (foot) and {first['waist']:.2f} s (waist)"
        else:
            other = "foot" if joined == "waist" else "waist"
            mine = self.newest[joined]  # decision E242: its newest at contact (nothing is noted after it)
            seen = (f"the {joined}'s newest sample at {mine:.2f} s when the {other}'s newest was "
                    f"{mine - (contact if joined == 'waist' else -contact):.2f} s")
        return (f"the waist clock is about {abs(off):.1f} s {'ahead of' if off > 0 else 'behind'} the foot's ({seen}: "
                f"two clocks, not a stopped sensor): pass Tracker(..., waist_clock_offset_s={given_s + off:.2f}) "
                "(t_waist = t_foot + offset) or stamp both units on one clock set at connection (decisions E223, "
                "E238)")


class RepeatedLines:
    """Decision E224: a kind of warning line that can repeat for as long as its cause lasts (E115's pause and resume
    on every packet) is written at most once per :data:`REPEAT_WARN_S` of stream time, with the count since the last
    line; ``counts`` (kind -> occurrences) counts every one. Decision E236: only flapping is held back: a held line
    whose cause lasts :data:`STILL_S` is written after all (:meth:`overdue`), and :meth:`summary` (at ``flush``)
    writes one line per kind with lines not written since its last."""

    __slots__ = ("counts", "_said", "_unsaid")

    def __init__(self):
        self.counts: dict[str, int] = {}
        self._said: dict[str, tuple[float, int]] = {}  # kind -> (stream time of its last line, count then)
        self._unsaid: dict[str, tuple[float, float, str]] = {}  # kind -> (first and last held-back time, last msg)

    def line(self, kind: str, msg: str, t: float) -> str | None:
        """``msg`` (with the occurrences not written since the last) when due at stream time ``t``, else None."""
        self.counts[kind] = self.counts.get(kind, 0) + 1
        last = self._said.get(kind)
        if last is not None and t - last[0] < REPEAT_WARN_S:
            self._unsaid[kind] = (self._unsaid.get(kind, (t,))[0], t, msg)
            return None
        return self._write(kind, msg, t, "")

    def _write(self, kind: str, msg: str, t: float, why: str) -> str:
        """``msg`` written at ``t``: the held-back count since the last line of ``kind`` appended (``why`` first)."""
        n, last = self.counts[kind], self._said.get(kind)
        self._said[kind] = (t, n)
        self._unsaid.pop(kind, None)
        k = 0 if last is None else n - last[1] - 1
        if not k and not why:
            return msg
        held = (f"{k} more such lines since {last[0]:.2f} s not written: at most one per {REPEAT_WARN_S:g} s of stream "
                "time" if k else "")
        return f"{msg} [{'; '.join(x for x in (why, held) if x)}; warning_counts[{kind!r}] = {n} (decision E224)]"

    def overdue(self, kind: str, t: float) -> str | None:
        """Decision E236: the held-back line of ``kind`` whose cause still lasts at stream time ``t``, written when
        it was held back :data:`STILL_S` or more before ``t`` (the caller asks only while the cause lasts), else
        None."""
        held = self._unsaid.get(kind)
        if held is None or t - held[1] < STILL_S:
            return None
        return self._write(kind, held[2], t, f"still so at {t:.2f} s, {t - held[1]:.1f} s later: not a stream that "
                                             f"comes back at once, so written after all (decision E236)")

    def summary(self, t: float) -> list[str]:
        """Decision E236 (at the end of a stream, stream time ``t``): one line per kind with lines not written since
        its last: the last of them, with the count."""
        out = []
        for kind in list(self._unsaid):
            first = self._unsaid[kind][0]
            out.append(self._write(kind, self._unsaid[kind][2], t, f"the last of the lines held back since {first:.2f} "
                                   "s, written at the end (decision E236)"))
        return out


def _wrapped(t0: float, last: float, offset_s: float, drift: float) -> tuple[int, float, float] | None:
    """Decision E297: ``(bits, tick_s, offset)`` when the unit clock's step back from ``last`` to ``t0`` (the tracker's
    clock; the unit reads ``t (1 + drift) + offset_s``, E229 / E248) is a counter wrapping (B312's rule on the unit's
    own readings, :func:`~pdrlearn.kernels.counter_wrap.live_wrap`): the offset that goes on exactly across it is the
    one now less the counter's period, ``2**bits`` ticks; None otherwise."""
    w = live_wrap(last * (1.0 + drift) + offset_s, t0 * (1.0 + drift) + offset_s)
    return None if w is None else (w[0], w[1], offset_s - 2.0 ** w[0] * w[1])


def _wrap_text(unit: str, bits: int, tick: float, off: float) -> str:
    """Decision E297: the clause naming a unit's counter that wrapped and the exact rebase."""
    word = {1e-3: "ms", 1e-6: "us"}.get(tick, f"{tick:g} s")
    period = 2.0 ** bits * tick
    # review R1 finding F3: a uint16 ms (65.5 s) or uint32 us (71.6 min) counter's period is a pod's plausible run
    # time, and a restart within 1 s of it reads the same
    restart = ("not a restart" if period >= 86400.0 else
               f"or a pod that restarted {period:.1f} s after its clock started (the two read the same: then follow "
               f"E227 instead, its samples just after the last)")
    return (f"the {unit} clock wrapped: a {bits}-bit {word} counter overflowing (2^{bits} {word} = "
            f"{period:.6f} s), {restart}; tracker.rebase_clock({unit!r}, {off:.6f}) goes on exactly "
            f"across it, but a packet holding the wrap is still refused: unwrap each pod's counter before pushing, "
            f"pdrlearn.runtime.CounterUnwrapper(bits={bits}, tick_s={tick:g}) (decision E297)")


def _all_went_back(head: str, back: dict, drift: dict) -> ClockWentBack:
    """Decision E243: the refusal of a push holding two units whose clocks both went back (unit -> (first sample,
    its streams' newest, offset now), the tracker's clock): each unit's first pushed sample goes just after the
    tracker's newest, so the push's units stay beside each other as pushed (E223's reading of one push: its units'
    first samples are the same wall time), in one refusal: rebasing one unit and pushing again refused the other."""
    newest = max(b for _, b, _ in back.values())
    # decision E248: each unit's drift (s/s, ``drift``), as order_error's one-unit offset
    offsets = {u: off + (a - newest - 1e-3) * (1.0 + drift.get(u, 0.0)) for u, (a, _, off) in back.items()}
    wraps = {u: w for u, (a, b, off) in back.items() if (w := _wrapped(a, b, off, drift.get(u, 0.0)))}
    if wraps:  # decision E297: a unit whose counter wrapped goes on exactly across it, whatever the other's did
        offsets.update({u: w[2] for u, w in wraps.items()})
        first = next(iter(wraps))
        return ClockWentBack(f"{head}: " + "; ".join(_wrap_text(u, *w) for u, w in wraps.items()) + " (ClockWentBack."
                             "offsets: every unit of the push that went back)", first, offsets[first], False, offsets)
    went = " and ".join(f"the {u} clock {b - a:.2f} s" for u, (a, b, _) in back.items())
    calls = " and ".join(f"tracker.rebase_clock({u!r}, {o:.2f})" for u, o in offsets.items())
    first = next(iter(offsets))
    return ClockWentBack(
        f"{head}: {went} went back, both pods reconnected with their clocks restarted? The push is refused and the "
        f"tracker unchanged; {calls} put their new samples just after the tracker's newest, beside each other as "
        f"pushed (less the seconds they were gone: {offsets[first]:.2f} - gone), and the same Tracker goes on "
        "(ClockWentBack.offsets; decisions E227, E243)", first, offsets[first], False, offsets)


def order_error(name: str, t0: float, last: float, *, duplicate: bool, max_lag_s: float, offset_s: float,
                other_newest: float | None, note: str = "", also_back: dict | None = None,
                drift: dict | None = None) -> DataError:
    """The refusal of a push whose first ``name`` sample (``t0`` s, the tracker's clock) is not after the stream's
    newest (``last``): a duplicate of a sample taken (decision E225), a clock that went back by more than
    ``max_lag_s`` (E227: :class:`ClockWentBack`, with the offset that puts it beside the other unit's newest,
    ``other_newest``, or just after its own last sample when none is past it, E235; ``offset_s`` the unit's offset
    now), or a late sample; ``note``: B141's jumped-clock note. ``also_back``: the other units of the push whose clock
    went back too, unit -> (first sample, its streams' newest, offset now) (decision E243: one refusal names both).
    ``drift``: unit -> its clock's drift in s/s (E229's waist model ``t = (t_unit - offset_s) / (1 + drift)``; decision
    E248: every offset given holds it)."""
    head = f"{name}: pushed timestamps are not increasing (at {t0:.3f} s after {last:.3f} s)"
    if duplicate:
        return DataError(f"{head}: that sample duplicates one already taken, a packet sent again? "
                         "Tracker(drop_duplicate_timestamps=True) drops such samples, counted in dropped_duplicates "
                         f"(decision E225); the push is refused and the tracker unchanged{note}")
    unit = unit_of(name)
    if last - t0 > max_lag_s and unit is not None and not note:  # B141's accepted jump: its own note, not E227
        if also_back:
            return _all_went_back(head, {unit: (t0, last, offset_s), **also_back}, drift or {})
        wrap = _wrapped(t0, last, offset_s, (drift or {}).get(unit, 0.0))
        if wrap is not None:  # decision E297: a counter wrap, not a restart: the exact offset, not E235's guess
            return ClockWentBack(f"{head}: {_wrap_text(unit, *wrap)} (ClockWentBack.offset_s)", unit, wrap[2], False)
        beside = other_newest is not None and other_newest > last
        # the sample 1 ms after the tracker's newest: its unit clock's reading t0 (1 + drift) + offset_s less that
        # time on the unit's clock (decision E248: with E229's drift; E227 took t0 - target, off by target x drift)
        off = offset_s + (t0 - (other_newest if beside else last) - 1e-3) * (1.0 + (drift or {}).get(unit, 0.0))
        where = ("beside the other unit's newest" if beside else
                 f"just after its last sample (less the seconds it was gone: {off:.2f} - gone)")
        return ClockWentBack(
            f"{head}: the {unit} clock went back {last - t0:.2f} s, a pod that reconnected with its clock restarted? "
            f"The push is refused and the tracker unchanged; tracker.rebase_clock({unit!r}, {off:.2f}) puts its new "
            f"samples {where} and the same Tracker goes on (ClockWentBack.offset_s; decision E227)", unit,
            off, beside)  # decision E235: always the offset the line names, never None
    return DataError(f"{head}; a packet that arrived late? a sample older than the stream's newest is refused (the "
                     "push is refused and the tracker unchanged): push each unit's samples in the order it sent them, "
                     f"{reorder_hint()}{note}")  # decision E349


__all__ = ["REPEAT_WARN_S", "STILL_S", "RepeatedLines", "StartClocks", "order_error", "unit_of"]
