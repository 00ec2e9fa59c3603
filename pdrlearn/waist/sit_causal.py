"""Decision W200: the sit veto of a realtime lower-back track, decided causally with a bounded delay.

W104's veto (:func:`pdrlearn.waist.posture.transfer_veto`) reads the whole recording: its walking upright is the median
up direction over all walking contacts, and W20's sides (the W109 / W180 / W184 sparing) are filtered zero-phase over
the whole recording. Here each contact is decided on the samples before its horizon, :data:`CAUSAL_HORIZON_S` after it
(its next contact, if any, is decided by then: W16's longest step + W31's decision delay), with the same kernels:

- the upright: W102's median contact direction over the walking contacts up to this one, once there are
  :data:`CAUSAL_UPRIGHT_MIN`; before that the start's direction (the first :data:`START_WINDOW_S` of the recording);
- the events: W104's runs over 25 deg on the samples of the last W31 history (:data:`~pdrlearn.kernels.waist.
  DECISION_HISTORY_S`) before the contact up to its horizon;
- the sparing: W20's sides of the contact and its two neighbours, the lateral velocity filtered on the same window
  and decided against the median at the window's walking contacts (W166's window scale).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.waist_stream import MAX_STEP_S
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.posture import (
    TILT_HALF_WINDOW_S,
    contact_directions,
    drop_contacts,
    flexion_runs,
    near_flexion,
    sample_tilt_deg,
    spared,
    walking_upright,
)

#: W200: a contact's veto reads the samples up to this long after it: W16's longest step (its next contact comes by
#: then, or its sequence has ended) + W31's decision delay (that contact is decided by then)
CAUSAL_HORIZON_S = MAX_STEP_S + K.DECISION_DELAY_S
#: W200: the walking contacts (``has_next``) needed before their median direction is the upright: W104 counted at most
#: 2 false contacts per simulated transfer (pendulum), so of 5 at least 3 are steps and the median is a step's
CAUSAL_UPRIGHT_MIN = 5
#: W200: before that, the upright is the mean up direction over the recording's first 2 x W102's half window (s)
START_WINDOW_S = 2.0 * TILT_HALF_WINDOW_S


def start_direction(t: np.ndarray, up_body: np.ndarray) -> np.ndarray:
    """W200: the normalised mean up direction over the first :data:`START_WINDOW_S` of ``t`` (a standing start reads
    the walking upright; a seated pelvis ~12 deg from it, W102)."""
    n = max(1, int(np.searchsorted(t, t[0] + START_WINDOW_S)))
    u = up_body[:n] / np.linalg.norm(up_body[:n], axis=1, keepdims=True)
    m = u.mean(axis=0)
    return m / np.linalg.norm(m)


def causal_uprights(d: np.ndarray, has_next: np.ndarray, start: np.ndarray) -> np.ndarray:
    """W200: per contact, the upright its veto uses: :func:`~pdrlearn.waist.posture.walking_upright` of the contact
    directions ``d`` over the walking contacts up to it (``has_next`` of contacts j <= i, known by its horizon) once
    there are :data:`CAUSAL_UPRIGHT_MIN`, else ``start``."""
    hn = np.asarray(has_next, dtype=bool)
    seen = np.cumsum(hn)
    return np.array([walking_upright(d[:i + 1], hn[:i + 1]) if seen[i] >= CAUSAL_UPRIGHT_MIN else start
                     for i in range(len(hn))]).reshape(-1, 3)


def causal_veto_mask(t: np.ndarray, up_body: np.ndarray, acc_ml: np.ndarray, fs: float, event_s: np.ndarray,
                     has_next: np.ndarray, *, keep_rhythm: bool = False, keep_between: bool | str = False
                     ) -> np.ndarray:
    """W200: per contact, vetoed: W104's window test against the flexion runs seen with its causal upright on the
    samples of [e - DECISION_HISTORY_S, e + :data:`CAUSAL_HORIZON_S`), less the sparing (W109 / W180 / W184) of W20's
    sides filtered on that window. Nothing after a contact's horizon is read."""
    e = np.asarray(event_s, dtype=float)
    hn = np.asarray(has_next, dtype=bool)
    veto = np.zeros(e.size, dtype=bool)
    if e.size == 0:
        return veto
    ups = causal_uprights(contact_directions(t, up_body, e), hn, start_direction(t, up_body))
    for i in range(e.size):
        lo = int(np.searchsorted(t, e[i] - K.DECISION_HISTORY_S))
        hi = int(np.searchsorted(t, e[i] + CAUSAL_HORIZON_S))  # samples before the horizon
        if hi - lo < 2:
            continue
        tw = t[lo:hi]
        if not near_flexion(e[i:i + 1], flexion_runs(tw, sample_tilt_deg(up_body[lo:hi], ups[i])))[0]:
            continue
        veto[i] = True
        if keep_rhythm or keep_between:
            # the contacts decided by the horizon inside the window: up to the latest next contact (W16's longest step)
            w = np.flatnonzero((e >= e[i] - K.DECISION_HISTORY_S) & (e <= e[i] + MAX_STEP_S))
            hn_w = hn[w].copy()
            hn_w[-1] = False  # the last one's next contact is not known by the horizon
            side = K.step_sides(contact_lateral_velocity(tw, acc_ml[lo:hi], fs, e[w]), hn_w)  # W20, W166's scale
            veto[i] = not spared(side, hn_w, keep_rhythm, keep_between)[int(np.searchsorted(w, i))]
    return veto


def causal_transfer_veto(steps: pd.DataFrame, imu: WaistIMU, *, keep_rhythm: bool = False,
                         keep_between: bool | str = False) -> pd.DataFrame:
    """``steps`` without the contacts :func:`causal_veto_mask` vetoes (decision W200; the step before a dropped
    contact ends its sequence, :func:`~pdrlearn.waist.posture.drop_contacts`). ``attrs["n_vetoed"]`` counts them."""
    if steps.empty or imu.up_body is None:
        out = steps.copy()
        out.attrs["n_vetoed"] = 0
        return out
    veto = causal_veto_mask(imu.t, imu.up_body, imu.acc_ml, imu.fs, steps["event_s"].to_numpy(float),
                            steps["has_next"].to_numpy(bool), keep_rhythm=keep_rhythm, keep_between=keep_between)
    return drop_contacts(steps, ~veto, "n_vetoed")
