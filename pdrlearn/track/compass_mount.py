"""Decision D25: is the waist unit mounted so that its compass can give the fused track's heading?

Trial T3 (session 38): a mirrored waist unit (x/y swapped, frame inferred) turned the default fused track by about
180 deg, a waist unit turned on the belt with its belt frame kept by 90-180 deg, exit 0. Two comparisons:

- turns (:func:`turn_mismatch`): between consecutive straight strides across a foot turn of at least
  :data:`MOUNT_TURN_MIN_DEG` and at most :data:`MOUNT_TURN_MAX_DEG` (D34), the waist compass's turn against the foot
  gyroscope's (a mirrored compass turns the other way: its turns match the mirrored foot turns, which a disturbed
  field's do not);
- the waist's forward (:func:`declared_forward_off`): D10's check of a declared waist frame measured the walking
  direction more than :data:`MOUNT_FORWARD_OFF_DEG` from the declared forward (the compass then reads the heading of
  another body direction, a constant offset no turn shows).
"""
from __future__ import annotations

import numpy as np

from pdrlearn.kernels.fixes import wrap_angle
from pdrlearn.track.frame_inference import asymmetric_forward_words

#: decision D25: a foot heading change of at least this (deg) between two consecutive straight strides is a turn
MOUNT_TURN_MIN_DEG = 45.0
#: decision D34 (amends D25): a foot turn over this (deg) is not judged: near +-180 deg the mirrored turn is the turn
#: itself, so a U-turn cannot tell a mirrored compass from a normal one; None: no bound (D25 as first written)
MOUNT_TURN_MAX_DEG: float | None = 135.0
#: decision D25: at least this many turns judge the compass's turns
MOUNT_MIN_TURNS = 2
#: decision D25: a median |compass turn - foot turn| over this (deg) fails (a mirrored compass: 180 deg on 90 deg)
MOUNT_TURN_MISMATCH_DEG = 45.0
#: decision D25: a declared waist forward measured more than this (deg, horizontal) off fails: halfway to the next
#: axis, the largest error of a nearest-axis declaration
MOUNT_FORWARD_OFF_DEG = 45.0


def turn_mismatch(foot: np.ndarray, compass: np.ndarray, keep: np.ndarray, min_turn_deg: float = MOUNT_TURN_MIN_DEG,
                  *, mirrored: bool = False, max_turn_deg: float | None = None) -> tuple[float | None, int]:
    """Decision D25 (a): the median |wrap(compass turn - foot turn)| (deg) over the turns between consecutive
    ``keep`` strides (time order) whose ``foot`` heading (rad) changed by at least ``min_turn_deg``, the compass turn
    being the change of ``compass`` (rad) between the same strides; and the number of turns (None: no turn).
    ``mirrored``: against the mirrored foot turn, |wrap(compass turn + foot turn)| (D25 amended).
    ``max_turn_deg``: only foot turns of at most this are judged (D34; None: :data:`MOUNT_TURN_MAX_DEG`)."""
    idx = np.flatnonzero(np.asarray(keep, bool))
    if len(idx) < 2:
        return None, 0
    df = wrap_angle(np.diff(np.asarray(foot, float)[idx]))
    dc = wrap_angle(np.diff(np.asarray(compass, float)[idx]))
    top = MOUNT_TURN_MAX_DEG if max_turn_deg is None else max_turn_deg
    turn = np.abs(df) >= np.radians(min_turn_deg)
    if top is not None:  # decision D34: a U-turn's mirrored turn is the turn itself
        turn &= np.abs(df) <= np.radians(top)
    if not turn.any():
        return None, 0
    sign = -1.0 if mirrored else 1.0
    return float(np.degrees(np.median(np.abs(wrap_angle(dc[turn] - sign * df[turn]))))), int(turn.sum())


def declared_forward_off(session, placement: str = "waist") -> float | None:
    """Decision D25 (b): the horizontal angle (deg) D10's check of ``placement``'s declared frame measured between
    the declared forward and the walking direction; None when the frame is not declared or the data did not fix it."""
    chk = session.declared_check(placement)
    return None if chk is None else chk.forward_deg


