"""A plain list of one foot's initial contacts (a mocap / Vicon event list) -> labelled strides (decision B338).

A foot reference is one row per stride, ``start_ms, end_ms, ic_ms``. A motion-capture lab has the contacts only,
often just those inside the capture volume. Decision G2 (docs/external-data.md, the gaitmap 4x10 m walk) lays such
a list out without losing its last contact: the stride from contact *i* to *i+1* has ``pre_ic`` = contact *i* (it
opens the chain) and ``ic`` = contact *i+1*, so every contact is a reference event and each chain of touching
strides is a labelled interval (docs/decisions/steps.md 15); the IC-to-IC layout ``ic`` = contact *i* scores the
chain's last contact as nothing (trial T2 finding 7: precision 0.931 instead of 0.964 on gaitmap's left foot).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.contact import MAX_STRIDE_S


def ic_strides(ic_s, tc_s=None, length_m=None) -> pd.DataFrame:
    """Decision B338: one foot's contact times (s) -> strides ``start_s, end_s, ic_s, pre_ic_s`` the G2 way
    (``pre_ic_s = start_s`` = contact *i*, ``ic_s = end_s`` = contact *i+1*). Consecutive contacts further apart
    than :data:`~pdrlearn.kernels.contact.MAX_STRIDE_S` (Mobilise-D's longest stride, 3 s: the foot left the capture
    volume) are not a stride: the chain ends there. A shorter interval is a stride, as the mocap reference of
    gaitmap labels a 2.3 s one: a contact missing from the list makes one long stride.

    Decision D51: a walkway's per-footfall values come along when given, each (N,) beside ``ic_s``: ``tc_s``, the
    footfall's own toe-off, becomes the stride's ``tc_s`` of the stride it opens (contact *i*'s toe-off, kept only
    inside that stride, as gaitmap's ``pre_ic < tc < ic``: stance = tc - pre_ic); ``length_m``, the footfall's
    stride length (a walkway's: heel of the previous same-side footfall to this one), becomes the length of the
    stride it closes (contact *i+1*'s). ``attrs["tc_given"]``: how many strides' opening footfalls had a toe-off
    before the inside-the-stride filter (the importer says how many it dropped)."""
    t = np.asarray(ic_s, dtype=float)
    extra = {k: np.asarray(v, dtype=float) for k, v in (("tc_s", tc_s), ("length_m", length_m)) if v is not None}
    order = np.argsort(t, kind="stable")
    t, extra = t[order], {k: v[order] for k, v in extra.items()}
    fin = np.isfinite(t)
    t, extra = t[fin], {k: v[fin] for k, v in extra.items()}
    keep = np.diff(t) <= MAX_STRIDE_S
    a, b = t[:-1][keep], t[1:][keep]
    out = pd.DataFrame({"start_s": a, "end_s": b, "ic_s": b, "pre_ic_s": a})
    if "tc_s" in extra:
        tc = extra["tc_s"][:-1][keep]
        with np.errstate(invalid="ignore"):
            out["tc_s"] = np.where((tc > a) & (tc < b), tc, np.nan)  # D51: the opening footfall's toe-off
        out.attrs["tc_given"] = int(np.isfinite(tc).sum())  # D51 amended (review R2 finding 6): before the filter
    if "length_m" in extra:
        out["length_m"] = extra["length_m"][1:][keep]  # D51: the closing footfall's stride length
    return out
