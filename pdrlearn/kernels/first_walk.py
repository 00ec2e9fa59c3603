"""Decision E215 (docs/decisions/export.md): L494's first-walk heading reference on a streamed foot-headed track
(``track --streaming``, the runtime ``Tracker``: one implementation, stride by stride).

Offline, L494 subtracts the first walk's direction (the circular mean of the first
:data:`~pdrlearn.track.plasys.WALK_REFERENCE_STRIDES` walking strides' travel headings) from a foot-only heading,
so a foot unit yawed on the shoe no longer turns the path. A stream knows that direction only at the end of its first
walk: :class:`FirstWalk` collects the placed directions of the foot-headed strides longer than L494's walking stride
and, at the 4th, says it in one line. E215 measured applying it there (the heading turned from that stride on) and did
not adopt it as the default: the line then says the streamed heading's 0 is the unit's facing and how far the first
walk heads from it. Applying it is an option (decision E222: the keyword ``first_walk`` of
``track_plasys(streaming=True)`` and the runtime ``Tracker``, ``enabled`` here; no module switch, W413).
"""

from __future__ import annotations

import cmath
import math

#: decision E215: the not-applied line is said when the first walk heads at least this far (deg) from the unit's facing
#: (a choice, not fitted: half the 20 deg yaw of L494's trial; a unit mounted straight reads a few degrees, and a line
#: on every stream of it said nothing); ``info["first_walk_deg"]`` of ``track --streaming`` holds the angle always
SAY_MIN_DEG = 10.0
#: decision L494: the walking strides the first walk's direction is read from (plasys.WALK_REFERENCE_STRIDES)
WALK_STRIDES = 4
#: decision L494 (amended): a walking stride is longer than the frame inference's ``MIN_STRIDE_M`` (m, D8's own
#: threshold for the strides' direction; frame_inference.MIN_STRIDE_M, pinned equal by a test)
WALK_MIN_M = 0.2


class FirstWalk:
    """Decision E215: :meth:`stride` each stride before it is placed; at the stride that ends the first walk (once)
    it returns the angle (rad) to subtract from the heading from that stride on -- the first walk's direction less the
    start heading ``start`` (rad) when ``enabled``, else 0.0 -- and the caller
    gives :meth:`line`; None at every other stride. Strides placed before keep the unit's facing and the position is
    not moved back (the reported steps' lengths along their headings still sum to the track, as a fix filter and
    ``pdrlearn run``'s rows read it). Decision E215: ``enabled=True`` re-references the foot-only heading once, at
    the end of the first walk (L494's rule, causal; the strides before keep the facing); False (the default:
    measured, not adopted) keeps its 0 the foot unit's facing at the start, and :meth:`line` says how far the first
    walk heads from it (decision E222: a keyword, no module switch)."""

    def __init__(self, start: float = 0.0, enabled: bool = False):
        self.start = float(start)
        self.apply = bool(enabled)
        self.heads: list[float] = []
        self.done = False
        self.angle: float | None = None  # the first walk's direction less the start heading (rad), once known
        self.n_before = 0  # the strides placed before it was known

    def stop(self) -> None:
        """Not judged from now on (a waist-headed stride or a used fix set the frame, a resumed tracker)."""
        self.done = True

    def stride(self, foot_headed: bool, direction: float, horizontal_m: float) -> float | None:
        if self.done:
            return None
        if not foot_headed:
            self.done = True
            return None
        self.n_before += 1
        if not (abs(horizontal_m) > WALK_MIN_M and math.isfinite(direction)):
            return None
        self.heads.append(direction - self.start)
        if len(self.heads) < WALK_STRIDES:
            return None
        self.done = True
        self.angle = cmath.phase(sum(cmath.exp(1j * h) for h in self.heads) / len(self.heads))  # L494's circular mean
        self.n_before -= 1  # the stride that ends the walk
        return self.angle if self.apply else 0.0

    def line(self, t: float) -> str | None:
        """The warning line at time ``t`` (s) of the stride that ended the first walk (None: not applied and the walk
        heads less than :data:`SAY_MIN_DEG` from the unit's facing)."""
        deg = math.degrees(self.angle)
        if not self.apply and abs(deg) < SAY_MIN_DEG:
            return None
        if self.apply:
            return (f"the foot-only heading's 0 is the first walk's direction (decision L494), known at {t:.1f} s "
                    f"after {WALK_STRIDES} walking strides: the heading turned by {-deg:+.1f} deg from then on; the "
                    f"{self.n_before} stride(s) placed before keep the foot unit's facing as 0 (decision E215)")
        return (f"the streamed foot-only heading's 0 is the foot unit's facing at the start, not the first walk's "
                f"direction (L494 is applied offline only, decision E215): the first walk heads {deg:+.1f} deg from "
                "it, so a unit yawed on the shoe turns this path by about that; `pdrlearn track` without --streaming "
                "references the first walk")
