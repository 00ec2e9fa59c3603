"""Toe-off (terminal contact) of each foot stride from the foot gyroscope (decision L73,
docs/decisions/localization.md): the kernel is :mod:`pdrlearn.kernels.toeoff` (decision E326: numpy only, so the lean
runtime's ``Tracker(gait=True)`` calls the same code; its docstring gives the method and sources), re-exported here;
this module keeps the toe-off's trust line (L414, L703).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.toeoff import LOWPASS_HZ, MIN_VOTE_ANGLE_RAD, sagittal_axis, toe_off_times
from pdrlearn.warning_lines import coded

__all__ = ["LOWPASS_HZ", "MIN_VOTE_ANGLE_RAD", "TOE_OFF_MIN_CHECKED_STANCE_S", "TOE_OFF_STANCE_BIAS_MS",
           "contact_rate_warning", "sagittal_axis", "stance_range_warning", "toe_off_times"]

#: decision L414: the shortest median stance time (s) at which L73 checked the stance times against a contact
#: reference - the smaller of `track datasets/real/gaitmap_level_{left,right} --toe-off`'s medians (0.692 / 0.701 s,
#: printed in session 34), rounded down to 0.01 s (L414's rule, fixed before reading it)
TOE_OFF_MIN_CHECKED_STANCE_S = 0.69
#: decision L73: the median stance-time error (ms) on those two recordings (ours - mocap), quoted in L414's line
TOE_OFF_STANCE_BIAS_MS = (-36.9, -40.1)


def stance_range_warning(summary: dict) -> str | None:
    """Decision L414: one line when a ``--toe-off`` track's ``median_stance_time_s`` is below
    :data:`TOE_OFF_MIN_CHECKED_STANCE_S`, the shortest contacts L73 checked (None otherwise, or without stance
    times). Decision L703: it states the known stance bias of the track's set-up (``info["stance_source"]``: force
    insoles or the IMU) in ms, in % of this walk's stance and in points of its gait cycle
    (``median_stride_time_s``). Decision L802: the line also when L285's "under 55 % of the gait cycle" line fired
    (a warning coded L285 in ``info["warnings"]``) at a longer stance - a slow walker's - so that line's reader
    knows the stance times' own bias; it then says so instead of "below 0.69 s"."""
    from pdrlearn.track.support_bias import STANCE_BIAS, bias_terms, setup_of, stance_bias_ms
    from pdrlearn.warning_lines import warning_code

    stance = summary.get("median_stance_time_s")
    if stance is None or not np.isfinite(stance):
        return None
    short_share = any(warning_code(str(w)) == "L285" or getattr(w, "code", None) == "L285"
                      for w in (summary.get("info") or {}).get("warnings", ()) or ())  # decision L802
    if stance >= TOE_OFF_MIN_CHECKED_STANCE_S and not short_share:
        return None
    setup = setup_of((summary.get("info") or {}).get("stance_source"))
    cycle, rate = summary.get("median_stride_time_s"), summary.get("rate_hz")  # decision L737: the foot's rate
    terms = bias_terms(setup, cycle, rate)
    ms = [r for r in (stance_bias_ms(k, cycle, rate) for k in ([setup] if setup else STANCE_BIAS)) if r is not None]
    share = (f" ({100 * -max(r[1] for r in ms) / 1000 / stance:.0f}-{100 * -min(r[0] for r in ms) / 1000 / stance:.0f}"
             f" % of this walk's {stance:.3f} s stance)") if ms else ""
    if stance >= TOE_OFF_MIN_CHECKED_STANCE_S:  # decision L802: L285's short stance at a checked contact length
        from pdrlearn.track.bilateral import STANCE_MIN_PCT

        pct = summary.get("median_stance_pct")
        of = f", {pct:.1f} % of the gait cycle," if isinstance(pct, float | int) and np.isfinite(pct) else ""
        return coded(f"median stance (contact) time {stance:.3f} s{of} is under "
                     f"{STANCE_MIN_PCT:.0f} % of the cycle (the L285 line): "
                     "--toe-off's stance times read short by a known bias (gaitmap's level walks with mocap, "
                     f"decision L73), in this walk's terms (L703): {terms}{share}; part of a short stance is this "
                     "bias, not the walker's (decisions L802, L414)", "L802")  # decision E170
    return coded(f"median stance (contact) time {stance:.3f} s is below {TOE_OFF_MIN_CHECKED_STANCE_S:.2f} s, the "
            "range at which --toe-off's stance times were checked against a reference: one walk, gaitmap's level "
            "walks with mocap at 0.69-0.70 s median contact (decision L73); most ordinary walks have shorter contacts "
            f"and get this line. The known bias, in this walk's terms (L703): {terms}{share} (decision L414)",
                 "L414")  # decision E170



def contact_rate_warning(summary: dict, *, low_hz: float = 90.0, high_hz: float = 300.0) -> str | None:
    """Steps decision 97 (not adopted, its fallback): one line when a ``--toe-off`` track's IMU-only contacts (the
    impact on the 8 Hz |acc|, decision 3) were dated at a foot rate under ``low_hz`` or over ``high_hz`` (Hz), where
    the same walk's contacts move with the rate (steps decisions 89, 93, 97); None otherwise, with force insoles'
    contacts, or without stance times or rate."""
    from pdrlearn.decision_refs import decision_ref
    from pdrlearn.track.support_bias import setup_of

    rate, stance = summary.get("rate_hz"), summary.get("median_stance_time_s")
    if rate is None or stance is None or not (np.isfinite(rate) and np.isfinite(stance)):
        return None
    if low_hz <= rate <= high_hz or setup_of((summary.get("info") or {}).get("stance_source")) == "force":
        return None
    if rate < low_hz:  # steps 97's simulated users 20600-20619, main's detector, printed
        why = ("on simulated feet the straight-stride stance bias moved by a median 48.5 ms per walker between 100, "
               "50 and 25 Hz (-77.1..-2.5 ms at 100 Hz, -141.4..+54.4 ms at 25 Hz)")
    else:  # steps 89 / 97: gaitmap level left (204.8 Hz) resampled to 999.9 Hz, printed
        why = ("the impact's ringing makes extra maxima (gaitmap level left resampled from 204.8 to 999.9 Hz: 6 of "
               "32 contacts moved, up to 33.3 ms)")
    return (f"foot rate {rate:g} Hz: the IMU-only contacts, and so stance and swing times, were checked against "
            f"motion capture at 102.4-204.8 Hz; outside {low_hz:g}-{high_hz:g} Hz they move with the rate: {why}; "
            f"compare contacts and stance times at one rate, or resample to it first "
            f"({decision_ref(89, 97, topic='steps')})")
