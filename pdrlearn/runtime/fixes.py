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

import numpy as np

from pdrlearn.errors import DataError

log = logging.getLogger(__name__)


class FixInput:
    """``add_fix`` / ``fix_stats`` for a tracker; the tracker calls :meth:`_fuse_step` on every step it reports."""

    def _init_fixes(self, start_xy, innovation_gate: bool | None = None) -> None:
        """The live fix filter from ``start_xy``; ``innovation_gate`` (decision D35: D31's gate, an option) None
        keeps the tracker's setting (a restart re-initialises the filter with it)."""
        from pdrlearn.kernels.fixes import FixConfig, LiveFixes, initial_fix_sigma

        if innovation_gate is not None:
            if not isinstance(innovation_gate, bool | np.bool_):
                raise DataError(f"innovation_gate={innovation_gate!r} must be True or False (decision D31's gate)")
            self._innovation_gate = bool(innovation_gate)
        gate = getattr(self, "_innovation_gate", False)
        # add_fix takes x, y in the track's frame: ``track --fixes``' start sigma for an x, y fix file (D19)
        self._fixes = LiveFixes(FixConfig(innovation_gate=gate), start_xy=start_xy,
                                initial_sigma_m=initial_fix_sigma(start_known=True, xy_fixes=True))
        self.fix_position: tuple[float, float] | None = None  # the fused position once a fix was used
        self._fix_warned = False

    def add_fix(self, t: float, x: float, y: float, accuracy_m: float | None = None, *,
                sigma_m: float | None = None) -> None:
        """Give the tracker a position fix: ``x``, ``y`` (m, ENU, the track's frame) at time ``t`` (s, the pushed
        clock), with its 68 % horizontal radius ``accuracy_m`` (m, as a fix file's column) or its per-axis standard
        deviation ``sigma_m`` (m). It is used at the step whose interval holds ``t`` (decision D14), so push it
        before that step is reported: a fix whose step was reported already is counted late, not used (D20)."""
        from pdrlearn.kernels.fixes import sigma_from_accuracy

        try:
            t, x, y = float(t), float(x), float(y)
        except (TypeError, ValueError):
            raise DataError(f"add_fix({t!r}, {x!r}, {y!r}): t (s), x and y (m) must be numbers") from None
        if (accuracy_m is None) == (sigma_m is None):
            raise DataError("add_fix: give the fix's accuracy_m (68 % radius, m) or sigma_m (per-axis SD, m), one of "
                            "them")
        s = float(sigma_from_accuracy(accuracy_m)) if sigma_m is None else float(sigma_m)
        if not all(math.isfinite(v) for v in (t, x, y, s)) or s <= 0:
            raise DataError(f"add_fix(t={t}, x={x}, y={y}): t, x, y must be finite and the accuracy > 0 m; drop "
                            "this fix")
        from pdrlearn.kernels.fixes import FIX_AHEAD_MAX_S, FIX_TIME_HINT

        now = self._pushed_until()
        if now is not None and t > now + FIX_AHEAD_MAX_S:  # decision E212: refused now, not held until flush()
            raise DataError(f"add_fix(t={t:g}, x={x:g}, y={y:g}): t is {t - now:.0f} s after the newest pushed sample "
                            f"({now:.1f} s): {FIX_TIME_HINT}; give t in seconds (t={t / 1000.0:g} if it was ms)")
        self._fixes.add(t, (x, y), s)

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
