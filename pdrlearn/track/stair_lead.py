"""Decision L561 (docs/decisions/localization.md): the stair flights of a bilateral walk and, on a step-to-step
flight (both feet on each stair, the same foot first every time: simulator S80 / S92, a prosthesis or a painful
knee's "up with the good, down with the bad"), the foot that leads.

Pure functions of :func:`pdrlearn.track.bilateral.merged_contacts`' table (``side``, ``bout``, ``ic_s``, ``z_m``:
each foot's rest height after the stride into the contact) and its contact kinds (L538). Per step (a contact and
the other foot's contact before it) the *step height* is the landing foot's height minus the other foot's, each
foot's height counted from its own rest height before the flight (the two tracks' height offsets cancel), signed
so that the climb is positive (up) or the descent is (down). On a step-to-step flight the leading foot's steps rise
one stair (h = r) and the trailing foot's end beside it (h = 0); step over step every step rises one stair. So with
``S`` = the left steps' mean height + the right steps' and ``D`` = left - right, ``D / S`` is +1 (left leads) or -1
(right leads) on a step-to-step flight and 0 step over step, whatever the rise.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L561: a flight is step-to-step, led by the left (right) foot, when ``D / S`` (module docstring) exceeds
#: this (is under minus this): midway between step over step's 0 and step-to-step's 1 (no document gives a limit)
STEP_TO_STEP_SHARE = 0.5
#: decision L561: the steps each foot needs on a flight before its pattern is judged (a first and a last stair)
MIN_STEPS_PER_SIDE = 2
#: decision L604: the fewest contacts of a flight (a run of one contact has no duration, ``start_s`` = ``end_s``)
MIN_FLIGHT_CONTACTS = 2
#: decision L561: the stair kinds (L538's) and their climb sign
_SIGN = {"stairs_up": 1.0, "stairs_down": -1.0}


def _runs(kinds: np.ndarray, bout: np.ndarray) -> list[tuple[int, int]]:
    """Maximal runs [a, b) of consecutive contacts of one stair kind in one bout."""
    runs, a = [], 0
    for k in range(1, len(kinds) + 1):
        if k == len(kinds) or kinds[k] != kinds[a] or bout[k] != bout[a]:
            if kinds[a] in _SIGN:
                runs.append((a, k))
            a = k
    return runs


def flight_lead(side: np.ndarray, z: np.ndarray, a: int, b: int, sign: float) -> dict:
    """Decision L561: the pattern of the flight of contacts [a, b) (``side``, rest heights ``z``, m; ``sign`` +1 up,
    -1 down): ``pattern`` "step-to-step" / "step-over-step" (None: too few steps or no height), ``lead`` (the leading
    foot of a step-to-step flight, else None), ``lead_index`` (``D / S``) and each side's mean step height (m)."""
    base = {}
    for s in ("left", "right"):
        own = np.flatnonzero(side[:a] == s)
        base[s] = float(z[own[-1]]) if len(own) else 0.0  # the foot's rest height before the flight (track origin 0)
    rel = z - np.array([base.get(s, 0.0) for s in side])
    k = np.arange(max(a, 1), b)
    k = k[side[k] != side[k - 1]]  # a step: the other foot's contact before it
    h = sign * (rel[k] - rel[k - 1])
    out = {"pattern": None, "lead": None, "lead_index": None, "n_steps_left": int((side[k] == "left").sum()),
           "n_steps_right": int((side[k] == "right").sum()), "step_height_m_left": None, "step_height_m_right": None}
    means = {}
    for s in ("left", "right"):
        hs = h[(side[k] == s) & np.isfinite(h)]
        means[s] = float(hs.mean()) if len(hs) >= MIN_STEPS_PER_SIDE else None
        out[f"step_height_m_{s}"] = means[s]
    if means["left"] is None or means["right"] is None or not means["left"] + means["right"] > 0:
        return out
    index = (means["left"] - means["right"]) / (means["left"] + means["right"])
    out["lead_index"] = float(index)
    if abs(index) > STEP_TO_STEP_SHARE:
        out.update(pattern="step-to-step", lead="left" if index > 0 else "right")
    else:
        out["pattern"] = "step-over-step"
    return out


def stair_flights(both: pd.DataFrame, kinds: np.ndarray) -> list[dict]:
    """Decision L561: one dict per stair flight of the merged contacts ``both`` (runs of consecutive contacts of one
    stair kind, :func:`pdrlearn.track.bilateral.contact_kinds`, in one bout; decision L604: of at least
    :data:`MIN_FLIGHT_CONTACTS` contacts, the last after the first): ``kind``, ``bout``, ``start_s`` /
    ``end_s`` (its first and last contact) and :func:`flight_lead`'s keys. Empty without a stair or a ``z_m``."""
    if "z_m" not in both or not len(both):
        return []
    side, bout = both["side"].to_numpy(), both["bout"].to_numpy(int)
    t, z = both["ic_s"].to_numpy(float), both["z_m"].to_numpy(float)
    out = []
    for a, b in _runs(np.asarray(kinds, dtype=object), bout):
        if b - a < MIN_FLIGHT_CONTACTS or not t[b - 1] > t[a]:  # decision L604: one contact is no flight
            continue
        kind = str(kinds[a])
        out.append({"kind": kind, "bout": int(bout[a]), "start_s": float(t[a]), "end_s": float(t[b - 1]),
                    **flight_lead(side, z, a, b, _SIGN[kind])})
    return out


#: decision L561: the words of a flight's kind in the printed and clinical lines
FLIGHT_WORDS = {"stairs_up": "up", "stairs_down": "down"}


def flight_line(f: dict) -> str:
    """Decision L561: one flight (a ``stairs`` dict, read defensively) in words, e.g. "up step-to-step, the right foot
    leading (10 / 10 steps L/R)"."""
    words = FLIGHT_WORDS.get(f.get("kind"), str(f.get("kind")))
    steps = f"{f.get('n_steps_left', '?')} / {f.get('n_steps_right', '?')} steps L/R"
    if f.get("pattern") == "step-to-step" and f.get("lead") in ("left", "right"):
        return f"{words} step-to-step, the {f['lead']} foot leading ({steps})"
    if f.get("pattern") == "step-over-step":
        return f"{words} step over step, the feet alternating ({steps})"
    return f"{words}: too few steps or no heights to tell the pattern ({steps})"
