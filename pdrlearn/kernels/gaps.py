"""Sensor-stream gaps (decision B11): the warning lines and the cut of a contact table at the gaps, numpy only
(:mod:`pdrlearn.track.gaps` re-exports them; the lean runtime's waist tracker uses them, decision W92)."""

from __future__ import annotations

import math

import numpy as np

#: Gaps longer than this (s) are reported and end a walking sequence: the shortest steps last ~0.4 s
#: and 1 s of missing data can hide one or two steps (brief: "gaps longer than e.g. 1 s").
MIN_GAP_S = 1.0


#: decision B149: where dropped samples come from, for every drop warning: a sensor's radio link, or a phone app
#: (which logs from a shared, loaded CPU and drops or batches samples: session 22's phone trial, 1 % drops)
DROPS_CAUSE = "check the Bluetooth link, or a phone app's sampling (its rate setting, the phone's load)"
#: decision L77: the B64 warning of the streamed paths (``pdrlearn run``, ``track --streaming``), which integrate
#: each stride on its timestamps (E36) and keep the distance (L78: median |distance error| 0.370 % at 1 %, 0.691 %
#: at 3 % drops, 0.289 % clean); an interval over 0.25 s still counts as one sample interval there (E36)
STREAMED_DROPS = ("%s: %s have %s interval(s) of dropped samples of 1 s or less (longest %.3f s): integrated on "
                  "the timestamps here, so they cost little distance (decisions B64, L78; an interval over 0.25 s "
                  "counts as one sample interval, E36); if they are many, " + DROPS_CAUSE)


def waist_gap_turn(cycle: bool = True) -> str:
    """Decisions E354 / E361 / E364 / E365 (review s53r1 F4): how the streamed trackers (the live ``Tracker``, ``track
    --streaming``) turn across the waist gyroscope's own gap inside L91's bridge (every unit silent), a clause that
    follows "across its own gap": ``cycle`` (``bridge_cycle``, the default) the strides either side's mean rates,
    re-anchored to the waist compass; False: E299's straight line between its samples around it."""
    if not cycle:
        return "a straight line between its samples around it, so a turn inside the gap is not measured (W389)"
    return ("the mean rates of the strides either side (decisions E354, E364), re-anchored to the waist compass where "
            "it reads the Earth's field (E361, E362): a turn on the spot inside the gap is lost")


#: decision W389: a waist gyroscope interval of dropped samples at least this long (s) gets :data:`GAP_TURN`
#: (W389's measurement of W34's line: 0.3 s intervals moved no heading, 0.5-0.9 s ones up to 25 deg)
GAP_TURN_S = 0.4
#: decision W389: what such an interval costs the waist heading (W34 bridges the gyroscope with a straight line)
GAP_TURN = ("; the waist gyroscope is a straight line across each one, which makes up or loses part of a turn: "
            "0.5-0.9 s intervals while walking moved the heading by up to 25 deg on simulated walks (decision "
            "W389) - check the path's heading after the longest one")


def gap_turn(left: list[tuple[str, int, float]]) -> str:
    """Decision W389: :data:`GAP_TURN` when the waist gyroscope has an interval of at least :data:`GAP_TURN_S`
    among ``left`` (name, count, longest), else an empty string."""
    return GAP_TURN if any(n == "wGyroscope" and m >= GAP_TURN_S for n, _, m in left) else ""


def per_stream(left: list[tuple[str, int, float]]) -> str:
    """The count of :data:`STREAMED_DROPS`: one number when every stream has as many intervals, else each
    stream's, in the order named (as the offline warning counts them)."""
    counts = [k for _, k, _ in left]
    return str(counts[0]) if len(set(counts)) == 1 else "/".join(map(str, counts)) + " (in that order)"


def streamed_drops_line(left: list[tuple[str, int, float]]) -> str:
    """Decisions L77 / E230: :data:`STREAMED_DROPS`' line (without its session prefix, with W389's :func:`gap_turn`)
    for ``left``, the streams' ``(name, intervals of dropped samples, longest s)``: ``pdrlearn run`` says it when it
    reads a session, the live :class:`~pdrlearn.runtime.Tracker` at ``flush`` from what was pushed (one mechanism)."""
    return (STREAMED_DROPS.removeprefix("%s: ") % (", ".join(n for n, _, _ in left), per_stream(left),
                                                   max(m for _, _, m in left))) + gap_turn(left)


def grouped_gaps(gaps: dict[str, list[tuple[float, float]]]) -> list[tuple[list[str], list[tuple[float, float]]]]:
    """``(stream names, gaps)`` with the streams that share the same gaps (to 0.1 s) in one entry, in first-seen
    order: one gap in every stream of a unit (a dropped radio link) is one line, not one per stream (B34)."""
    groups: dict[tuple, tuple[list[str], list[tuple[float, float]]]] = {}
    for name, g in gaps.items():
        key = tuple((round(a, 1), round(b, 1)) for a, b in g)
        groups.setdefault(key, ([], g))[0].append(name)
    return list(groups.values())