def declared_forward_yaw(session, placement: str = "waist") -> float | None:
    """Decision L796: the signed angle (deg, + counter-clockwise) D10's check measured from ``placement``'s used
    forward to the walking direction (:func:`pdrlearn.track.frame_inference.forward_yaw_deg`); None when not
    measured, or the check was not judged (W415: a side or backward drill's travel is no forward)."""
    chk = session.declared_check(placement)
    return None if chk is None else chk.forward_yaw_deg


def trusted_forward_yaw(session, info: dict, *, gate: bool = True) -> tuple[float | None, str | None]:
    """Decision L801 (amends L796): (the yaw in deg to turn the waist compass by, or None; a warning line or None).
    The yaw D10's check measured (:func:`declared_forward_yaw`, recorded in ``info["forward_yaw_deg"]``) is not
    trusted when W435 does not trust the measured forward (its step-frequency power ratio under
    :data:`pdrlearn.track.frame_inference.MIN_JUDGED_POWER_RATIO`: an asymmetric gait turns it by 12-50 deg) or when
    meta.json's ``"force_frame"`` keeps the declared waist frame (W434: the user's forward, not the measurement's).
    ``gate`` (L801's candidate; the default since decision L803): an untrusted yaw is not applied,
    ``info["forward_yaw_skipped"]`` names why and the line says the compass was not turned; ``gate=False`` (L796's
    turn, ``--params '{"forward_yaw_gate": false}'``) applies the yaw and ``info["forward_yaw_untrusted"]`` and the
    line say it may be the gait's."""
    from pdrlearn.decision_refs import decision_ref
    from pdrlearn.track.frame_inference import MIN_JUDGED_POWER_RATIO

    yaw = declared_forward_yaw(session)
    info["forward_yaw_deg"] = yaw
    if yaw is None:
        return None, None
    ratio = forward_power_ratio(session)
    if _waist_forced(session):
        why, words = "force_frame", ('meta.json\'s "force_frame" keeps the declared waist frame (W434: the unit is '
                                     "worn as declared)")
    elif ratio is not None and ratio < MIN_JUDGED_POWER_RATIO:  # decision W435's bound (x10)
        why, words = "power_ratio", (f"its step-frequency power ratio is only x{ratio:.1f} (under "
                                     f"x{MIN_JUDGED_POWER_RATIO:g}): an asymmetric gait (a hemiparesis, a prosthesis) "
                                     "can turn the measured forward by 12-50 deg (W435)")
    else:
        return yaw, None
    measured = f"the waist unit's measured mount yaw ({yaw:+.1f} deg, L796)"
    if gate:
        info["forward_yaw_skipped"] = why
        return None, (f"the waist compass was not turned by {measured}: {words}; if the unit really is turned on its "
                      "belt, --params '{\"forward_yaw_gate\": false}' turns it all the same "
                      f"({decision_ref('L801')}, {decision_ref('L803')})")
    info["forward_yaw_untrusted"] = why
    return yaw, (f"the waist compass was turned by {measured}, though {words}; if the gait or the declared frame "
                 "turned that measurement, leave \"forward_yaw_gate\": false out of --params (the default, L803, "
                 f"leaves the compass unturned here; '{{\"forward_yaw\": false}}' never turns it) "
                 f"({decision_ref('L801')})")


def forward_power_ratio(session, placement: str = "waist") -> float | None:
    """Decision W435: the step-frequency power ratio of the forward D10's check measured (None: none measured)."""
    chk = session.declared_check(placement)
    return None if chk is None else getattr(chk, "forward_power_ratio", None)


