"""Decision L703: the known bias of a foot track's stance, double and single support, stated in the walker's own
terms (ms per contact, and percentage points of this walk's gait cycle) for the set-up that timed the contacts.

Each stance runs from an IC to the same foot's toe-off; each double-support period from one foot's IC to the other
foot's toe-off. A stance that reads ``b`` ms long (``b < 0``: short) therefore moves the stance share of a cycle of
``c`` s by ``100 b / c`` points, each of the cycle's two double-support periods by ``b`` (together ``200 b / c``
points) and the single support (the other foot's swing) by ``-100 b / c`` points.
"""

from __future__ import annotations

import math

from pdrlearn.track.toeoff import TOE_OFF_STANCE_BIAS_MS

#: decision L703: the stance-time error (ours - reference, each set-up's range over its measured walks) by the source
#: of the contacts. "imu": L73's real gaitmap level walks against motion capture (lateral shoe mount, adults, one
#: 1.09 s cycle: ms, ``pdrlearn.track.toeoff.TOE_OFF_STANCE_BIAS_MS``). "force" (decision L730, replacing L703's
#: -4.67 to -4.12 % of the cycle): the simulator's insoles, as two terms - the contact's lag (:data:`FORCE_IC_LAG_PCT`,
#: a share of the cycle) and the toe-off's error (:data:`FORCE_TOE_OFF_MS`, ms)
STANCE_BIAS = {"imu": ((min(TOE_OFF_STANCE_BIAS_MS), max(TOE_OFF_STANCE_BIAS_MS)), "ms"),
               "force": (((2.61, 2.86), (-15.9, -13.4)), "ms and % of the gait cycle")}
#: decision L730: the insoles' contact lag (force onset at 10 % of the stance peak - the simulator's contact, % of the
#: gait cycle; its load rises from zero slope over 10 % of the cycle) and toe-off error (ms: the gyroscope's toe-off,
#: L73 - the drop-off is not gait's toe-off, L388 not adopted), lowest and highest per-walk medians over users
#: 16000-16009 at normal, fast and race pace (0.58-1.18 s cycles; experiments/support_bias_s48_l728.py)
FORCE_IC_LAG_PCT, FORCE_TOE_OFF_MS = STANCE_BIAS["force"][0]
#: decision L737: the lowest foot rate (Hz) the insoles' two terms (L730, measured at 100 Hz) are stated at: on fresh
#: users 16500-16519's 60 walks per rate the tracked - true double support lay within L730's range +-1 point on 60 at
#: 100 and 50 Hz but 50 at 20 Hz (race pace 11 of 20: the 20 Hz contact reads -4.8 ms, not +15.8 ms, late)
FORCE_BIAS_MIN_HZ = 50.0
#: decision L703: where each range was measured (the line names it)
BIAS_SOURCE = {"imu": "IMU-only contacts (against motion capture on gaitmap's real level walks, lateral shoe mount, "
                      "adults; L73)",
               "force": "force-insole contacts (the simulator's insoles: IC at the force onset, late by a share of "
                        "the cycle; toe-off the gyroscope's, early; L730; no real insole reference)"}


#: decision L703 (steps 87): below this gait cycle (s) IMU-only contacts fired 50-80 ms early at the terminal-swing
#: deceleration on some strides (simulated children at 0.34-0.44 s steps, 0.68-0.88 s cycles; none on adults' 1.0-1.2
#: s cycles); steps 91 re-dates them there, so the sign of the support bias is still not claimed (simulated only)
IMU_EARLY_CYCLE_S = 0.95
#: steps decision 92: the median stance-time error (ms) of the simulated children's IMU-only walks after steps 91's
#: re-dating (users 15540-15559, 0.68-0.88 s cycles, session 48), lowest and highest; L703's -23.5 to +23.5 ms (users
#: 14900-14919) was decision 3's
IMU_CHILD_STANCE_MS = (-30.1, -3.8)


def force_unstated(rate_hz: float | None) -> bool:
    """Decision L737: the insoles' bias is not stated at a known foot rate under :data:`FORCE_BIAS_MIN_HZ` (review
    R2 F3: by more than 1 %, the measured rate of a nominal 50 Hz unit, as D7's ``warn_low_rate``)."""
    return rate_hz is not None and math.isfinite(rate_hz) and rate_hz < FORCE_BIAS_MIN_HZ * 0.99  # D7's 1 %


def stance_bias_ms(setup: str, cycle_s: float | None, rate_hz: float | None = None) -> tuple[float, float] | None:
    """Decision L703: the (most, least) negative stance-time error (ms) of ``setup`` at a gait cycle of ``cycle_s``
    (s); None when the set-up's bias is a share of the cycle and the cycle is unknown, or (decision L737) the
    insoles' at a foot rate ``rate_hz`` under :data:`FORCE_BIAS_MIN_HZ`."""
    (lo, hi), unit = STANCE_BIAS[setup]
    if setup == "force" and force_unstated(rate_hz):  # decision L737
        return None
    if unit == "ms":
        return lo, hi
    if cycle_s is None or not math.isfinite(cycle_s) or cycle_s <= 0:
        return None
    (lag_lo, lag_hi), (to_lo, to_hi) = lo, hi  # decision L730: toe-off (ms) - contact lag (% of the cycle)
    return to_lo - 10.0 * lag_hi * cycle_s, to_hi - 10.0 * lag_lo * cycle_s


