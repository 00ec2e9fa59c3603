"""Decision E211: the foot runtime's ``Tracker`` names each lift or escalator ride it does not count.

Offline ``pdrlearn track`` books a standstill's barometric change of half a storey or more as a ride (decisions
W158, W231, L375: ``rides.csv``, ``floors_up_rides``); the streamed foot track's ``z`` is the walked height only, so
after a lift every live step kept the height before it, with no warning (trial T5 of session 38, finding 3). The
watch holds the pushed barometer across the standstill between two reported strides and reads its ride with the
offline kernel (:func:`pdrlearn.kernels.pause_ride.pause_ride_dz`, the same rule as ``track.rides``); a ride of
:data:`~pdrlearn.kernels.pause_ride.RIDE_MIN_M` or more gives one warning line naming it, as soon as the stride after
it is reported.
"""

from __future__ import annotations

import numpy as np

#: the barometers the watch reads, the first one the tracker uses (the waist phone's, then a foot unit's)
BAROMETERS = ("wBarometer", "fBarometer")


class RideWatch:
    """The pushed barometer (s, hPa) since the last reported stride; :meth:`line` for the standstill ``(a, b)``."""

    def __init__(self, name: str):
        self.name = name
        self._t = np.zeros(0)
        self._p = np.zeros(0)

    def push(self, t, values) -> None:
        t = np.asarray(t, dtype=float).reshape(-1)
        if not len(t):  # an empty push (a stream that stopped, a chunk without barometer rows)
            return
        p = np.asarray(values, dtype=float).reshape(len(t), -1)[:, 0]
        self._t = np.concatenate([self._t, t])
        self._p = np.concatenate([self._p, p])

    def line(self, a: float, b: float) -> str | None:
        """The warning line when the standstill from ``a`` to ``b`` (s) holds a ride (W231's rule: a standstill
        up to RIDE_WINDOW_S counts whole, a longer one only its fast spans); None otherwise. Drops the samples
        before ``a`` less a smoothing window (the next standstill starts after ``b``)."""
        from pdrlearn.kernels.barometer import ALTITUDE_SMOOTH_S
        from pdrlearn.kernels.pause_ride import RIDE_MIN_M, pause_ride_dz

        ok = np.isfinite(self._t) & np.isfinite(self._p)
        dz = None
        if b > a and np.count_nonzero(ok) >= 2 and self._t[ok][0] <= a:
            dz = pause_ride_dz(self._t[ok], self._p[ok], float(a), float(b))[0]  # decision W231, as track.rides
        keep = self._t >= b - 2.0 * ALTITUDE_SMOOTH_S
        self._t, self._p = self._t[keep], self._p[keep]
        if dz is None or not abs(dz) >= RIDE_MIN_M:  # W231's half storey, as track.rides._pause_dz
            return None
        return (f"{self.name}: the altitude changed {dz:+.1f} m while the wearer stood from {a:.1f} to {b:.1f} s (a "
                "lift or escalator ride, decision W231); the streamed z counts the walked height only, so the steps "
                "after it keep the height before it (decision E211): `pdrlearn track` on the recording counts rides "
                "(rides.csv, floors_up_rides)")
