"""Cohort C245: the affected side of a bilateral walk (``gait`` / ``gait-all --affected-side left|right``: a
prosthesis, a paretic or an operated leg) and the words its sides take: a side is "affected" or "unaffected" where
one is named, else "left" / "right". Pure functions; gait_summary.json's ``affected_side`` carries the choice."""

from __future__ import annotations

from pdrlearn.errors import DataError


def check_affected_side(value: str | None, option: str = "--affected-side") -> str | None:
    """Cohort C245: ``value`` lower-cased when it is "left" or "right", None for None; else one error line naming
    ``option`` and the fix."""
    from pdrlearn.track.bilateral import SIDES

    if value is None:
        return None
    side = str(value).strip().lower()
    if side not in SIDES:
        raise DataError(f"{option} {value!r}: not a side; give left or right (the foot of the prosthesis, or the "
                        "paretic or operated leg; decision C245)")
    return side


def side_word(side: str, affected: str | None) -> str:
    """Cohort C245: ``side`` ("left" / "right") as the summary words it: "affected" / "unaffected" when ``affected``
    names a side, else the side itself."""
    if affected not in ("left", "right"):
        return side
    return "affected" if side == affected else "unaffected"


def sides_note(affected: str | None) -> str:
    """Cohort C245: "left = affected" (the L / R columns' key) when a side is named, else ""."""
    return f"{affected} = affected" if affected in ("left", "right") else ""


def toe_clearance_text(walk: dict, affected: str | None = None, *,
                       side_error_m: tuple[float, float] = (0.0056, 0.0381)) -> str | None:
    """Decision L795 (cohort C260): "toe clearance (minimum in mid-swing, medians) left x.xxx m / right y.yyy m", and
    ": left lower" when ``walk``'s ``toe_clearance_lower`` names the clearly lower side (a foot drop), the sides
    worded by ``affected`` (C245); None without either side's ``min_toe_clearance_m_left`` / ``_right``. Decision
    L804: a named side says the gap and the measure's error - ``side_error_m``, the median and the largest |error| of
    the tracked side difference against the simulated toe's over L804's 10 symmetric walkers (users 20710-20719)."""
    v = {s: walk.get(f"min_toe_clearance_m_{s}") for s in ("left", "right")}
    if all(x is None for x in v.values()):
        return None
    text = "toe clearance (minimum in mid-swing, medians) " + " / ".join(
        f"{side_word(s, affected) if affected in ('left', 'right') else s} "
        f"{'-' if v[s] is None else format(v[s], '.3f')} m" for s in ("left", "right"))
    low = walk.get("toe_clearance_lower")
    if low in ("left", "right") and None not in v.values():
        gap = 1000.0 * abs(float(v["left"]) - float(v["right"]))
        text += (f": {side_word(low, affected)} lower by {gap:.0f} mm (a dragging toe, e.g. foot drop - or the "
                 f"measure's error: in simulated symmetric walkers the sides' difference read off by a median "
                 f"{1000.0 * side_error_m[0]:.0f} mm, up to {1000.0 * side_error_m[1]:.0f} mm, L804)")
    return text + " (L795)"