def setup_of(source) -> str | None:
    """``"imu"`` or ``"force"`` of a track's ``info["stance_source"]`` / gait's ``contact_source`` value(s) (one
    string or a per-foot dict); None when they differ or are unknown (both ranges are then given)."""
    values = set(source.values()) if isinstance(source, dict) else {source}
    kinds = {"force" if v == "force" else "imu" if v in ("imu", "inertial") else None for v in values}
    return kinds.pop() if len(kinds) == 1 else None


def force_rate_text(rate_hz: float | None) -> str | None:
    """Decision L737: the insoles' bias clause at a foot rate under :data:`FORCE_BIAS_MIN_HZ` (its numbers not
    stated), or the rates they were measured at when ``rate_hz`` is unknown; None at a rate they hold at."""
    from pdrlearn.decision_refs import decision_ref

    if rate_hz is None or not math.isfinite(rate_hz):
        return f"measured at {FORCE_BIAS_MIN_HZ:g}-100 Hz foot rates: {decision_ref('L730', 'L737')}"
    if not force_unstated(rate_hz):
        return None
    return (f"with {BIAS_SOURCE['force']} the bias was measured at 100 Hz and holds at {FORCE_BIAS_MIN_HZ:g} Hz; "
            f"at this walk's {rate_hz:g} Hz foot rate it is not stated: on the coarser sample grid the contact's and "
            f"the toe-off's errors differ, and the range missed 10 of 60 simulated 20 Hz walks "
            f"({decision_ref('L730', 'L737')})")


def bias_terms(setup: str | None, cycle_s: float | None, rate_hz: float | None = None) -> str:
    """Decision L703: the clause giving the stance bias of ``setup`` (both set-ups' when None) in ms and, with a
    finite gait cycle ``cycle_s`` (s), in percentage points of that cycle: stance, double support, single support.
    ``rate_hz`` (decision L737): the foot units' rate - under :data:`FORCE_BIAS_MIN_HZ` the insoles' numbers are not
    stated; unknown (None), the clause says the rates they were measured at."""
    setups = [setup] if setup in STANCE_BIAS else list(STANCE_BIAS)
    parts = []
    for s in setups:
        rate_text = force_rate_text(rate_hz) if s == "force" else None  # decision L737
        if rate_text is not None and rate_text.startswith("with "):
            parts.append(rate_text)
            continue
        ms = stance_bias_ms(s, cycle_s)
        if ms is None:  # decision L730: the insoles' two terms without a cycle to add them in
            (lag_lo, lag_hi), (to_lo, to_hi) = STANCE_BIAS[s][0]
            parts.append(f"with {BIAS_SOURCE[s]} each stance reads {-to_hi:.0f}-{-to_lo:.0f} ms plus "
                         f"{lag_lo:.1f}-{lag_hi:.1f} % of the gait cycle short" + (f" ({rate_text})" if rate_text
                                                                                   else ""))
            continue
        text = f"with {BIAS_SOURCE[s]} each stance reads {-ms[1]:.0f}-{-ms[0]:.0f} ms short"
        if cycle_s is not None and math.isfinite(cycle_s) and cycle_s > 0:
            pp = [100.0 * b / 1000.0 / cycle_s for b in ms]
            text += (f", at this walk's {cycle_s:.2f} s gait cycle {pp[0]:+.1f} to {pp[1]:+.1f} percentage points of "
                     f"stance, {2 * pp[0]:+.1f} to {2 * pp[1]:+.1f} of double support and {-pp[1]:+.1f} to "
                     f"{-pp[0]:+.1f} of single support")
        if s == "imu" and cycle_s is not None and cycle_s < IMU_EARLY_CYCLE_S:
            text += (f"; but at a gait cycle under {IMU_EARLY_CYCLE_S:g} s IMU-only contacts are re-dated at the "
                     "stride's rhythm (steps 91; before it some fired 50-80 ms early, steps 87): simulated children's "
                     f"stance read {IMU_CHILD_STANCE_MS[0]:+.0f} to {IMU_CHILD_STANCE_MS[1]:+.0f} ms (steps 92), a "
                     "simulated measure only, so no sign is claimed")
        if rate_text is not None:  # decision L737: the unknown rate's clause
            text += f" ({rate_text})"
        parts.append(text)
    return "; ".join(parts)


def support_note(setup: str | None, cycle_s: float | None, rate_hz: float | None = None) -> str:
    """Decisions L262, L285, L703: ``pdrlearn gait``'s caveat on its double and single support from foot tracks
    (``rate_hz``: the foot units' rate, decision L737)."""
    unsure = setup != "force" and cycle_s is not None and cycle_s < IMU_EARLY_CYCLE_S  # IMU contacts may fire early
    head = ("double and single support from foot units carry a contact bias whose sign is not known at this walk's "
            "short cycle" if unsure else "double support reads low and single support high from foot units")
    return (head + " (decisions L73, L262, L285, L703): " + bias_terms(setup, cycle_s, rate_hz)
            + "; the size depends on the mount and the walker, a measured bias and no bound")
