"""Decision E303: the live Tracker's clipping (B77 / B311, or B456 at a declared full scale) and stuck-axis (B455)
checks, numpy only, on consecutive blocks of :data:`~pdrlearn.kernels.frozen_foot.LIVE_BLOCK_S` of each IMU stream's
own time (B213's 10 s blocks): the same kernel, :mod:`pdrlearn.kernels.clipping`, as ``info`` / ``track`` / ``run``.

One line per stream for clipping (the first block that clips: its count, share and level, the range to buy) and one
per stream and axis for a stuck axis, once :data:`~pdrlearn.kernels.clipping.STUCK_MIN_RUNS` stuck runs are counted
over the blocks so far. A block is judged when the stream has a sample at or after its end, and at :meth:`ClipWatch.
flush` on what it holds; a run that spans two blocks is judged in each part (a stuck run cut under
:data:`~pdrlearn.kernels.clipping.STUCK_S` is not counted). Memory: one block per stream; none for a stream whose
lines are all said.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.kernels.clipping import (
    FULL_SCALE_KEY,
    MOVING_RAD_S,
    STUCK_MIN_RUNS,
    clipped_axes,
    parse_full_scale,
    saturation_warning,
    stuck_message,
    stuck_runs,
)
from pdrlearn.kernels.frozen_foot import LIVE_BLOCK_S

#: the streams watched and the kind each is judged as (the Tracker's IMUs)
CLIP_WATCHED = {"fAccelerometer": "accelerometer", "fGyroscope": "gyroscope", "wAccelerometer": "accelerometer",
                "wGyroscope": "gyroscope"}
AXES = ("x", "y", "z")


def full_scales(declared, where: str = "Tracker") -> dict[str, float]:
    """Decision B456: a ``full_scale`` mapping (stream name -> ``"4 g"``, ``"500 deg/s"``, as meta.json's) in SI units;
    a one-line :class:`DataError` naming ``where`` for anything else."""
    if declared is None:
        return {}
    if not isinstance(declared, dict):
        raise DataError(f"{where}: {FULL_SCALE_KEY}={declared!r}: give a dict of sensor name -> range, e.g. "
                        "{'fAccelerometer': '4 g', 'fGyroscope': '500 deg/s'} (decision B456)")
    out = {}
    for name, text in declared.items():
        if name not in CLIP_WATCHED:
            raise DataError(f"{where}: {FULL_SCALE_KEY}: {name!r} is no accelerometer or gyroscope stream; use one of "
                            + ", ".join(CLIP_WATCHED) + " (decision B456)")
        try:
            out[name] = parse_full_scale(text, CLIP_WATCHED[name])
        except ValueError as exc:
            raise DataError(f"{where}: {FULL_SCALE_KEY}.{name}: {exc} (decision B456)") from None
    return out


def take_before(items: list, end: float) -> tuple[list, np.ndarray, np.ndarray]:
    """The samples of a watch's pushed ``items`` (``(t, values)`` arrays, or one ``(t, list)`` sample on Python floats)
    before ``end``: ``(the items kept, t, values)`` (decisions B213, E303)."""
    ts, vs, keep, one_t, one_v = [], [], [], [], []
    for item in items:
        t, v = item
        if isinstance(t, float):  # the one-sample path's (t, list of floats)
            if t < end:
                one_t.append(t)
                one_v.append(v)
            else:
                keep.append(item)
            continue
        if one_t:
            ts.append(np.array(one_t))
            vs.append(np.array(one_v, dtype=float).reshape(len(one_t), -1))
            one_t, one_v = [], []
        n = int(np.searchsorted(t, end, side="left"))
        if n:
            ts.append(np.asarray(t[:n], dtype=float))
            vs.append(np.asarray(v[:n], dtype=float).reshape(n, -1))
        if n < len(t):
            keep.append((t[n:], v[n:]))
    if one_t:
        ts.append(np.array(one_t))
        vs.append(np.array(one_v, dtype=float).reshape(len(one_t), -1))
    if not ts:
        return keep, np.zeros(0), np.zeros((0, 1))
    return keep, np.concatenate(ts), np.concatenate(vs)


class ClipWatch:
    """Decision E303: B77 / B311 / B456 clipping and B455 stuck axes on each watched stream's blocks."""

    def __init__(self, used, full_scale=None, *, waist: bool = True, block_s: float = LIVE_BLOCK_S):
        self.block_s = float(block_s)
        self.scales = full_scales(full_scale)
        self.waist = bool(waist)  # decision L530: the foot gyroscope's line names the heading the waist gives
        self.items: dict[str, list] = {n: [] for n in CLIP_WATCHED if n in set(used)}
        self.start: dict[str, float] = {}
        self.k: dict[str, int] = dict.fromkeys(self.items, 0)
        self.clip_said: set[str] = set()
        self.runs: dict[tuple[str, int], list] = {}  # (stream, axis) -> [(first time s, length), ...]
        self.stuck_said: set[tuple[str, int]] = set()
        self.dt: dict[str, float] = {}

    def push(self, arrays: dict, fast: dict | None = None) -> list[str]:
        """One push (``arrays`` name -> ``(t, values)``, ``fast`` name -> one ``(t, values)`` sample, as
        :class:`~pdrlearn.runtime.guard.FrozenFootWatch`); the lines of the blocks it closes."""
        out: list[str] = []
        fast = fast or {}
        for name in list(self.items):
            f = fast.get(name)
            if f is not None:
                item, newest = f, f[0]
            elif name in arrays and len(arrays[name][0]):
                item, newest = arrays[name], float(arrays[name][0][-1])
            else:
                continue
            self.items[name].append(item)
            if name not in self.start:
                t0 = item[0]
                self.start[name] = float(t0 if isinstance(t0, float) else t0[0])
            while newest >= self.start[name] + (self.k[name] + 1) * self.block_s and name in self.items:
                out += self._close(name)
        return out

    def flush(self) -> list[str]:
        """The end of the streams: each open block judged on what it holds."""
        out: list[str] = []
        for name in list(self.items):
            if name in self.start:
                out += self._close(name, final=True)
        return out

    def _close(self, name: str, final: bool = False) -> list[str]:
        begin = self.start[name] + self.k[name] * self.block_s
        end = math.inf if final else begin + self.block_s
        self.items[name], t, v = take_before(self.items[name], end)
        self.k[name] += 1
        lines = self._judge(name, t, v, begin) if len(t) >= 4 and v.shape[1] == 3 else []
        if name in self.clip_said and all((name, j) in self.stuck_said for j in range(3)):
            del self.items[name]  # everything said: no more memory for it
        return lines

    def _judge(self, name: str, t: np.ndarray, v: np.ndarray, begin: float) -> list[str]:
        kind, lines = CLIP_WATCHED[name], []
        scale = self.scales.get(name)
        dt = self.dt.setdefault(name, float(np.median(np.diff(t))))
        if name not in self.clip_said:
            hit, top = clipped_axes(v, kind, scale)
            n = int(hit.any(axis=1).sum()) if hit.size else 0
            if n:
                self.clip_said.add(name)
                moving = (int(np.count_nonzero(np.linalg.norm(v, axis=1) >= MOVING_RAD_S)) if kind == "gyroscope"
                          else None)
                where = (f"stream {name} (the {self.block_s:g} s block from {begin:.1f} to {float(t[-1]):.1f} s, "
                         "judged live, decision E303)")
                lines.append(str(saturation_warning(where, kind, n, len(t), top,
                                                    "waist" if name.startswith("w") else "foot", moving=moving,
                                                    waist=self.waist, declared=scale is not None)))
        for j, runs in enumerate(stuck_runs(v, dt, kind, scale)):
            key = (name, j)
            if key in self.stuck_said or not runs:
                continue
            self.runs.setdefault(key, []).extend((float(t[a]), n) for a, n in runs)
            have = self.runs[key]
            if len(have) >= STUCK_MIN_RUNS:
                self.stuck_said.add(key)
                lines.append(stuck_message(f"stream {name}", AXES[j], have, dt, have[0][0]))
                del self.runs[key]
        return lines
