"""Sensor-stream gaps in the tracking pipelines (decision B11, docs/decisions/bad-input.md).

A pipeline must not invent displacement across a gap in a stream it uses: :func:`gap_warnings` names
the gaps longer than ``min_gap_s`` for ``TrackResult.info["warnings"]``, and :func:`cut_steps_at_gaps`
ends the walking sequence at such a gap (no step spans it, no contact inside it counts).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.io.session import Session
from pdrlearn.kernels.gaps import (  # noqa: F401  (W92; L160 / L167: the drop strides' rules)
    MIN_GAP_S,
    drop_stride_disp,
    gap_lines,
    gap_warnings,
    grouped_gaps,
    neighbour_heights,
    waist_gap_turn,
)

#: the foot streams whose gaps lose the foot's turn (decisions L90 / L91): the gyroscope, and the accelerometer
#: whose clock the offline foot integrates the gyroscope on
FOOT_IMU = ("fAccelerometer", "fGyroscope")


def overlaps_any(a: float, b: float, gaps: dict[str, list[tuple[float, float]]]) -> bool:
    """Whether ``a``..``b`` (s) overlaps one of ``gaps`` (the test of :func:`overlaps_gaps`, one interval)."""
    return any(g0 < b and g1 > a for g in gaps.values() for g0, g1 in g)


def gap_heading_clause(foot_gaps: dict[str, list[tuple[float, float]]], how: str,
                       waist_gaps: list[tuple[float, float]] = (), cycle: bool = True) -> str:
    """Decision L92: what a foot gap does to the heading, for the gap warning ("" when no foot accelerometer or
    gyroscope gap). ``how``: "bridged" (the waist gyroscope's turn, L91), "fused" (each stretch aligned to the
    waist heading on its own, L90), "waist" (the waist heading, not touched by a foot gap) or "none" (the turn
    is unknown, taken as 0, L90). Decision E365 (review s53r1 F4): "bridged" with ``waist_gaps`` (the waist
    gyroscope's own gaps, s) overlapping a foot gap adds what is done across them (:func:`waist_gap_turn`,
    ``cycle``: E354's ``bridge_cycle``)."""
    if not any(foot_gaps.get(n) for n in FOOT_IMU):
        return ""
    silent = any(a < y and b > x for n in FOOT_IMU for x, y in foot_gaps.get(n, ()) for a, b in waist_gaps)
    if how == "bridged" and silent:
        return "; the turn inside them is the waist gyroscope's (L91), across its own gap by " + waist_gap_turn(cycle)
    return {"bridged": "; the turn inside them is the waist gyroscope's (L91)",
            "fused": "; the foot's turn inside them is unknown: the heading of each stretch between them is aligned "
                     "to the waist heading on its own (L90)",
            "waist": "; the heading is the waist unit's, which they do not touch",
            "none": "; the turn inside them is unknown (taken as 0, L90): the heading after them is uncertain"}[how]


#: decision B231: what a waist gap (``wAccelerometer`` / ``wGyroscope``, over 1 s) does, by what heads the strides
#: (offline ``heading``: fused / waist / foot; streamed heading auto: "streamed", asked ``waist-gyro``)
WAIST_GAP_WORDS = {
    "fused": "the strides go on and their lengths (the foot's) are counted; the heading inside them is the foot's "
             "turn, fused with a waist heading that takes the gap as a rest (W34; L90's fusion): uncertain after a "
             "long gap",
    "waist": "the strides go on and their lengths (the foot's) are counted; the waist heading takes the gap as a "
             "rest (W34): a turn inside them is lost",
    "foot": "the strides go on and their lengths (the foot's) are counted; the foot heads them, the waist gap does "
            "not touch the heading",
    "streamed": "the strides go on and their lengths (the foot's) are counted; a stride across them turns with the "
                "foot's gyroscope (E114), its classes read the waist interpolated across the gap",
    "waist-gyro": "the strides go on and their lengths (the foot's) are counted; the waist gyroscope (heading "
                  "waist-gyro) is interpolated across them: the heading of the strides across them is unreliable",
}


def unit_gap_warnings(session: Session, foot_gaps: dict[str, list[tuple[float, float]]], foot_words: str,
                      waist_how: str) -> list[str]:
    """Decision B231: the gap lines of a two-unit track, per unit: the foot's gaps (``foot_gaps``) with
    ``foot_words``, the waist's (accelerometer and gyroscope, over 1 s) with :data:`WAIST_GAP_WORDS` ``[waist_how]``
    (a waist gap moves nothing to 0 m; before, it was told "no displacement is counted inside them"). Streams with
    the same gaps stay one line (B34): a line naming a foot stream has the foot's words (its stride is 0 m)."""
    out = []
    for names, g in grouped_gaps({**foot_gaps, **long_gaps(session, ("wAccelerometer", "wGyroscope"))}):
        words = foot_words if any(n in foot_gaps for n in names) else WAIST_GAP_WORDS[waist_how]
        out += gap_warnings(dict.fromkeys(names, g), words)
    return out


def long_gaps(session: Session, names: tuple[str, ...], *, min_gap_s: float = MIN_GAP_S,
              max_gap_s: float = np.inf) -> dict[str, list[tuple[float, float]]]:
    """Stream name -> ``[(start_s, end_s), ...]`` of its gaps longer than ``min_gap_s`` (s) and at most
    ``max_gap_s`` (s; decision L160 asks for the short ones)."""
    out = {}
    for name in names:
        s = session.streams.get(name)
        if s is None:
            continue
        g = [(gap.start_s, gap.start_s + gap.duration_s) for gap in s.gaps()
             if min_gap_s < gap.duration_s <= max_gap_s]
        if g:
            out[name] = g
    return out


def cut_steps_at_gaps(steps: pd.DataFrame, gaps: dict[str, list[tuple[float, float]]]) -> pd.DataFrame:
    """Drop the contacts inside a gap and end each walking sequence before a gap: a step
    (``start_s``..``end_s`` with ``has_next``) spanning a gap becomes a closing contact (``end_s =
    start_s``, ``has_next = False``)."""
    if not gaps or len(steps) == 0:
        return steps
    from pdrlearn.kernels.gaps import cut_contacts_at_gaps

    keep, spans = cut_contacts_at_gaps(steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float),
                                       steps["has_next"].to_numpy(bool), gaps)
    out = steps.loc[keep].copy()
    st = out["start_s"].to_numpy(float)
    out.loc[out.index[spans], "end_s"] = st[spans]
    out.loc[out.index[spans], "has_next"] = False
    out.attrs = dict(steps.attrs)
    return out.reset_index(drop=True)


