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

#: decision L703: the stance-time error (ms, ours - reference, each set-up's range over its measured walks) by the
#: source of the contacts. "imu": L73's real gaitmap level walks against motion capture (lateral shoe mount, adults,
#: ``pdrlearn.track.toeoff.TOE_OFF_STANCE_BIAS_MS``); "force": the simulator's insoles (IC at the force onset, late;
#: toe-off at the drop-off, early), measured in session 47 on simulated children and adults (no real insole reference)
STANCE_BIAS_MS = {"imu": (min(TOE_OFF_STANCE_BIAS_MS), max(TOE_OFF_STANCE_BIAS_MS)), "force": (-36.0, -33.0)}
#: decision L703: where each range was measured (the line names it)
BIAS_SOURCE = {"imu": "IMU-only contacts against motion capture on gaitmap's real level walks (lateral shoe mount, "
                      "adults; L73)",
               "force": "force-insole contacts on the simulator's insoles (IC at the force onset, late; toe-off at "
                        "the drop-off, early; no real insole reference)"}


def setup_of(source) -> str | None:
    """``"imu"`` or ``"force"`` of a track's ``info["stance_source"]`` / gait's ``contact_source`` value(s) (one
    string or a per-foot dict); None when they differ or are unknown (both ranges are then given)."""
    values = set(source.values()) if isinstance(source, dict) else {source}
    kinds = {"force" if v == "force" else "imu" if v in ("imu", "inertial") else None for v in values}
    return kinds.pop() if len(kinds) == 1 else None


def bias_terms(setup: str | None, cycle_s: float | None) -> str:
    """Decision L703: the clause giving the stance bias of ``setup`` (both set-ups' when None) in ms and, with a
    finite gait cycle ``cycle_s`` (s), in percentage points of that cycle: stance, double support, single support."""
    setups = [setup] if setup in STANCE_BIAS_MS else list(STANCE_BIAS_MS)
    parts = []
    for s in setups:
        lo, hi = STANCE_BIAS_MS[s]
        text = f"with {BIAS_SOURCE[s]} each stance reads {-hi:.0f}-{-lo:.0f} ms short"
        if cycle_s is not None and math.isfinite(cycle_s) and cycle_s > 0:
            pp = [100.0 * b / 1000.0 / cycle_s for b in (lo, hi)]
            text += (f", at this walk's {cycle_s:.2f} s gait cycle {pp[0]:+.1f} to {pp[1]:+.1f} percentage points of "
                     f"stance, {2 * pp[0]:+.1f} to {2 * pp[1]:+.1f} of double support and {-pp[1]:+.1f} to "
                     f"{-pp[0]:+.1f} of single support")
        parts.append(text)
    return "; ".join(parts)


def support_note(setup: str | None, cycle_s: float | None) -> str:
    """Decisions L262, L285, L703: ``pdrlearn gait``'s caveat on its double and single support from foot tracks."""
    return ("double support reads low and single support high from foot units (decisions L73, L262, L285, L703): "
            + bias_terms(setup, cycle_s) + "; the size depends on the mount and the walker, a measured bias and no "
            "bound")
