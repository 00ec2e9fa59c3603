"""Chair transfers of the lower-back unit: each sit-to-stand and stand-to-sit, and a Timed-Up-and-Go time
(decisions W182, W183, docs/decisions/waist.md).

The transfers are W104's trunk-flexion events (:func:`pdrlearn.waist.posture.flexion_events`: a run of samples whose
trunk tilts more than 25 deg from the session's walking upright) - no second detector. Each event is widened to the
whole movement and classed by the pelvis's height change over it:

* **bounds** (W182): from the event's tilt peak, backward and forward for as long as the trunk's tilt still moves
  toward the peak at :data:`MOVING_DPS` deg/s or more (the tilt's rate over :data:`RATE_WINDOW_S`): the trunk is at
  rest, seated or standing, before and after a transfer;
* **kind** (W182): the pelvis's height change from the movement's start to its end, the vertical acceleration
  (gravity removed, the AHRS's) integrated twice with the velocity made zero at both bounds (the trunk rests there;
  a constant acceleration error is removed with it): up by :data:`HEIGHT_MIN_M` or more is a ``sit-to-stand``, down
  by as much a ``stand-to-sit``; less is a bend (picking something up, leaning forward) and no transfer;
* **TUG time** (W183): ``tug_time_s`` is the first sit-to-stand's start to the last stand-to-sit's end, only when
  the session starts and ends seated: no step starts before that sit-to-stand's start or after that stand-to-sit's
  end (a contact inside a transfer may: W146), and no transfer lies between them (else None: the test was not
  recorded from seat to seat).

Not from a seed: the clinical TUG runs from rising off the chair to sitting back on it (Podsiadlo & Richardson 1991,
J Am Geriatr Soc 39:142-148, as recalled), and the thresholds are this module's choices (W182), set before
measuring. A foot unit sees no trunk: a foot track has no transfers (the summary keys are None).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.posture import flexion_events

#: decision W182: the trunk still moves while its tilt changes this fast (deg/s) toward the flexion peak; a
#: transfer's trunk flexes 30-45 deg in about a second (30-45 deg/s on average), standing or seated it rests
MOVING_DPS = 10.0
#: decision W182: the tilt's rate is the mean over this window (s), so that a walking step's rocking of a few degrees
#: does not extend a transfer
RATE_WINDOW_S = 0.25
#: decision W182: a rise or a sit moves the pelvis by this much (m) or more; standing hip height (~0.9 m) less a
#: chair seat (~0.45 m) is ~0.45 m, half of a low 0.40 m is taken; a bend moves it less
HEIGHT_MIN_M = 0.20
#: decision W233's candidate (measured, see its text): the height change over at least this (s) on each side of the tilt
#: peak (W104's TRANSFER_HALF_S); None = over W182's movement bounds only
HEIGHT_HALF_S: float | None = None
SIT_TO_STAND, STAND_TO_SIT = "sit-to-stand", "stand-to-sit"
#: transfers.csv's columns (decision W182), in order
TRANSFER_COLUMNS = ("transfer", "kind", "start_s", "end_s", "duration_s", "peak_s", "peak_tilt_deg",
                    "height_change_m")
#: decision W183: the summary keys of :func:`transfer_summary`
TRANSFER_SUMMARY_KEYS = ("n_sit_to_stand", "n_stand_to_sit", "median_sit_to_stand_s", "median_stand_to_sit_s",
                         "tug_time_s", "n_lie_down", "n_get_up", "tug_time_note")
#: decision W258: the lying kinds (W245) counted by direction: into lying (``n_lie_down``) and out of it
#: (``n_get_up``); their sit / stand side is W223's split (W257), their direction right on every HAPT label (W246)
#: decision W245: transfers.csv's lying kinds (into lying from / out of lying to: sitting, standing), written by
#: :mod:`pdrlearn.waist.lying`
SIT_TO_LIE, LIE_TO_SIT, STAND_TO_LIE, LIE_TO_STAND = "sit-to-lie", "lie-to-sit", "stand-to-lie", "lie-to-stand"
LIE_DOWN_KINDS, GET_UP_KINDS = (SIT_TO_LIE, STAND_TO_LIE), (LIE_TO_SIT, LIE_TO_STAND)


def _tilt_deg(imu: WaistIMU, up: np.ndarray) -> np.ndarray:
    u = imu.up_body / np.linalg.norm(imu.up_body, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip(u @ up, -1.0, 1.0)))


def tilt_rate_dps(t: np.ndarray, tilt: np.ndarray, fs: float) -> np.ndarray:
    """The trunk tilt's rate (deg/s), the mean over :data:`RATE_WINDOW_S` (decision W182; shared by W245's lying
    transfers)."""
    w = max(int(round(RATE_WINDOW_S * fs)), 1)
    return np.convolve(np.gradient(tilt, t), np.ones(w) / w, mode="same")


def movement_bounds(t: np.ndarray, tilt: np.ndarray, peak: int, fs: float) -> tuple[int, int]:
    """Sample indices ``(start, end)`` of the movement around the tilt peak ``peak`` (decision W182): backward from
    the peak past the samples near it where the tilt's rate (mean over :data:`RATE_WINDOW_S`) is under
    :data:`MOVING_DPS` (at most :data:`RATE_WINDOW_S` of them: the top of the flexion), then past those where the
    trunk flexes at :data:`MOVING_DPS` or more; the first sample after them is the start. Forward alike with the
    trunk straightening (the rate at or under -:data:`MOVING_DPS`)."""
    w = max(int(round(RATE_WINDOW_S * fs)), 1)
    rate = tilt_rate_dps(t, tilt, fs)
    a = peak
    while a > 0 and peak - a < w and rate[a - 1] < MOVING_DPS:  # the top of the flexion
        a -= 1
    while a > 0 and rate[a - 1] >= MOVING_DPS:
        a -= 1
    b = peak
    while b < len(t) - 1 and b - peak < w and rate[b + 1] > -MOVING_DPS:
        b += 1
    while b < len(t) - 1 and rate[b + 1] <= -MOVING_DPS:
        b += 1
    return a, b


def height_change_m(t: np.ndarray, acc_v: np.ndarray, a: int, b: int) -> float:
    """The pelvis's height change (m) from sample ``a`` to ``b``: ``acc_v`` (m/s^2, up +) integrated to a velocity
    (trapezoids), less the line that makes it zero at both ends (the trunk rests there), integrated again
    (decision W182)."""
    if b - a < 2:
        return 0.0
    tt, acc = t[a:b + 1], acc_v[a:b + 1]
    v = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * np.diff(tt))])
    v = v - v[-1] * (tt - tt[0]) / (tt[-1] - tt[0])
    return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(tt)))


def chair_transfers(imu: WaistIMU, steps: pd.DataFrame) -> pd.DataFrame:
    """Decision W182: transfers.csv's rows (:data:`TRANSFER_COLUMNS`) of a lower-back track: each W104 flexion
    event of ``steps``' contacts (``event_s``, ``has_next``) widened to its movement (:func:`movement_bounds`) and
    classed by :func:`height_change_m`; bends (less than :data:`HEIGHT_MIN_M`) are left out."""
    rows: list[dict] = []
    if imu.up_body is not None and len(steps) and "event_s" in steps:
        ev = steps["event_s"].to_numpy(float)
        walking = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(ev), bool)
        events = flexion_events(imu, ev, walking)
        if events:
            from pdrlearn.waist.posture import _contact_directions

            tilt = _tilt_deg(imu, _contact_directions(imu, ev, walking)[1])
            for _, t_peak, _ in events:
                peak = int(np.clip(np.searchsorted(imu.t, t_peak), 0, len(imu.t) - 1))
                a, b = movement_bounds(imu.t, tilt, peak, imu.fs)
                ha, hb = a, b
                if HEIGHT_HALF_S is not None:  # decision W233: at least W104's +-1 s around the peak
                    ha = min(a, int(np.searchsorted(imu.t, t_peak - HEIGHT_HALF_S)))
                    hb = max(b, min(int(np.searchsorted(imu.t, t_peak + HEIGHT_HALF_S)), len(imu.t) - 1))
                dz = height_change_m(imu.t, imu.acc_v, ha, hb)
                if abs(dz) < HEIGHT_MIN_M:
                    continue
                t0, t1 = float(imu.t[a]), float(imu.t[b])
                if rows and t0 < rows[-1]["end_s"]:  # one movement seen as two flexion runs: keep the first
                    continue
                rows.append({"transfer": len(rows) + 1, "kind": SIT_TO_STAND if dz > 0 else STAND_TO_SIT,
                             "start_s": t0, "end_s": t1, "duration_s": t1 - t0, "peak_s": float(t_peak),
                             "peak_tilt_deg": float(tilt[peak]), "height_change_m": dz})
    return pd.DataFrame(rows, columns=list(TRANSFER_COLUMNS))


def transfer_summary(transfers, steps: pd.DataFrame | None = None) -> dict:
    """Decision W183: :data:`TRANSFER_SUMMARY_KEYS` of a transfers table (a DataFrame or its records; None = a
    track without a trunk unit: every key None). ``tug_time_s`` (module docstring) needs ``steps`` (the contacts'
    ``start_s``); without them it is judged on the transfers alone (a sit-to-stand first and a stand-to-sit
    last)."""
    if transfers is None:
        return dict.fromkeys(TRANSFER_SUMMARY_KEYS)
    tr = pd.DataFrame(list(transfers) if not isinstance(transfers, pd.DataFrame) else transfers,
                      columns=list(TRANSFER_COLUMNS))
    rise, sit = tr[tr["kind"] == SIT_TO_STAND], tr[tr["kind"] == STAND_TO_SIT]
    out = {"n_sit_to_stand": int(len(rise)), "n_stand_to_sit": int(len(sit)),
           "median_sit_to_stand_s": float(rise["duration_s"].median()) if len(rise) else None,
           "median_stand_to_sit_s": float(sit["duration_s"].median()) if len(sit) else None, "tug_time_s": None,
           "n_lie_down": int(tr["kind"].isin(LIE_DOWN_KINDS).sum()),  # decision W258
           "n_get_up": int(tr["kind"].isin(GET_UP_KINDS).sum())}
    contacts = np.zeros(0) if steps is None or not len(steps) else steps["start_s"].to_numpy(float)
    if len(tr) >= 2 and tr["kind"].iloc[0] == SIT_TO_STAND and tr["kind"].iloc[-1] == STAND_TO_SIT:
        t0, t1 = float(tr["start_s"].iloc[0]), float(tr["end_s"].iloc[-1])
        if len(tr) == 2 and not ((contacts < t0).any() or (contacts > t1).any()):
            out["tug_time_s"] = t1 - t0
    # decision W282: why not, when a rise is followed by a sit (a TUG could be timed on them)
    pair = len(rise) and len(sit) and float(rise["start_s"].min()) < float(sit["end_s"].max())
    out["tug_time_note"] = tug_note(tr, contacts) if out["tug_time_s"] is None and pair else None
    return out


def tug_note(tr: pd.DataFrame, contacts: np.ndarray) -> str:
    """Decision W282: why a transfers table ``tr`` (a sit-to-stand followed by a stand-to-sit) with step ``contacts``
    (start times, s) has no ``tug_time_s`` (W183's rule, module docstring), in one line that points at ``--window``."""
    rise, sit = tr[tr["kind"] == SIT_TO_STAND], tr[tr["kind"] == STAND_TO_SIT]
    first, last = tr.iloc[0], tr.iloc[-1]
    times = (f"the rises start at {', '.join(f'{t:.1f}' for t in rise['start_s'])} s" if len(rise) else "no rise")
    times += f", the sits end at {', '.join(f'{t:.1f}' for t in sit['end_s'])} s" if len(sit) else ", no sit"
    if first["kind"] != SIT_TO_STAND or last["kind"] != STAND_TO_SIT:
        return (f"no TUG time: the recording does not start and end seated (first transfer {first['kind']} at "
                f"{first['start_s']:.1f} s, last {last['kind']} at {last['start_s']:.1f} s; {times}); a TUG is "
                "timed from a rise to the next sit of a session cut with --window START,END around them (W183, W282)")
    if len(tr) > 2:
        return (f"no TUG time: {len(tr)} transfers ({len(rise)} sit-to-stand, {len(sit)} stand-to-sit), not one "
                f"seat-to-seat test ({times}); time each trial with --window START,END around one rise and the "
                "next sit (W183, W282)")
    t0, t1 = float(first["start_s"]), float(last["end_s"])
    n0, n1 = int((contacts < t0).sum()), int((contacts > t1).sum())
    return (f"no TUG time: {n0} step(s) before the rise at {t0:.1f} s and {n1} after the sit ending at {t1:.1f} s: "
            "not recorded from seat to seat; --window START,END around the rise and the sit times it (W183, W282)")
