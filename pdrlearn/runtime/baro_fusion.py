"""Decision E339: L154's barometric altitude for the live foot :class:`~pdrlearn.runtime.Tracker`
(``altitude="fused"``, ``pdrlearn run --altitude fused``).

Offline ``pdrlearn track --altitude fused`` fuses the strides' height changes with the waist barometer
(:func:`pdrlearn.kernels.barometer.fuse_altitude`); the runtime read the barometer only for rides (E211) and L145's
check (E232), so ``run`` on a hike read its integrated foot height (trial s51t1: +17 % altitude). The holder keeps the
pushed barometer in E106's :class:`~pdrlearn.kernels.barometer.LiveAltitude` (W89's centred mean, B188's check) and
the emitted rows until the barometer was pushed far enough past a row's end for its offline altitude (the window's
right half past the first sample at or after the end), then runs the same filter
(:class:`~pdrlearn.kernels.barometer.AltitudeFusion`) on it. A released row's ``dz_m`` is its fused height change and
its ``z`` the foot's plus the fused heights' difference so far: the tracker's own position keeps the foot's height.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from pdrlearn.errors import DataError


class FusedRows:
    """The pushed barometer ``name`` (s, hPa) and the rows waiting for it: :meth:`push` the barometer's samples,
    :meth:`rows` the emitted rows (returns those released, in order, fused). ``end_s``: the barometer stream's
    declared end (a recording's: rows after it need not wait); ``wait_s``: a row is released anyway once the other
    streams are this far past its end plus the window (a barometer that stopped; the thesis' 2 s delay)."""

    def __init__(self, name: str, *, end_s: float | None = None, wait_s: float = 2.0):
        from pdrlearn.kernels.barometer import AltitudeFusion, LiveAltitude

        self.name = name
        self.end_s = math.inf if end_s is None else float(end_s)
        self.wait_s = float(wait_s)
        self._alt = LiveAltitude()
        self._kf = AltitudeFusion()
        self._held: list = []
        self._started = False
        self.shift_m = 0.0  # the fused heights less the foot's, so far (m)
        self.foot_change_m = 0.0  # decision L154's info: the foot's own altitude change over the rows released
        self.n_fused = 0  # rows fused (a row without a usable barometer keeps its own height)

    def push(self, t, values) -> tuple | None:
        """Hold barometer samples; B188's finding the first time they make the barometer implausible, else None."""
        t = np.asarray(t, dtype=float).reshape(-1)
        v = np.asarray(values, dtype=float).reshape(len(t), -1)[:, 0]
        held = self._alt.times
        if held.size and len(t) and t[0] <= held[-1]:  # decision E356: a resumed tracker re-pushes samples held
            keep = t > held[-1]
            t, v = t[keep], v[keep]
        if not len(t):
            return None
        return self._alt.push(t, v)

    def state(self, row) -> dict:
        """Decision E356: what :meth:`restore` needs to go on as this holder; ``row`` turns a held row into plain
        numbers (the restart state is JSON)."""
        return {"barometer": self._alt.state(), "filter": self._kf.state(), "held": [row(r) for r in self._held],
                "started": self._started, "shift_m": self.shift_m, "foot_change_m": self.foot_change_m,
                "n_fused": self.n_fused}

    def restore(self, state: dict, row) -> None:
        """Decision E356: go on from :meth:`state` (``row``: a held row from its plain numbers)."""
        from pdrlearn.kernels.barometer import LiveAltitude

        self._alt = LiveAltitude.from_state(state["barometer"])
        self._kf.set_state(state["filter"])
        self._held = [row(r) for r in state["held"]]
        self._started = bool(state["started"])
        self.shift_m, self.foot_change_m = float(state["shift_m"]), float(state["foot_change_m"])
        self.n_fused = int(state["n_fused"])

    def _ready(self, ts: float, latest: float) -> bool:
        t = self._alt.times
        last = float(t[-1]) if t.size else -math.inf
        if last >= self.end_s or ts + self._alt.window_s <= latest - self.wait_s:
            return True
        j = int(np.searchsorted(t, ts, side="left"))  # W89: the first sample at or after ts, and its window
        return j < t.size and last >= float(t[j]) + 0.5 * self._alt.window_s

    def rows(self, steps: list, latest: float, final: bool = False) -> list:
        """Hold ``steps`` (emitted rows, in order) behind the ones held; release those whose barometric altitude is
        known (``latest``: the newest pushed sample of any stream, s; ``final``: all, on the samples pushed)."""
        self._held += steps
        out = []
        while self._held and (final or self._ready(self._held[0].end_s, latest)):
            out.append(self._fuse(self._held.pop(0)))
        if out:
            self._alt.trim(self._held[0].start_s if self._held else out[-1].end_s)
        return out

    def _fuse(self, st):
        foot = float(np.nan_to_num(st.dz_m))
        self.foot_change_m += foot
        if not self._started and self._alt.times.size:
            self._alt.set_origin(st.start_s)  # the first row's start, as fuse_altitude's relative_altitude
            b0 = self._alt.at(st.start_s)
            if b0 is not None:
                self._kf.start(st.start_s, b0)
                self._started = True
        b = self._alt.at(st.end_s) if self._started else None
        if b is not None:
            fused = self._kf.stride(foot, st.end_s, b)
            self.shift_m += fused - foot
            st.dz_m = fused
            self.n_fused += 1
        st.z = st.z + self.shift_m
        return st


def check_altitude(altitude: str, where: str) -> str:
    """Decision E339's ``--altitude`` value (decision E357: ``pdrlearn run``'s and ``python -m pdrlearn.runtime``'s one
    check): one of :data:`~pdrlearn.kernels.barometer.ALTITUDES`, else one line naming ``where`` (the command)."""
    from pdrlearn.kernels.barometer import ALTITUDES

    if altitude not in ALTITUDES:
        raise DataError(f"{where}: --altitude {altitude!r} is not one of {', '.join(ALTITUDES)} (foot: the strides' "
                        "own height; fused: with the waist barometer, decision E339)")
    return altitude


def replay_altitude(altitude: str, units, given: str | None, where: str, name: str) -> str:
    """Decision E339 (amended while measuring; E357: shared by ``pdrlearn run`` and ``python -m pdrlearn.runtime``): the
    altitude a replay of the session ``name`` tracks with the body ``units`` it tracks: ``"fused"`` needs the waist
    unit (its barometer); a ``--units`` (``given``) that leaves it out is refused in one line, a session without the
    waist unit keeps the foot's altitude with L154's line (as ``track --altitude fused``)."""
    from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER

    if altitude != "fused" or "waist" in units:
        return altitude
    if given is not None:
        raise DataError(f"{where}: --altitude fused reads the waist barometer (wBarometer.csv), which --units {given} "
                        "leaves out: add waist to --units (--units foot,waist) or drop --altitude")
    logging.getLogger("pdrlearn.cli").warning("%s: %s", name, FUSED_WITHOUT_BAROMETER)
    return "foot"
