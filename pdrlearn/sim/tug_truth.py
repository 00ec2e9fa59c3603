"""The true TUG phases of a simulated seated Timed-Up-and-Go (decision W294, docs/decisions/waist.md): what
:func:`pdrlearn.waist.tug_phases.tug_phases` is scored against, from the simulator's own records - its transfers
(``extras["transfers"]``), initial contacts (``extras["ics"]``) and the waist's true heading (``trajectory``)."""

from __future__ import annotations

import numpy as np

from pdrlearn.sim.path import Turn
from pdrlearn.sim.route import parse_route


def turn_span_indices(trajectory, route: str) -> tuple[np.ndarray, np.ndarray, list[tuple[int, int]]]:
    """Decision L201 / L255's truth of each route turn (``parse_route``'s ``Turn`` items, in order): ``(t, hs,
    spans)``, the samples' times, the waist's true heading (deg, unwrapped, 1 s moving mean) and per turn the sample
    indices where it has gone 5 % / 95 % of the turn's route angle beyond the earlier turns' angles, searched from
    the previous turn's end (shared with ``experiments/turns_transfers.py``)."""
    t = trajectory["t"].to_numpy(float)
    h = np.degrees(np.unwrap(trajectory["heading_rad"].to_numpy(float)))
    w = max(int(round(1.0 / np.median(np.diff(t)))), 1)  # L201: the 1 s mean removes the walking sway
    hs = np.convolve(np.pad(h, (w // 2, w - 1 - w // 2), mode="edge"), np.ones(w) / w, mode="valid")
    base, k0, spans = hs[0], 0, []
    for seg in parse_route(route):
        if not isinstance(seg, Turn):
            continue
        a = float(np.degrees(seg.angle_rad))
        frac = (hs - base) / a
        i0 = k0 + int(np.argmax(frac[k0:] >= 0.05))
        i1 = i0 + int(np.argmax(frac[i0:] >= 0.95))
        spans.append((i0, i1))
        base, k0 = base + a, i1
    return t, hs, spans


def true_turn_spans(trajectory, route: str) -> list[tuple[float, float]]:
    """:func:`turn_span_indices`' spans as times (s)."""
    t, _, spans = turn_span_indices(trajectory, route)
    return [(float(t[i0]), float(t[i1])) for i0, i1 in spans]


def true_tug_phases(session, route: str) -> dict:
    """Decision W294: the true ``{phase: {start_s, end_s, duration_s} or None}`` of a simulated seated TUG
    (``simulate_path(..., sit_start_s=..., sit_end_s=...)`` of ``route``): sit-to-stand = the first transfer's
    ``rise_s`` to ``end_s``, stand-to-sit = the last one's ``start_s`` to ``seated_s``, turn / turn-to-sit = the
    first / last of :func:`true_turn_spans` (no turn-to-sit with one turn), walk out = the first true contact after
    the rise to the turn's start, walk back = the turn's end to the turn-to-sit's start (else the last true contact
    before the sit) - W293's boundaries on the simulator's records."""
    tr = session.extras["transfers"]
    return _segment_truth(session, tr.iloc[0], tr.iloc[-1], true_turn_spans(session.trajectory, route))


def _segment_truth(session, rise, sit, turns: list[tuple[float, float]]) -> dict:
    """W294's phases of one seat-to-seat segment: the simulator's transfers rows ``rise`` (its ``rise_s`` to
    ``end_s``) and ``sit`` (``start_s`` to ``seated_s``) and the segment's true turn spans ``turns``."""
    from pdrlearn.waist.tug_phases import phase_span

    up, seated = float(rise["end_s"]), float(sit["start_s"])
    ics = np.sort(session.extras["ics"]["ic_s"].to_numpy(float))
    ics = ics[(ics > up) & (ics < seated)]
    turn = turns[0] if turns else None
    to_sit = turns[-1] if len(turns) >= 2 else None
    return {"sit_to_stand": phase_span(float(rise["rise_s"]), up),
            "walk_out": phase_span(float(ics[0]) if ics.size else None, None if turn is None else turn[0]),
            "turn": None if turn is None else phase_span(*turn),
            "walk_back": (None if turn is None else
                          phase_span(turn[1], to_sit[0] if to_sit else (float(ics[-1]) if ics.size else None))),
            "turn_to_sit": None if to_sit is None else phase_span(*to_sit),
            "stand_to_sit": phase_span(seated, float(sit["seated_s"]))}


def trials_route(trial: str, n: int, sit_s: float = 10.0) -> str:
    """Decision W326: ``n`` TUG trials of route ``trial`` joined by ``sit:SIT_S`` (sit down, rest, rise: the trial
    finding's two-trial recording); simulate it with ``sit_start_s`` / ``sit_end_s`` so it starts and ends seated."""
    return f", sit:{sit_s:g}, ".join([trial] * n)


def true_trials(session, trial: str, n: int) -> list[dict]:
    """Decision W326: per trial of a :func:`trials_route` session (seated at both ends), ``{"start_s", "end_s",
    "tug_time_s", "phases"}``: transfers row k's ``rise_s`` to row k+1's ``seated_s`` (W183's TUG truth per trial) and
    :func:`true_tug_phases`' phases on that segment with the trial's own route turns."""
    tr = session.extras["transfers"]
    turns = true_turn_spans(session.trajectory, trials_route(trial, n))
    per = len(turns) // n
    out = []
    for k in range(n):
        rise, sit = tr.iloc[k], tr.iloc[k + 1]
        t0, t1 = float(rise["rise_s"]), float(sit["seated_s"])
        out.append({"start_s": t0, "end_s": t1, "tug_time_s": t1 - t0,
                    "phases": _segment_truth(session, rise, sit, turns[k * per:(k + 1) * per])})
    return out
