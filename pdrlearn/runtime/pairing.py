"""Decision E204: an accelerometer and a gyroscope delivered as two streams with their own timestamps (Android's
sensor events, a phone app's two listeners) paired for :meth:`pdrlearn.runtime.WaistTracker.push`, which takes one
``t`` for both. Numpy only, like the rest of :mod:`pdrlearn.runtime`."""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.order import first_out_of_order


def _rows(name: str, t, v, last: float) -> tuple[np.ndarray, np.ndarray]:
    """Decision E204: one push's stamps (s) and (n, 3) values, or one DataError line: not numbers, a wrong shape, a
    NaN / inf stamp, or a stamp that goes back (from the one before it, or from ``last``, the stream's last pushed)."""
    try:
        t = np.asarray(t, dtype=np.float64).reshape(-1)
        v = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise DataError(f"SensorPair.{name}: timestamps (s) and values must be numbers ({e}); push float arrays"
                        ) from None
    if v.size == 3 and t.size == 1:
        v = v.reshape(1, 3)
    if not v.size and not t.size:
        v = np.zeros((0, 3))
    if v.shape != (t.size, 3):
        raise DataError(f"SensorPair.{name}: expected values of shape ({t.size}, 3) for {t.size} timestamps, got "
                        f"{np.shape(v)}")
    if not np.isfinite(t).all():
        raise DataError(f"SensorPair.{name}: NaN or inf timestamps; drop those samples")
    i = first_out_of_order(t, last, strict=False)
    if i is not None:  # E204 (amended): a step back would be interpolated from (gyr) or dropped as early (acc)
        before = "the previous push's last" if i == 0 else f"sample {i - 1}"
        raise DataError(f"SensorPair.{name}: timestamps must not go back (seconds): sample {i} of this push "
                        f"(t={t[i]:.6f} s) is before {before} (t={t[i - 1] if i else last:.6f} s); push each stream "
                        "in time order (sort a batch by time before pushing)")
    return t, v


class SensorPair:
    """Decision E204: pairs the two streams on the accelerometer's timestamps, the gyroscope linearly interpolated
    there, as the offline pipelines do (``pdrlearn.waist.ahrs.body_data``): an accelerometer sample is released by
    :meth:`take` once a gyroscope sample at or after its time has arrived; accelerometer samples before the first
    gyroscope sample are dropped (counted in ``n_dropped``), as offline reads only the span both cover.

    ``pair.push_acc(t, acc)`` and ``pair.push_gyr(t, gyr)`` as each stream's samples arrive (s, (n, 3)), then
    ``tracker.push(*pair.take())``. Each stream's stamps must not go back (one DataError line, nothing kept: a
    gyroscope batch out of order made the pair drop accelerometer samples the gyroscope covered); a repeated stamp
    is kept (the gyroscope's interpolates the same; the accelerometer's is the tracker's, E203's option)."""

    def __init__(self):
        self._ta, self._a = np.zeros(0), np.zeros((0, 3))
        self._tg, self._g = np.zeros(0), np.zeros((0, 3))
        self.n_dropped = 0
        self._last_a = self._last_g = -np.inf  # each stream's last pushed stamp (E204: no step back)

    def push_acc(self, t, acc) -> None:
        t, v = _rows("push_acc", t, acc, self._last_a)
        self._last_a = float(t[-1]) if t.size else self._last_a
        self._ta, self._a = np.concatenate([self._ta, t]), np.vstack([self._a, v])

    def push_gyr(self, t, gyr) -> None:
        t, v = _rows("push_gyr", t, gyr, self._last_g)
        self._last_g = float(t[-1]) if t.size else self._last_g
        self._tg, self._g = np.concatenate([self._tg, t]), np.vstack([self._g, v])

    def take(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(t, acc, gyr)``: the accelerometer samples the gyroscope now covers, with the gyroscope at their times
        (empty arrays when none)."""
        empty = (np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)))
        if not self._tg.size or not self._ta.size:
            return empty
        early = self._ta < self._tg[0]
        if early.any():  # before the gyroscope's first sample: nothing to interpolate from
            self.n_dropped += int(early.sum())
            self._ta, self._a = self._ta[~early], self._a[~early]
        ready = self._ta <= self._tg[-1]
        if not ready.any():
            return empty
        t, a = self._ta[ready], self._a[ready]
        g = np.column_stack([np.interp(t, self._tg, self._g[:, j]) for j in range(3)])
        self._ta, self._a = self._ta[~ready], self._a[~ready]
        k = max(int(np.searchsorted(self._tg, t[-1], "right")) - 1, 0)  # the gyroscope sample at or before the last
        self._tg, self._g = self._tg[k:], self._g[k:]  # released time starts the next interpolation
        return t, a, g
