"""Position fixes for the live trackers (decisions D19-D21): ``tracker.add_fix(t, x, y, accuracy_m)``.

A fix (a map-matched door, a beacon, a GNSS position; ENU metres in the track's frame, at time ``t`` on the pushed
clock) is used at the step whose interval holds it, as ``pdrlearn track --fixes`` uses a fix file (decision D14):
:class:`pdrlearn.kernels.fixes.LiveFixes`, the step EKF of ``SporadicFixFusion`` one step at a time. Every reported
step feeds it; once a fix was used, the steps carry its causal (real-time) estimate as ``x``, ``y`` -- the ``x_rt``,
``y_rt`` of offline ``aid_track`` on the same steps and fixes -- and :attr:`fix_position` holds it.
"""

from __future__ import annotations

import logging
import math
import numbers

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.runtime.threads import new_guard, one_call_at_a_time

log = logging.getLogger(__name__)

#: decision E256: what each ``add_fix`` argument is, for its one-line refusal
_FIX_ARGS = {"t": "time in seconds on the pushed clock", "x": "east in metres (the track's frame)",
             "y": "north in metres (the track's frame)", "accuracy_m": "68 % horizontal radius in metres",
             "sigma_m": "per-axis standard deviation in metres"}


def _fix_number(name: str, value) -> float:
    """Decision E256: ``add_fix``'s argument ``name`` as a finite float, or one :class:`DataError` line naming it.
    A real number only (a Python or numpy int / float): a string, a bool, None or an array is refused, not parsed
    (``float("5")`` accepted a string before E256, and an array accuracy escaped as a numpy TypeError)."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        raise DataError(f"add_fix: {name}={value!r} is a {type(value).__name__}: t (s), x and y (m) must be numbers; "
                        f"give {name} as a float, the fix's {_FIX_ARGS[name]}")
    v = float(value)
    if not math.isfinite(v):
        raise DataError(f"add_fix: {name}={v} is not finite: t, x, y must be finite and the accuracy > 0 m; give "
                        f"{name} as the fix's {_FIX_ARGS[name]}, or drop this fix")
    return v


class FixInput:
    """``add_fix`` / ``fix_stats`` for a tracker; the tracker calls :meth:`_fuse_step` on every step it reports."""

    _one_at_a_time = "add_fix"  # decision E256: a tracker names all its guarded calls (E231, E241)

    def _init_fixes(self, start_xy, innovation_gate: bool | None = None) -> None:
        """The live fix filter from ``start_xy``; ``innovation_gate`` (decision D35: D31's gate, an option) None
        keeps the tracker's setting (a restart re-initialises the filter with it)."""
        from pdrlearn.kernels.fixes import FixConfig, LiveFixes, initial_fix_sigma

        if innovation_gate is not None:
            if not isinstance(innovation_gate, bool | np.bool_):
                raise DataError(f"innovation_gate={innovation_gate!r} must be True or False (decision D31's gate)")
            self._innovation_gate = bool(innovation_gate)
        gate = getattr(self, "_innovation_gate", False)
        if not hasattr(self, "_busy"):  # decision E256: add_fix takes the tracker's E231 guard (its own, alone)
            self._busy = new_guard()
        # add_fix takes x, y in the track's frame: ``track --fixes``' start sigma for an x, y fix file (D19)
        self._fixes = LiveFixes(FixConfig(innovation_gate=gate), start_xy=start_xy,
                                initial_sigma_m=initial_fix_sigma(start_known=True, xy_fixes=True))
        self.fix_position: tuple[float, float] | None = None  # the fused position once a fix was used
        self._fix_warned = False

    @one_call_at_a_time
    def add_fix(self, t: float, x: float, y: float, accuracy_m: float | None = None, *,
                sigma_m: float | None = None) -> None:
        """Give the tracker a position fix: ``x``, ``y`` (m, ENU, the track's frame) at time ``t`` (s, the pushed
        clock), with its 68 % horizontal radius ``accuracy_m`` (m, as a fix file's column) or its per-axis standard
        deviation ``sigma_m`` (m). It is used at the step whose interval holds ``t`` (decision D14), so push it
        before that step is reported: a fix whose step was reported already is counted late, not used (D20); fixes
        given out of time order are used in time order while their steps are not reported (D14's sorted table).
        A bad fix is refused in one :class:`DataError` line naming the argument (decision E256), and a second
        thread inside the tracker with :class:`ConcurrentUseError` (E231's guard)."""
        from pdrlearn.kernels.fixes import FIX_AHEAD_MAX_S, FIX_TIME_HINT, sigma_from_accuracy

        if (accuracy_m is None) == (sigma_m is None):
            raise DataError("add_fix: give the fix's accuracy_m (68 % radius, m) or sigma_m (per-axis SD, m), one of "
                            "them")
        t, x, y = (_fix_number(name, v) for name, v in (("t", t), ("x", x), ("y", y)))
        spread = "accuracy_m" if sigma_m is None else "sigma_m"
        s = _fix_number(spread, accuracy_m if sigma_m is None else sigma_m)
        if not s > 0:  # decision E256: a fix without a spread has no weight in the filter
            raise DataError(f"add_fix(t={t:g}, x={x:g}, y={y:g}): {spread}={s:g}: t, x, y must be finite and the "
                            f"accuracy > 0 m; give the fix's {_FIX_ARGS[spread]}, or drop this fix")
        if sigma_m is None:
            s = float(sigma_from_accuracy(s))
        now = self._pushed_until()
        if now is not None and t > now + FIX_AHEAD_MAX_S:  # decision E212: refused now, not held until flush()
            raise DataError(f"add_fix(t={t:g}, x={x:g}, y={y:g}): t is {t - now:.0f} s after the newest pushed sample "
                            f"({now:.1f} s): {FIX_TIME_HINT}; give t in seconds (t={t / 1000.0:g} if it was ms)")
        first = self._pushed_from()
        if first is not None and t < first - FIX_AHEAD_MAX_S:  # decision E256: E212's bound the other way
            raise DataError(f"add_fix(t={t:g}, x={x:g}, y={y:g}): t is {first - t:.0f} s before the first pushed "
                            f"sample ({first:.1f} s): a fix on another clock? give t in seconds on the pushed "
                            "samples' clock")
        self._fixes.add(t, (x, y), s)

    def _pushed_from(self) -> float | None:
        """Decision E256: the time (s) of the first pushed sample, None before any: the foot Tracker's
        ``min(_first_t, _oldest)`` (as its stopped-stream check reads it), the waist stream's track start."""
        first = min(getattr(self, "_first_t", math.inf), getattr(self, "_oldest", math.inf),
                    math.inf if self._fixes.t_start is None else self._fixes.t_start)
        return float(first) if math.isfinite(first) else None

    def _pushed_until(self) -> float | None:
        """Decision E212: the time (s) of the newest pushed sample (the foot Tracker's ``_latest``, the waist
        stream's ``_last_t``), None before any."""
        for name in ("_latest", "_last_t"):
            v = getattr(self, name, None)
            if v is not None and math.isfinite(v):
                return float(v)
        return None

    def fix_stats(self) -> dict:
        """The fix counters of ``track --fixes``' summary (decision D17): ``fixes_read``, ``fixes_used``,
        ``fixes_unused`` = ``fixes_superseded`` + ``fixes_outside_track`` + ``fixes_late`` (D20) + ``fixes_rejected``
        (D31)."""
        return self._fixes.stats()

    def _fuse_step(self, start_s: float, end_s: float, length: float, heading: float):
        """The step's fused position (x, y), or None while no fix has been used (the step keeps its PDR position,
        which the filter's estimate equals to rounding until then)."""
        n_rejected = len(self._fixes.rejected)
        if self._fixes.state is None:  # decision D50: start fixes from the first pushed sample on, as track --fixes
            self._fixes.t_first = self._pushed_from()
        xy, _ = self._fixes.step(start_s, end_s, length, heading)
        if len(self._fixes.rejected) > n_rejected:  # decision D31: each rejected fix named as it is rejected
            from pdrlearn.kernels.fixes import rejected_phrase

            msg = (f"fix rejected by the innovation gate (more than 3 sigma from the filter's estimate, decision "
                   f"D31): {rejected_phrase(self._fixes.rejected[n_rejected:])}")
            self.warnings.append(msg)
            log.warning("%s", msg)
        if self._fixes.used:
            self.fix_position = (float(xy[0]), float(xy[1]))
            return self.fix_position
        return None

    def _warn_unused_fixes(self) -> None:
        """Decision D21 (D18 live): at the end of a stream, one line when pushed fixes were not used."""
        st = self._fixes.stats()
        if not st["fixes_unused"] or self._fix_warned:
            return
        self._fix_warned = True
        why = [f"{st[k]} {what}" for k, what in (("fixes_superseded", "superseded by a later fix in the same step"),
                                                  ("fixes_outside_track", "outside the tracked steps"),
                                                  ("fixes_late", "pushed after their step was reported (D20)"),
                                                  ("fixes_rejected", "rejected by the innovation gate (D31)"))
               if st[k]]
        msg = f"{st['fixes_unused']} of {st['fixes_read']} fixes not used: {', '.join(why)}"
        self.warnings.append(msg)
        log.warning("%s", msg)
