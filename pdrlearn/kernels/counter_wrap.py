"""Decision B312: a sensor's timestamp counter that wraps around (a 16-bit millisecond counter every 65.536 s, a
32-bit microsecond counter every 71.6 min) is unwrapped, not taken for a clock reset. Numpy only."""

from __future__ import annotations

import numpy as np

#: decision B312: the counter widths recognised (bits): 16 is the narrowest timestamp counter a sensor's firmware
#: keeps (a 16-bit ms counter lasts 65.5 s); a narrower one wraps too often to be a recording's clock
WRAP_BITS = range(16, 65)
#: decision B312: the interval across a wrap must be continuous sampling: at most this many median intervals (D3's
#: gap: longer is a gap, across which the number of wraps is not known)
WRAP_GAP = 1.5


def counter_wraps(raw: np.ndarray) -> tuple[int, np.ndarray]:
    """Decision B312: ``(bits, idx)`` when every backward step of the raw timestamps ``raw`` (the file's own
    ticks) is a wrap of a ``bits``-bit counter: all values in ``[0, 2**bits)`` (the smallest such width of
    :data:`WRAP_BITS`), and each step ``raw[i] -> raw[i + 1]`` at ``idx`` is, with ``2**bits`` added, a forward
    interval of at most :data:`WRAP_GAP` median intervals (sampling continues across it). ``(0, [])`` otherwise
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
    bits = next((b for b in WRAP_BITS if r.max() < 2.0 ** b), 0)
    if not bits:
        return none
    across = d[back] + 2.0 ** bits  # the interval across each wrap, in ticks
    if ((across > 0) & (across <= WRAP_GAP * float(np.median(fwd)))).all():
        return bits, back
    return none


def unwrap(raw: np.ndarray, bits: int, idx: np.ndarray) -> np.ndarray:
    """Decision B312: ``raw`` with ``2**bits`` added after each wrap at ``idx`` (:func:`counter_wraps`)."""
    out = np.asarray(raw, dtype=float).copy()
    step = np.zeros(out.size)
    step[np.asarray(idx, dtype=np.int64) + 1] = 2.0 ** bits
    return out + np.cumsum(step)


def wrap_message(where: str, raw: np.ndarray, bits: int, idx: np.ndarray, unit: str, line: int) -> str:
    """Decision B312's one warning line: the file, where the counter first wraps, its width and what was done."""
    i = int(idx[0])
    more = f" ({idx.size} times)" if idx.size > 1 else ""
    return (f"{where}: the timestamps wrap around from {raw[i]:.0f} to {raw[i + 1]:.0f} {unit} at line {line}{more}: a "
            f"{bits}-bit counter overflowing (2^{bits} = {2 ** bits} {unit}) with sampling continuing across it, not a "
            f"clock reset; unwrapped by adding 2^{bits} {unit} after each wrap (decision B312)")