def mount_check(session, foot: np.ndarray, compass: np.ndarray, keep: np.ndarray) -> tuple[str | None, dict]:
    """Decision D25: (a warning line or None, ``info["compass_mount"]``) for a heading that reads the waist compass:
    the turn mismatch of :func:`turn_mismatch` (with at least :data:`MOUNT_MIN_TURNS` turns) and the declared
    forward's offset of :func:`declared_forward_off`; the line says the track follows the foot's gyroscope heading.
    Decision W415: when the waist frame check was not judged (a side or backward drill) there is no line, but
    ``info["fallback"]`` is still set (the foot gyroscope's heading: the numbers D25 gave before W415)."""
    mismatch, n = turn_mismatch(foot, compass, keep)
    mirror = turn_mismatch(foot, compass, keep, mirrored=True)[0]
    off = declared_forward_off(session)
    info = {"turn_mismatch_deg": mismatch, "mirrored_mismatch_deg": mirror, "n_turns": n,
            "waist_forward_off_deg": off, "limit_deg": MOUNT_TURN_MISMATCH_DEG,
            "forward_limit_deg": MOUNT_FORWARD_OFF_DEG, "fallback": False}
    why = []
    # D25 amended: a disturbed field (30 uT hard iron) also bends the compass's turns (54.8 deg), but not into the
    # mirrored foot turns (126.3 deg): only a compass whose turns match the mirrored ones is a mirrored unit
    if (mismatch is not None and n >= MOUNT_MIN_TURNS and mismatch > MOUNT_TURN_MISMATCH_DEG
            and mirror <= MOUNT_TURN_MISMATCH_DEG):
        why.append(f"its compass turns differ from the foot gyroscope's turns by a median {mismatch:.0f} deg over {n} "
                   f"turns (over {MOUNT_TURN_MISMATCH_DEG:g} deg: the compass turns the other way, the unit's data "
                   "are mirrored, e.g. two axes swapped)")
    ratio = forward_power_ratio(session)
    info["forward_power_ratio"] = ratio  # decision W435: under x10, an asymmetric gait may have turned the measurement
    asymmetric = off is not None and off > MOUNT_FORWARD_OFF_DEG and bool(asymmetric_forward_words(ratio))
    forced = off is not None and off > MOUNT_FORWARD_OFF_DEG and _waist_forced(session)
    if forced:  # decision W434: the user's "force_frame" keeps the declared waist frame, and so its compass
        info["forward_forced"] = True
    elif off is not None and off > MOUNT_FORWARD_OFF_DEG:
        why.append(f"its declared forward is {off:.0f} deg from the direction it walks (over "
                   f"{MOUNT_FORWARD_OFF_DEG:g} deg: the unit is turned on the belt against its declared frame"
                   + (", or" + asymmetric_forward_words(ratio)[1:] if asymmetric else "") + ")")
    if not why:
        return None, info
    info["fallback"] = True
    chk = session.declared_check("waist")
    if chk is not None and chk.side_drill:  # decision W415: a side or backward drill, not a mounting fault: no line,
        info["not_judged"] = chk.unchecked  # but the foot gyroscope's heading as before W415 (numbers unchanged)
        return None, info
    guess = "may not match" if asymmetric and len(why) == 1 else "does not match"  # W435: the gait may turn it
    return (f"the waist unit's mounting {guess} its frame - " + "; ".join(why) + " - so its compass would "
            "turn the whole track: this track's heading is the foot gyroscope's own (0 = the walker's facing at the "
            "first walk, L494/L510, as `--units foot`; --initial-heading DEG sets it, L511), not the compass's "
            "(decision D25); " + ("if the unit is worn as declared, keep its frame: the foot gyroscope's heading is "
                                  "the safe choice here, since a unit really turned on the belt would turn the whole "
                                  "track (W435: 35-38 m off on a 35 m route); to keep its compass all the same, "
                                  "\"force_frame\": [\"waist\"] in meta.json (W434)" if asymmetric else
                                  "declare the waist unit's frame as it is worn (`pdrlearn info` prints the frame the "
                                  "data give)")), info


def _waist_forced(session) -> bool:
    """Decision W434: whether ``session`` forces its declared waist frame (meta.json ``"force_frame"``, D23's
    override; False for a session object without one)."""
    forced = getattr(session, "frame_forced", None)
    return bool(forced("waist")) if callable(forced) else False
