"""Decision W625: a waist gap inside walking bridged at the pace of the steps either side (numpy only, so the live
trackers can share it with offline ``track``)."""

from __future__ import annotations

import numpy as np


def pace_bridge(start_s, end_s, has_next, length_m, gaps, *, max_gap_s: float = 5.0, n_side: int = 3,
                max_edge_s: float = 1.5, cadence_ratio: float = 1.25) -> tuple[np.ndarray, np.ndarray]:
    """Decision W625: ``(bridged_m, bridged_end_s)`` (n,) for a steps table cut at ``gaps`` (B11: the step across a
    gap is a closing contact, ``has_next`` False). A gap ``(a, b)`` (s) of at most ``max_gap_s`` is bridged at the row
    ``i`` of the last contact before it when ``n_side`` steps of one walking sequence (``has_next``, each ending at the
    next row's start) come before row ``i`` and after the first contact after the gap (row ``i + 1``), row ``i``
    starts within ``max_edge_s`` (W16's longest step) of ``a`` and row ``i + 1`` within ``max_edge_s`` of ``b``, and
    the median step time after is within a factor ``cadence_ratio`` of the one before. Its bridged metres are the
    mean pace of those ``2 n_side`` steps (their lengths' sum over their durations' sum) x (row ``i + 1``'s start -
    row ``i``'s), ``bridged_end_s`` that start; 0 and NaN at every other row."""
    st, en = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    nxt, length = np.asarray(has_next, dtype=bool), np.asarray(length_m, dtype=float)
    n = len(st)
    out, out_end = np.zeros(n), np.full(n, np.nan)
    chained = nxt.copy()  # a step of a walking sequence: it ends where the next row starts
    chained[:-1] &= np.isclose(en[:-1], st[1:])
    chained[-1:] = False
    for a, b in sorted(ab for g in gaps.values() for ab in g):
        if not 0.0 < b - a <= max_gap_s:
            continue
        i = int(np.searchsorted(st, a)) - 1  # the last contact before the gap
        if i < n_side or i + 1 + n_side > n or nxt[i]:
            continue
        if a - st[i] > max_edge_s or st[i + 1] - b > max_edge_s or st[i + 1] < b:
            continue
        before, after = np.arange(i - n_side, i), np.arange(i + 1, i + 1 + n_side)
        side = np.r_[before, after]
        if not chained[side].all() or not np.isfinite(length[side]).all():
            continue
        dur = en[side] - st[side]
        t0, t1 = float(np.median(dur[:n_side])), float(np.median(dur[n_side:]))
        if not (t0 > 0 and t1 > 0 and max(t0, t1) / min(t0, t1) <= cadence_ratio):
            continue
        out[i] = float(np.abs(length[side]).sum() / dur.sum()) * (st[i + 1] - st[i])
        out_end[i] = st[i + 1]
    return out, out_end
