"""The chair transfers and TUG of a foot + waist session's default (foot) track (decisions W418, W419,
docs/decisions/waist.md).

A PLASYS track follows the foot, which does not see the trunk; W418 runs the waist-pendulum pipeline on the session's
lower-back unit alone (what ``track --units waist`` runs; W428: only as far as these need) and keeps its transfers,
walking contacts and yaw-rate turns in the foot track's ``info`` (``transfers``, ``trunk_contacts``,
``trunk_yaw_turns``; W586: and its posture runs, ``trunk_postures``, the track's standing / sitting / lying split).
W419: the TUG's chair transfers and seat-to-seat rules then read the waist, its turns and step count the foot.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.warning_lines import isolated_warnings

#: decision W419: the value of tug_trials.csv's ``steps_source`` / ``turns_source`` per unit
FOOT, WAIST = "foot", "waist"


def add_trunk_transfers(result, session) -> None:
    """Decision W418: put the lower-back unit's chair transfers (W182), walking contacts and yaw-rate turns into a
    foot track ``result``'s ``info`` (``transfers``, ``trunk_contacts``, ``trunk_yaw_turns``; W586: the posture runs,
    ``trunk_postures``), read by a
    waist-pendulum track of ``session``'s waist unit alone (W428: :func:`~pdrlearn.track.waist.trunk_events`, that
    track's code stopped once these are known); nothing when the session has no lower-back unit. A
    waist unit that cannot be tracked leaves ``info["trunk_note"]`` (one line naming the command) instead."""
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import trunk_events

    if not session.has("wAccelerometer", "wGyroscope") or result.info.get("transfers") is not None:
        return
    try:
        with isolated_warnings():  # the inner track's warnings are not the output's (W418; per thread, E179)
            # W428: only what the TUG reads of the waist-pendulum track (its own code stopped after the contacts)
            waist = trunk_events(keep_units(session, ("waist",)))
    except DataError as exc:
        result.info["trunk_note"] = (f"no chair transfers from the lower-back unit ({exc}); a TUG needs them: "
                                     f"pdrlearn track {session.where} --units waist (W418)")
        return
    result.info["transfers"] = waist.info.get("transfers")
    if result.info["transfers"] is None:  # W427: a dead (e.g. frozen) waist unit tracks but reads no transfers
        result.info["trunk_note"] = ("no chair transfers from the lower-back unit (its track read none: is "
                                     "wAccelerometer frozen or unplugged?); a TUG needs them: "
                                     f"pdrlearn track {session.where} --units waist (W418, W427)")
    # decision W586: the lower back's posture runs (W222, the waist-only track's own), for the posture split
    result.info["trunk_postures"] = waist.info.get("postures")
    cols = [c for c in ("start_s", "end_s", "event_s") if c in waist.steps]
    result.info["trunk_contacts"] = waist.steps[cols].to_dict("records")
    result.info["trunk_yaw_turns"] = waist.info.get("yaw_turns")


def tug_contacts(result) -> pd.DataFrame:
    """Decision W418: the walking contacts (``start_s``) W183 / W325's seat-to-seat rules and W293's walk phases read:
    the lower-back unit's (``info["trunk_contacts"]``) on a foot track, else the track's own steps."""
    rows = result.info.get("trunk_contacts")
    return result.steps if rows is None else pd.DataFrame(rows, columns=["start_s", "end_s", "event_s"])


def tug_yaw_turns(result):
    """Decision W307 with W418: the yaw-rate turns a TUG's turn-to-sit may fall back on (the waist unit's)."""
    return result.info.get("trunk_yaw_turns", result.info.get("yaw_turns"))


def foot_strides(result) -> pd.DataFrame | None:
    """Decision W419: the foot strides a two-unit TUG counts its steps on (a foot track with the waist's transfers,
    W418); None on a lower-back track (its steps are counted as they are)."""
    return result.steps if result.info.get("trunk_contacts") is not None else None


def foot_step_count(strides: pd.DataFrame, t0: float, t1: float) -> int:
    """Decision W419: the steps of both feet from ``t0`` to ``t1`` (s) read from one foot's ``strides``: 2 x the
    strides whose contact (``event_s``, else ``start_s``) lies in it (the foot summary's "~N steps", the other foot
    alternating)."""
    col = "event_s" if "event_s" in strides else "start_s"
    ev = strides[col].to_numpy(float) if len(strides) else np.zeros(0)
    return 2 * int(((ev >= t0) & (ev <= t1)).sum())


def tug_source_summary(result, summary: dict) -> dict:
    """Decision W419: the summary's ``tug_steps_source`` / ``tug_turns_source``; None without transfers and (W427)
    without a TUG in ``summary`` (no ``tug_time_s``, ``n_tug_trials`` 0: nothing was counted)."""
    has_tug = bool(summary.get("n_tug_trials")) or summary.get("tug_time_s") is not None
    if result.info.get("transfers") is None or not has_tug:
        return {"tug_steps_source": None, "tug_turns_source": None}
    unit = FOOT if foot_strides(result) is not None else WAIST
    return {"tug_steps_source": unit, "tug_turns_source": unit}


def trunk_note(result) -> str | None:
    """Decision W418: ``tug_time_note``'s line when a two-unit track could not read the waist's transfers."""
    return result.info.get("trunk_note")
