"""Numpy kernels of a lower-back unit re-clipped on the belt (decisions W623, W624; docs/decisions/waist.md).

Shared by the offline search (:mod:`pdrlearn.waist.reclip`) and the live trackers (numpy only, the runtime's rule):
the samples that walk, the rotations between two measured frames, and the live watch, which reads the unit's
gravity while walking only (the forward needs D8's inference, offline). Not from a seed: the bounds are W623's.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.decision_refs import decision_ref


def _unit(v: np.ndarray) -> np.ndarray:
    n = float(np.linalg.norm(v))
    return v / n if n > 0 else v


def walking_samples(acc: np.ndarray, fs: float, *, window_s: float = 2.0, walk_std: float = 0.5,
                    skip: np.ndarray | None = None) -> np.ndarray:
    """Decision W623: the samples that walk: the standard deviation of |a| over the centred ``window_s`` reaches
    ``walk_std`` m/s^2 (W4's motion gate on the norm, which needs no axis, as D8's walking up reads it); ``skip``
    (a sample mask: bridged samples of a gap) left out."""
    norm = np.linalg.norm(np.asarray(acc, dtype=float), axis=1)
    n = max(int(round(window_s * fs)), 2)
    k = np.ones(n) / n
    m1 = np.convolve(norm, k, "same")
    m2 = np.convolve(norm * norm, k, "same")
    walk = np.sqrt(np.maximum(m2 - m1 * m1, 0.0)) >= walk_std
    return walk if skip is None else walk & ~np.asarray(skip, dtype=bool)


def two_vector_rotation(up_from: np.ndarray, fwd_from: np.ndarray, up_to: np.ndarray,
                        fwd_to: np.ndarray) -> np.ndarray:
    """The rotation (3, 3) taking ``up_from`` onto ``up_to`` and the horizontal part of ``fwd_from`` onto that of
    ``fwd_to`` (the two-vector, TRIAD alignment: up exact, forward about it)."""
    def basis(u, f):
        u = _unit(np.asarray(u, dtype=float))
        f = np.asarray(f, dtype=float)
        f = _unit(f - (f @ u) * u)
        return np.column_stack([f, np.cross(u, f), u])

    return basis(up_to, fwd_to) @ basis(up_from, fwd_from).T


def tilt_rotation(up_from: np.ndarray, up_to: np.ndarray) -> np.ndarray:
    """The smallest rotation (3, 3) taking ``up_from`` onto ``up_to`` (Rodrigues)."""
    u, v = _unit(np.asarray(up_from, float)), _unit(np.asarray(up_to, float))
    axis = np.cross(u, v)
    s, c = float(np.linalg.norm(axis)), float(u @ v)
    if s < 1e-12:
        return np.eye(3)
    k = axis / s
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


def rotation_angle_deg(R: np.ndarray) -> float:
    """The angle (deg) of a rotation matrix."""
    return float(np.degrees(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0))))


class LiveReclipWatch:
    """Decisions W623 / W624, live: every ``check_s`` seconds the unit's gravity while walking (the mean specific
    force of the last ``span_s`` of walking, :func:`walking_samples`, in the last ``keep_s`` of pushed sensor-frame
    samples, at least ``min_walk_s`` of it) is compared with a reference, the first one measured (after a re-clip: the
    first measured wholly after it); a turn of at least ``min_deg`` is a re-clip: :meth:`push` returns its line once,
    and :meth:`extra_sigma_m` grows the position radius by the distance walked since times sin(min(angle, 90 deg))
    (the heading error a turn of that angle can leave). A re-clip about the vertical alone is not seen live (the
    forward needs D8's inference, offline), and the live track is not re-framed."""

    def __init__(self, fs: float, *, span_s: float = 20.0, check_s: float = 10.0, keep_s: float = 60.0,
                 min_deg: float = 25.0, min_walk_s: float = 10.0):
        self.fs = float(fs)
        self._span, self._check, self._keep = span_s, check_s, keep_s
        self._min_deg, self._min_walk = min_deg, min_walk_s
        self._t = np.zeros(0)
        self._a = np.zeros((0, 3))
        self._ref: np.ndarray | None = None
        self._after = -np.inf
        self._next: float | None = None
        #: the re-clips found: ``[time_s, angle_deg, metres walked since]``
        self.found: list[list[float]] = []

    def push(self, t: np.ndarray, acc: np.ndarray) -> str | None:
        """Add sensor-frame samples; the line of a re-clip found by this push, else None."""
        self._t = np.concatenate([self._t, np.asarray(t, dtype=float)])
        self._a = np.concatenate([self._a, np.asarray(acc, dtype=float)])
        if self._t[-1] - self._t[0] > self._keep:
            i = int(np.searchsorted(self._t, self._t[-1] - self._keep))
            self._t, self._a = self._t[i:], self._a[i:]
        now = float(self._t[-1])
        if self._next is None:
            self._next = now + self._check
        if now < self._next:
            return None
        self._next = now + self._check
        walk = np.flatnonzero(walking_samples(self._a, self.fs))[-int(round(self._span * self.fs)):]
        if len(walk) < self._min_walk * self.fs or self._t[walk[0]] < self._after:
            return None
        up = _unit(self._a[walk].mean(axis=0))
        if self._ref is None:
            self._ref = up
            return None
        ang = float(np.degrees(np.arccos(np.clip(up @ self._ref, -1.0, 1.0))))
        if ang < self._min_deg:
            return None
        self._ref, self._after = None, now  # re-armed by the first gravity measured wholly after this one
        self.found.append([now, ang, 0.0])
        return (f"the lower-back unit was re-clipped before {now:.1f} s: its gravity while walking turned {ang:.0f} "
                "deg in the unit; the live track keeps its first frame, so its heading may be off from here: the "
                f"position radius grows with the distance walked since ({decision_ref('W623')}, "
                f"{decision_ref('W624')})")

    def extra_sigma_m(self, length_m: float) -> float:
        """The radius (m) the re-clips found add after a step of ``length_m`` (0 without one)."""
        extra = 0.0
        for r in self.found:
            r[2] += abs(float(length_m))
            extra += r[2] * float(np.sin(np.radians(min(r[1], 90.0))))
        return extra


__all__ = ["walking_samples", "two_vector_rotation", "tilt_rotation", "rotation_angle_deg", "LiveReclipWatch"]
