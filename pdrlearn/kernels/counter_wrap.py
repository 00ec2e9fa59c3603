"""Decision B312: a sensor's timestamp counter that wraps around (a 16-bit millisecond counter every 65.536 s, a
32-bit microsecond counter every 71.6 min) is unwrapped, not taken for a clock reset. Numpy only."""

from __future__ import annotations

import math

import numpy as np

#: decision B312: the counter widths recognised (bits): 16 is the narrowest timestamp counter a sensor's firmware
#: keeps (a 16-bit ms counter lasts 65.5 s); a narrower one wraps too often to be a recording's clock
WRAP_BITS = range(16, 65)
#: decision B312: the interval across a wrap must be continuous sampling: at most this many median intervals (D3's
#: gap: longer is a gap, across which the number of wraps is not known)
WRAP_GAP = 1.5
#: decision B450: with the counter's tick known (s), the interval across a wrap may be as long as B11's gap limit
#: (``kernels.gaps.MIN_GAP_S``, 1 s): packets lost over a Bluetooth link at the wrap, a gap said as such; the number
#: of wraps across it is known as long as it is under half the counter's period (a 16-bit ms counter's 32.8 s)
WRAP_TICKS_S = (1e-3, 1e-6)  # decision E297: the live path's ticks tried (a ms and a us counter pushed as seconds)
#: decisions B450 / E297, amended (review R1 finding F3): the widths a firmware's ms / us timestamp counter has
#: (uint16, uint32, uint64). Only these may wrap across more than B312's 1.5 intervals (B450's 1 s, the live path's
#: E297): with every width of :data:`WRAP_BITS`, a pod restarted within 1 s below any 2^k ms or us (2.1 s, 4.2 s,
#: 16.8 s ...) read as a wrap. No 24: the 24-bit sensor counters known tick at 1/32768 s (Shimmer3's 3-byte
#: timestamp) or 39 us (the BMI160's sensor time), not the ms / us ticks tried here
COUNTER_BITS = (16, 32, 64)
#: decision B451: across a wrap with packets lost (B450's gap), the pod's sampling goes on, so the interval across is
#: a whole number of its sample intervals to within this many (the ticks' rounding: 1 ms of a 19.2 ms interval is
#: 0.05); a restart starts its clock anew, off that phase
WRAP_PHASE = 0.25


def counter_width(top: float, widths=WRAP_BITS) -> int:
    """Decision B312: the smallest counter width of ``widths`` (:data:`WRAP_BITS`; the live path
    :data:`COUNTER_BITS`, B450 / E297) above ``top`` (the largest raw value), 0 when none."""
    return next((b for b in widths if top < 2.0 ** b), 0)


def wrap_limit(median_ticks: float, bits: int, tick_s: float | None = None) -> float:
    """Decisions B312 / B450: the longest interval (ticks) across a wrap of a ``bits``-bit counter: WRAP_GAP
    median intervals, or, with the tick known (``tick_s``, s) and ``bits`` a firmware's width
    (:data:`COUNTER_BITS`, review R1 finding F3), B11's 1 s gap limit when that is longer and under half the
    counter's period (the number of wraps across it is then known)."""
    from pdrlearn.kernels.gaps import MIN_GAP_S

    limit = WRAP_GAP * median_ticks
    if tick_s and bits in COUNTER_BITS and MIN_GAP_S / tick_s < 2.0 ** (bits - 1):  # R1 F3: a firmware's width
        limit = max(limit, MIN_GAP_S / tick_s)
    return limit


def counter_wraps(raw: np.ndarray, tick_s: float | None = None) -> tuple[int, np.ndarray]:
    """Decision B312: ``(bits, idx)`` when every backward step of the raw timestamps ``raw`` (the file's own
    ticks) is a wrap of a ``bits``-bit counter: all values in ``[0, 2**bits)`` (the smallest such width of
    :data:`WRAP_BITS`), and each step ``raw[i] -> raw[i + 1]`` at ``idx`` is, with ``2**bits`` added, a forward
    interval of at most :data:`WRAP_GAP` median intervals (sampling continues across it), or with the tick known
    (``tick_s``, s; decision B450) at most :func:`wrap_limit`'s 1 s (packets lost at the wrap), then a whole number
    of sample intervals (:data:`WRAP_PHASE`, decision B451: a restart is off the phase). ``(0, [])`` otherwise
    (no backward step, a clock reset, rows out of order: :func:`pdrlearn.io.validate.check_timestamps` judges)."""
    r = np.asarray(raw, dtype=float)
    none = (0, np.empty(0, dtype=np.int64))
    if r.size < 3 or not np.isfinite(r).all() or r.min() < 0:
        return none
    d = np.diff(r)
    back = np.flatnonzero(d < 0)
    fwd = d[d > 0]
    if not back.size or not fwd.size:
        return none
    bits = counter_width(float(r.max()))
    if not bits:
        return none
    across = d[back] + 2.0 ** bits  # the interval across each wrap, in ticks
    median = float(np.median(fwd))
    if not ((across > 0) & (across <= wrap_limit(median, bits, tick_s))).all():
        return none
    gaps = across[across > WRAP_GAP * median]  # decision B450's packets lost at a wrap
    if gaps.size:  # decision B451: the sampling goes on across them, a whole number of its intervals
        step = float(np.mean(fwd[fwd <= WRAP_GAP * median]))  # the mean interval, so the ticks' rounding averages out
        if (np.abs(gaps / step - np.round(gaps / step)) > WRAP_PHASE).any():
            return none
    return bits, back


