"""Decision L729: the gait cycles whose toe-offs come before the other foot's contact (a flight) - counted, timed and
told instead of left out of the double support without a word.

A gait cycle of foot F (its IC to its next) has two hand-overs: the other foot's toe-off against F's contact, and
F's toe-off against the other foot's contact. In walking each overlaps (a double-support period, Perry & Burnfield
2010, Gait Analysis ch. 1); when a toe-off comes first, neither foot is on the ground until the contact (a flight:
race walking's loss of contact, running) - or the two units' clocks differ, which moves one hand-over's overlap down
and the other's up by the offset (decision L284). A flight after both feet's toe-offs is a loss of contact's pattern;
flights after one foot's toe-off only, the other hand-over's double support longer, a clock offset's.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.kernels.gait_values import cycle_flights  # noqa: F401  (decision E327: moved there, re-exported)


def flight_after(side: str, other: str, after_other: float, after_own: float) -> str | None:
    """Decision L729: the foot (``side`` / ``other``) whose toe-off started the cycle's flight, ``"both"``, or None
    without a flight."""
    feet = [f for f, v in ((other, after_other), (side, after_own)) if v > 0]
    return None if not feet else feet[0] if len(feet) == 1 else "both"


#: decision L746: what the flight line says of backward cycles' flights (backward walking lands toe first; L329)
BACKWARD_FLIGHT = ("backward walking, which lands toe first and whose contact and toe-off detection no measurement "
                   "covers (L329): no loss of contact or clock offset is read from them")


def per_cycle(flights) -> str:
    """Decision C268: the mean flight of ``flights`` (gait_cycles.csv rows with a flight) per gait cycle - its two
    flights summed - and per step (half: a cycle holds two steps), for the line."""
    mean = 1000 * float(flights["flight_time_s"].mean())
    return f"{mean:.0f} ms per gait cycle on average (its two flights summed; {mean / 2:.0f} ms per step)"


def flight_warning(walk: dict, cycles) -> str | None:
    """Decision L729: one line when the walk's cycles (``cycles``: gait_cycles.csv's rows with ``flight_time_s``
    and ``flight_after``) have a flight, naming both causes (a loss of contact; a clock offset, L284); None
    without one. Decision L746: flights in cycles of ``kind`` backward are counted apart and named as backward
    walking's (:data:`BACKWARD_FLIGHT`), not blamed on race walking or a clock; the line's count, mean and feet are
    the other cycles'."""
    if not (walk.get("n_flight_cycles") or 0):
        return None
    fl = cycles[cycles["flight_time_s"] > 0]
    back = (fl["kind"] == "backward").to_numpy(bool) if "kind" in fl else np.zeros(len(fl), bool)  # L746
    of = int(cycles["flight_time_s"].notna().sum())  # L736: every cycle with both toe-offs in their strides
    ref = decision_ref("L729", "L284", "L746") if back.any() else decision_ref("L729", "L284")
    if back.all():  # decision L746: only backward walking's cycles
        return (f"bilateral gait: {len(fl)} of {of} gait cycles have a toe-off before the other foot's contact "
                f"({per_cycle(fl)}), all of them in {BACKWARD_FLIGHT} "
                f"({ref})")
    fl, n_back = fl[~back], int(back.sum())
    by = {f: int((fl["flight_after"] == f).sum()) for f in ("left", "right", "both")}
    off = walk.get("clock_offset_s")
    off_txt = "" if off is None else f" (clock_offset_s {1000 * off:+.0f} ms)"
    back_txt = "" if not n_back else f"; {n_back} more in {BACKWARD_FLIGHT}"
    return (f"bilateral gait: {len(fl)} of {of} gait cycles have a flight - a foot's toe-off before the other foot's "
            f"contact, {per_cycle(fl)} with neither foot on the ground "
            f"(after the left foot's toe-off in {by['left']}, the right's in {by['right']}, both in {by['both']}): a "
            "loss of contact (race walking's fault, running) or a clock offset between the two units, which shortens "
            "the double support after one foot's toe-off and lengthens it after the other's - flights after one "
            f"foot's toe-off only point to the clock{off_txt}{back_txt}. These cycles give no double or single "
            "support (n_support_cycles counts the others); gait_cycles.csv's flight_time_s and flight_after give "
            f"each ({ref})")
