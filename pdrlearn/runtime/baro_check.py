"""Decision E232: L145's foot-vs-barometer altitude check for the live foot :class:`~pdrlearn.runtime.Tracker`.

``pdrlearn run`` compares a foot track's altitude change with the waist barometer's over the strides' span (L145,
with L172's climbs and L180's missed climb); the live tracker, pushed the same barometer, said nothing (trial T4 of
session 40, finding F6). The watch holds the pushed barometer in E106's :class:`~pdrlearn.kernels.barometer.
LiveAltitude` (W89's centred smoothing, B188's plausibility), reads its altitude at the span's start and at each
emitted row's end once the samples up to that time plus the smoothing window were pushed (so the offline value), and
gives :func:`pdrlearn.kernels.barometer_check.barometer_keys`' keys, the offline summary's, to
:func:`~pdrlearn.kernels.barometer_check.barometer_warning`. State: the barometer over a few smoothing windows and two
floats a row and the track's z (24 bytes, as E75's height log: the check judges the whole walk).
"""

from __future__ import annotations

from array import array

import numpy as np


class BaroCheck:
    """The pushed barometer ``name`` (s, hPa) and the track's rows: ``push(t, values)``, ``row(step)`` for each emitted
    row, ``line(final)`` L145's line on what was read so far (None when they agree, or before two rows)."""

    def __init__(self, name: str):
        from pdrlearn.kernels.barometer import LiveAltitude

        self.name = name
        self._alt = LiveAltitude()
        self._pending: list[float] = []  # times whose altitude waits for the smoothing window's right half
        self._at, self._z = array("d"), array("d")  # the barometer's altitude (m) at the span start and row ends
        self._track = array("d")  # the track's z at the same times

    def push(self, t, values) -> None:
        t = np.asarray(t, dtype=float).reshape(-1)
        if len(t):
            self._alt.push(t, np.asarray(values, dtype=float).reshape(len(t), -1)[:, 0])
            self._read(final=False)

    def row(self, start_s: float, end_s: float, z: float, dz: float) -> None:
        if not self._track:
            self._alt.set_origin(start_s)  # the span's start, as track's relative_altitude(span)
            self._pending.append(float(start_s))
            self._track.append(float(z) - float(dz))
        self._pending.append(float(end_s))
        self._track.append(float(z))
        self._read(final=False)

    def _read(self, final: bool) -> None:
        t = self._alt._t
        last = float(t[-1]) if t.size else -np.inf
        while self._pending and (final or self._pending[0] + self._alt.window_s <= last):
            ts = self._pending.pop(0)
            z = self._alt.at(ts)
            self._at.append(ts)
            self._z.append(np.nan if z is None else z)
        if self._at:
            self._alt.trim(self._pending[0] if self._pending else self._at[-1])

    def line(self, final: bool = False) -> str | None:
        """L145's line (``pdrlearn run``'s, decision E232) on the rows read so far; ``final``: the last rows on the
        samples pushed (the end of the stream). None when the altitudes agree, the barometer is implausible (B188)
        or fewer than two rows were read."""
        from pdrlearn.kernels.altitude_check import ascent_descent
        from pdrlearn.kernels.barometer_check import barometer_keys, barometer_warning

        if final:
            self._read(final=True)
        n = len(self._z)
        if n < 2 or self._alt.implausible is not None or not np.isfinite(self._z).all():
            return None
        at, z = np.frombuffer(self._at, dtype=float), np.frombuffer(self._z, dtype=float)
        track = np.frombuffer(self._track, dtype=float)[:n]
        up, down = ascent_descent(track, 0.0)  # decision L146: a foot track's strides as they are (track's _ascent)
        summary = {"altitude_change_m": float(track[-1] - track[0]), "ascent_m": up, "descent_m": down,
                   "barometer_unused": True, **barometer_keys(at, z, float(z[-1]))}
        return barometer_warning(summary)