def gap_lines(gaps: dict[str, list[tuple[float, float]]], consequence: str) -> list[str]:
    """One line per group of streams with the same gaps (:func:`grouped_gaps`): the streams, the count, the
    longest gap and where, then ``consequence``."""
    out = []
    for names, g in grouped_gaps(gaps):
        t0, t1 = max(g, key=lambda ab: ab[1] - ab[0])
        out.append(f"{', '.join(names)} {'has' if len(names) == 1 else 'have'} {len(g)} gap(s) longer than "
                   f"{MIN_GAP_S:g} s (longest {t1 - t0:.1f} s at {t0:.1f} s); {consequence}")
    return out


def gap_warnings(gaps: dict[str, list[tuple[float, float]]],
                 consequence: str = "no displacement is counted inside them", *,
                 fix: str = "re-record or trim the session") -> list[str]:
    """One warning per group of streams with the same gaps: the count, the longest gap and ``consequence``
    (what the pipeline does about them; decision B34), then ``fix`` (decision E349: a live tracker's own, where a
    stream cannot be re-recorded)."""
    return gap_lines(gaps, f"{consequence} - {fix}")


def cut_contacts_at_gaps(start_s: np.ndarray, end_s: np.ndarray, has_next: np.ndarray,
                         gaps: dict[str, list[tuple[float, float]]]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`pdrlearn.track.gaps.cut_steps_at_gaps` on arrays: ``(keep, spans)``: ``keep`` (n,) the contacts
    outside every gap; ``spans`` (n_kept,) the kept steps (``has_next``) that span a gap before the next kept
    contact, which become closing contacts (``end_s = start_s``, ``has_next`` False)."""
    st = np.asarray(start_s, dtype=float)
    iv = np.array([ab for g in gaps.values() for ab in g], dtype=float).reshape(-1, 2)
    inside = ((st[:, None] > iv[None, :, 0]) & (st[:, None] < iv[None, :, 1])).any(axis=1)
    keep = ~inside
    st, en = st[keep], np.asarray(end_s, dtype=float)[keep]
    nxt = np.append(st[1:], np.inf)
    spans = ((st[:, None] < iv[None, :, 1]) & (np.maximum(en, nxt)[:, None] > iv[None, :, 0])).any(axis=1)
    return keep, spans & np.asarray(has_next, dtype=bool)[keep]


def neighbour_heights(dz: np.ndarray, across: np.ndarray, skip: np.ndarray) -> np.ndarray:
    """Decision L160: ``dz`` with each ``across`` stride's value replaced by the mean of the nearest strides before
    and after it that are neither ``across`` nor ``skip`` (one of them at an end; 0 when there is none). A new
    array. The streamed form (L167, one stride at a time) is :func:`drop_stride_disp`."""
    out = np.array(dz, dtype=np.float64)
    good = np.flatnonzero(~across & ~skip)
    for i in np.flatnonzero(across):
        k = np.searchsorted(good, i)
        near = [out[good[j]] for j in (k - 1, k) if 0 <= j < good.size]
        out[i] = float(np.mean(near)) if near else 0.0
    return out


#: decision L167: the most strides one across dropped samples stands for (a stance lost in the burst joins two)
DROP_SPAN_MAX = 2.0


def drop_stride_disp(disp, duration_s: float, ref, neighbour: bool = False) -> tuple[float, float, float]:
    """Decision L167 (L160's rule streamed: only the neighbour before is known when a stride ends): the step-frame
    displacement ``(dx, dy, dz)`` (m) of a stride of ``duration_s`` (s) across dropped foot samples. ``ref``:
    ``((dx, dy, dz), duration_s)`` of the nearest stride before it that crossed no drop, or None (then ``disp``
    itself). Its own direction, ``ref``'s horizontal length x the ratio of the durations (at most
    :data:`DROP_SPAN_MAX`), ``ref``'s height change. ``neighbour``: whether L167's rule applies (decision E101: the
    callers' ``drop_neighbour`` keyword; L167 not adopted, so False by default, decision L549: no module switch);
    False: ``disp`` itself."""
    dx, dy, dz = (float(v) for v in disp)
    if ref is None or not neighbour:
        return dx, dy, dz
    (rx, ry, rz), rdur = ref
    length = math.hypot(float(rx), float(ry)) * min(float(duration_s) / float(rdur), DROP_SPAN_MAX)
    own = math.hypot(dx, dy)
    if own > 0.0:
        return dx * length / own, dy * length / own, float(rz)
    return length, 0.0, float(rz)