def overlaps_gaps(steps: pd.DataFrame, gaps: dict[str, list[tuple[float, float]]]) -> np.ndarray:
    """(n_rows,) bool: the row's ``start_s``..``end_s`` overlaps one of ``gaps``."""
    st, en = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    if not gaps or len(steps) == 0:
        return np.zeros(len(st), dtype=bool)
    iv = np.array([ab for g in gaps.values() for ab in g])
    return ((st[:, None] < iv[None, :, 1]) & (en[:, None] > iv[None, :, 0])).any(axis=1)


def drop_steps_across_gaps(steps: pd.DataFrame, gaps: dict[str, list[tuple[float, float]]]) -> pd.DataFrame:
    """Rows of a strides table (``start_s``..``end_s``) that overlap no gap (index reset)."""
    if not gaps or len(steps) == 0:
        return steps
    out = steps.loc[~overlaps_gaps(steps, gaps)].reset_index(drop=True)
    out.attrs = dict(steps.attrs)
    return out


def longest_gap_in(start_s, end_s, gaps: dict[str, list[tuple[float, float]]]) -> np.ndarray:
    """(n_rows,) s: the longest of ``gaps`` overlapping each ``start_s``..``end_s`` (0.0: none), as the
    runtime's ``Step.gap_s`` (decision E30/E37; offline decision L67)."""
    st, en = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    if not gaps or not len(st):
        return np.zeros(len(st))
    iv = np.array([ab for g in gaps.values() for ab in g])
    over = (st[:, None] < iv[None, :, 1]) & (en[:, None] > iv[None, :, 0])
    return np.where(over, (iv[:, 1] - iv[:, 0])[None, :], 0.0).max(axis=1)


def gap_rows(steps: pd.DataFrame, gaps: dict[str, list[tuple[float, float]]]) -> pd.DataFrame:
    """Decision L67: one row (``start_s``, ``end_s``, ``gap_s``, ``before``) for each stretch between two
    consecutive strides of ``steps`` that one of ``gaps`` overlaps: the strides dropped there (a stride across
    a foot-stream gap is not integrated) become one row of 0 m, as the runtime's Step across a gap (E30).
    ``before``: the index of the stride the row goes before."""
    cols = ["start_s", "end_s", "gap_s", "before"]
    if not gaps or len(steps) < 2:
        return pd.DataFrame(columns=cols)
    a = steps["end_s"].to_numpy(float)[:-1]
    b = steps["start_s"].to_numpy(float)[1:]
    dur = longest_gap_in(a, b, gaps)
    k = np.flatnonzero((b > a) & (dur > 0))
    return pd.DataFrame({"start_s": a[k], "end_s": b[k], "gap_s": dur[k], "before": k + 1})


def drop_strides(session: Session, strides: pd.DataFrame, skip: np.ndarray, *, min_gap_s: float = 0.0) -> np.ndarray:
    """Decisions L160 / L167: (n_rows,) bool, the strides of ``strides`` (``start_s``..``end_s``) overlapping an
    interval of dropped foot-IMU samples longer than ``min_gap_s`` (s) and at most B11's :data:`MIN_GAP_S`, except
    the ``skip`` ones (a stride across a B11 gap, which moves 0 m)."""
    return overlaps_gaps(strides, long_gaps(session, FOOT_IMU, min_gap_s=min_gap_s, max_gap_s=MIN_GAP_S)) & ~skip


def drop_stride_warning(n: int, streamed: bool = False) -> str:
    """One line for the ``n`` strides across dropped foot samples: what offline (decision L160) or a streamed path
    (L167) gives them instead of their own integration."""
    if streamed:
        return (f"{n} stride(s) across dropped foot samples over 0.25 s: each takes the length and height change of "
                "the stride before it, as the gap clock loses part of its swing (decision L167)")
    return (f"{n} stride(s) across dropped foot samples: each takes the height change of its neighbours, as the "
            "fixed-interval integration loses part of its swing (decision L160)")
