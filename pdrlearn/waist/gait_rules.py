"""Mobilise-D's gait definition applied to detected contacts: stride selection and walking-bout assembly
(decision W47: measured on the lower-back IC detector, not used by any pipeline).

The Mobilise-D pipeline (mobgap 1.2.0, ``src/mobgap/pipeline/_mobilised_pipeline.py``) turns its initial
contacts into strides within each gait sequence (``laterality/_utils.py: strides_list_from_ic_lr_list``: a
stride runs from a contact to the next contact of the same foot), keeps the strides that pass
``wba.StrideSelection`` and assembles the survivors into walking bouts with ``wba.WbAssembly``; only the
contacts of strides inside a bout are reported. The functions here apply the same rules to detected contacts:

- strides: within a walking sequence (consecutive contacts with a next one, the analogue of mobgap's gait
  sequence), stride ``k`` runs from contact ``k`` to contact ``k + 2``: the IC detector's sequences alternate
  sides (W20), so this is the next contact of the same foot (the INDIP stride lists are per foot and, where
  the feet alternate, the same chain: decision W47);
- a stride's length is the sum of its two steps' lengths (e.g. the pendulum's, as the pipeline sums them);
- stride selection (mobgap ``StrideSelection.PredefinedParameters.mobilised``): duration in (0.2, 3.0] s and
  length > 0.15 m; a missing (NaN) length fails, as mobgap's comparisons do;
- bout assembly (mobgap ``WbAssembly.PredefinedParameters.mobilised``): the selected strides in time order,
  a stride starting more than 3 s after the previous one's end starts a new bout (``MaxBreakCriteria(
  max_break_s=3)``, compared with ``<=``, ``remove_last_ic=False``); a bout is kept with at least 4 strides
  (``NStridesCriteria(min_strides=4, min_strides_left=3, min_strides_right=3)``: mobgap's ``check_include``
  returns on ``min_strides`` before it looks at the per-foot minima, so 4 strides of any feet is the rule it
  applies);
- a contact is kept if it starts or ends a stride of a kept bout (a contact of no stride -- a walking
  sequence of one or two contacts, the middle contact of three -- is in no bout, as in mobgap).

Pure functions of arrays; nothing is fitted.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

MIN_STRIDE_S = 0.2  # Mobilise-D stride selection, mobgap StrideSelection mobilised default (exclusive)
MAX_STRIDE_S = 3.0  # Mobilise-D stride selection, mobgap StrideSelection mobilised default (inclusive)
MIN_STRIDE_LENGTH_M = 0.15  # Mobilise-D stride selection, mobgap StrideSelection mobilised default (exclusive)
MIN_BOUT_STRIDES = 4  # Mobilise-D WB assembly, mobgap WbAssembly mobilised default NStridesCriteria(min_strides=4)
MAX_BREAK_S = 3.0  # Mobilise-D WB assembly, mobgap WbAssembly mobilised default MaxBreakCriteria(max_break_s=3)
#: contact times are sample times in float seconds: a difference within this of a limit is the limit (mobgap
#: compares whole samples / rate; 5.28 - 2.28 s is 3.0000000000000004 s, 528 - 228 samples at 100 Hz are 3 s)
TIME_EPS_S = 1e-9


def positional_strides(has_next: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(first, last)`` contact indices of every stride: contact ``k`` to ``k + 2`` inside one walking
    sequence (``has_next[k]`` and ``has_next[k + 1]``: no sequence break between them)."""
    hn = np.asarray(has_next, dtype=bool)
    if hn.size < 3:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int)
    k = np.flatnonzero(hn[:-2] & hn[1:-1])
    return k, k + 2