def unwrap(raw: np.ndarray, bits: int, idx: np.ndarray) -> np.ndarray:
    """Decision B312: ``raw`` with ``2**bits`` added after each wrap at ``idx`` (:func:`counter_wraps`)."""
    out = np.asarray(raw, dtype=float).copy()
    step = np.zeros(out.size)
    step[np.asarray(idx, dtype=np.int64) + 1] = 2.0 ** bits
    return out + np.cumsum(step)


def wrap_message(where: str, raw: np.ndarray, bits: int, idx: np.ndarray, unit: str, line: int) -> str:
    """Decision B312's one warning line: the file, where the counter first wraps, its width and what was done;
    decision B450: the longest interval across a wrap when it is a gap (over :data:`WRAP_GAP` median intervals)."""
    i = int(idx[0])
    more = f" ({idx.size} times)" if idx.size > 1 else ""
    r = np.asarray(raw, dtype=float)
    d = np.diff(r)
    across = d[idx] + 2.0 ** bits
    median = float(np.median(d[d > 0]))
    across_it, gap = "with sampling continuing across it", ""
    if across.max() > WRAP_GAP * median:  # decision B450: samples lost at the wrap, said as the gap they are
        k = int(np.argmax(across))
        across_it = "with samples lost across it"
        gap = (f"; the interval across the wrap at line {line + int(idx[k]) - i} is {across[k]:.0f} {unit}, "
               f"{across[k] / median:.1f} sample intervals: a gap (packets lost), kept as one (decision B450)")
    return (f"{where}: the timestamps wrap around from {raw[i]:.0f} to {raw[i + 1]:.0f} {unit} at line {line}{more}: a "
            f"{bits}-bit counter overflowing (2^{bits} = {2 ** bits} {unit}) {across_it}, not a clock reset; "
            f"unwrapped by adding 2^{bits} {unit} after each wrap (decision B312){gap}")


def live_wrap(last_s: float, t0_s: float) -> tuple[int, float] | None:
    """Decision E297: ``(bits, tick_s)`` when a live unit clock stepping back from ``last_s`` to ``t0_s`` (s, the
    unit's own readings) is a ``bits``-bit counter of ``tick_s`` s ticks (:data:`WRAP_TICKS_S`) wrapping: the
    smallest of :data:`COUNTER_BITS` above ``last_s`` (review R1 finding F3; B312's :func:`counter_width`) with the
    interval across it, ``2**bits`` ticks added, positive and within :func:`wrap_limit`'s 1 s (B450); None
    otherwise (a restart, E227). A uint16 ms counter (65.5 s) and a uint32 us one (71.6 min) read the same as a
    restart then: the line says both (``runtime.links``)."""
    if not (math.isfinite(last_s) and math.isfinite(t0_s)) or t0_s < 0 or t0_s >= last_s:
        return None
    for tick in WRAP_TICKS_S:
        bits = counter_width(last_s / tick, COUNTER_BITS)  # E297 (R1 F3): a firmware's width, not any 16..64
        across = (t0_s - last_s) / tick + 2.0 ** bits
        if bits and 0 < across <= wrap_limit(0.0, bits, tick):
            return bits, tick
    return None


def unwrap_near(raw: np.ndarray, ref_raw: int, ref: int, bits: int) -> np.ndarray:
    """Decision E297: the ``bits``-bit counter values ``raw`` unwrapped, each as the ticks nearest to the value
    before it (the first to the reference, ``ref_raw`` read as the unwrapped ``ref``): the running sum from ``ref`` of
    each step modulo ``2**bits``, taken in ``[-2**(bits-1), 2**(bits-1))``; so a wrap, packets out of order and
    repeats all land where they belong while each step is within half the counter's period, also in a chunk that
    spans more than half of it (review R1 finding F4; int64 ticks, bits <= 62)."""
    half, full = 1 << (bits - 1), 1 << bits
    c = np.asarray(raw, dtype=np.int64).reshape(-1)
    steps = np.diff(c, prepend=np.int64(ref_raw))
    return int(ref) + np.cumsum((steps + half) % full - half)
