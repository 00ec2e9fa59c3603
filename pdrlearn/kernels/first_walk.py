"""Decision E215 (docs/decisions/export.md): L494's first-walk heading reference, applied once and causally to a
streamed foot-headed track (``track --streaming``, the runtime ``Tracker``: one implementation, stride by stride).

Offline, L494 subtracts the first walk's direction (the circular mean of the first
:data:`~pdrlearn.track.plasys.WALK_REFERENCE_STRIDES` walking strides' travel headings) from a foot-only heading,
so a foot unit yawed on the shoe no longer turns the path. A stream knows that direction only at the end of its first
walk: :class:`FirstWalk` collects the placed directions of the foot-headed strides longer than L494's walking stride
and, at the 4th, returns the angle to turn the heading by from then on, once.
"""

from __future__ import annotations

import cmath
import math

#: decision E215: the streamed track re-references its foot-only heading once at the end of the first walk (L494's
#: rule, causal); False = the heading's 0 stays the foot unit's facing at the start
STREAMED_FIRST_WALK = False
#: decision L494: the walking strides the first walk's direction is read from (plasys.WALK_REFERENCE_STRIDES)
WALK_STRIDES = 4
#: decision L494 (amended): a walking stride is longer than the frame inference's ``MIN_STRIDE_M`` (m, D8's own
#: threshold for the strides' direction; frame_inference.MIN_STRIDE_M, pinned equal by a test)
WALK_MIN_M = 0.2


class FirstWalk:
    """Decision E215: :meth:`stride` each stride before it is placed; it returns the angle (rad) to subtract from the
    heading from that stride on (the stride that ends the first walk, once), else None. The strides placed before keep
    the unit's facing and the position is not moved back (the steps reported stay consistent: their lengths along
    their headings sum to the track, as a fix filter and ``pdrlearn run``'s rows read it). ``start``: the stream's
    start heading (rad; the reference is the walk's direction less it, as offline's)."""

    def __init__(self, start: float = 0.0, enabled: bool | None = None):
        self.start = float(start)
        self.heads: list[float] = []
        self.done = not (STREAMED_FIRST_WALK if enabled is None else enabled)
        self.angle: float | None = None  # the angle applied (None: not applied)
        self.n_before = 0  # the strides placed before it was applied

    def stop(self) -> None:
        """Not applied from now on (a waist-headed stride or a fix set the frame, decision E215)."""
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
        self.n_before -= 1  # the stride that ends the walk is placed in the new frame
        return self.angle

    def line(self, t: float) -> str:
        """The warning line of the applied reference at time ``t`` (s)."""
        return (f"the foot-only heading's 0 is the first walk's direction (decision L494), known at {t:.1f} s after "
                f"{WALK_STRIDES} walking strides: the heading turned by {math.degrees(-self.angle):+.1f} deg from then "
                f"on; the {self.n_before} stride(s) placed before keep the foot unit's facing as 0 (decision E215)")