def select_strides(duration_s: np.ndarray, length_m: np.ndarray, *, min_s: float = MIN_STRIDE_S,
                   max_s: float = MAX_STRIDE_S, min_length_m: float = MIN_STRIDE_LENGTH_M) -> np.ndarray:
    """Mobilise-D stride selection: ``min_s < duration <= max_s`` and ``length > min_length_m`` (a NaN fails)."""
    d = np.asarray(duration_s, dtype=np.float64)
    length = np.asarray(length_m, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        return (d > min_s + TIME_EPS_S) & (d <= max_s + TIME_EPS_S) & (length > min_length_m)


def assemble_bouts(start_s: np.ndarray, end_s: np.ndarray, *, max_break_s: float = MAX_BREAK_S,
                   min_strides: int = MIN_BOUT_STRIDES) -> np.ndarray:
    """Bout number of each stride (time-ordered by start), -1 where its preliminary bout has fewer than
    ``min_strides`` strides. A stride starting more than ``max_break_s`` after the previous stride's end
    starts a new bout (mobgap ``MaxBreakCriteria``)."""
    s = np.asarray(start_s, dtype=np.float64)
    e = np.asarray(end_s, dtype=np.float64)
    if s.size == 0:
        return np.zeros(0, dtype=int)
    if np.any(np.diff(s) < 0):
        raise ValueError("assemble_bouts: strides must be ordered by start")
    new = np.concatenate([[True], (s[1:] - e[:-1]) > max_break_s + TIME_EPS_S])
    pre = np.cumsum(new) - 1
    sizes = np.bincount(pre)
    ok = sizes[pre] >= min_strides
    ids = np.full(s.size, -1, dtype=int)
    kept = np.unique(pre[ok])
    ids[ok] = np.searchsorted(kept, pre[ok])
    return ids


def gait_rule_mask(event_s: np.ndarray, has_next: np.ndarray, step_length_m: np.ndarray) -> np.ndarray:
    """Contacts that start or end a stride of a Mobilise-D walking bout (module docstring).

    Parameters
    ----------
    event_s : (n,) contact times (s), ascending
    has_next : (n,) the contact's step ends at the next contact (False: it closes a walking sequence)
    step_length_m : (n,) length of the step from each contact to the next (m; ignored where ``has_next`` is
        False)
    """
    t = np.asarray(event_s, dtype=np.float64)
    sl = np.asarray(step_length_m, dtype=np.float64)
    keep = np.zeros(t.size, dtype=bool)
    a, b = positional_strides(has_next)
    if a.size == 0:
        return keep
    ok = select_strides(t[b] - t[a], sl[a] + sl[a + 1])
    a, b = a[ok], b[ok]
    bout = assemble_bouts(t[a], t[b])
    keep[a[bout >= 0]] = True
    keep[b[bout >= 0]] = True
    return keep


def keep_contacts(steps: pd.DataFrame, keep: np.ndarray, *, max_step_s: float) -> pd.DataFrame:
    """The steps table (:func:`pdrlearn.waist.events.steps_from_events` form) with only the ``keep`` rows:
    a kept contact's step ends at the next kept contact if no sequence break lay between them and it
    follows within ``max_step_s`` (else it closes its sequence: ``end_s == start_s``, confidence 0.5)."""
    keep = np.asarray(keep, dtype=bool)
    if keep.size != len(steps):
        raise ValueError("keep_contacts: one flag per row")
    hn = steps["has_next"].to_numpy(bool)
    seq = np.concatenate([[0], np.cumsum(~hn[:-1])]) if hn.size else np.zeros(0, dtype=int)  # sequence number
    out = steps.loc[keep].copy()
    ev, sq = out["event_s"].to_numpy(float), seq[keep]
    nxt = np.append(ev[1:], np.inf)
    same = np.append(sq[1:] == sq[:-1], False)
    has_next = same & ((nxt - ev) <= max_step_s)
    out["end_s"] = np.where(has_next, nxt, ev)
    out["has_next"] = has_next
    out["confidence"] = np.where(has_next, 1.0, 0.5)
    out.attrs = dict(steps.attrs)
    return out.reset_index(drop=True)
