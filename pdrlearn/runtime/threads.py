"""One thread at a time inside a live tracker (decision E231 for the foot ``Tracker``, E241 for ``WaistTracker``).

A tracker's stream state is not thread-safe; two threads inside it at once interleave silently (trial s40 T4). The
guard is a non-blocking lock: a second thread is refused in one line, never made to wait (a wait would hide the
missing lock of a service that pushes from two threads). Plain Python: the lean runtime's import set.
"""

from __future__ import annotations

import functools
import threading

from pdrlearn.errors import ConcurrentUseError


def new_guard() -> threading.Lock:
    """The per-tracker lock :func:`one_call_at_a_time` takes (a tracker's ``_busy``)."""
    return threading.Lock()


class OwnGuard:
    """Decision E252: a copy of a tracker gets its own :func:`new_guard` (a ``threading.Lock`` cannot be copied or
    pickled, so ``copy.deepcopy(tracker)`` -- a checkpoint, or a "what if" branch of a live stream -- raised "cannot
    pickle '_thread.lock' object"). Both the foot ``Tracker`` and the waist trackers inherit it. ``copy.copy`` gets
    a new guard too, so a shallow copy on another thread is not refused as "a second thread"; it shares the stream
    state (buffers, filters) with the original, so feed a shallow copy only when the original is no longer fed, or
    take a deep copy."""

    def __getstate__(self) -> dict:
        state = dict(self.__dict__)
        state.pop("_busy", None)
        return state

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self._busy = new_guard()


def one_call_at_a_time(method):
    """Decisions E231, E241: ``method`` (a tracker's ``push`` / ``flush``, the waist's ``push_barometer``) refused with
    one :class:`ConcurrentUseError` line when another thread is inside one of the tracker's guarded calls (its
    ``_busy`` lock, :func:`new_guard`; the calls are named by the class's ``_one_at_a_time``). Without it two unlocked
    threads interleaved their pushes silently (trial s40 T4: 89.42 m and a final y of -0.89 m instead of 89.41 m /
    -0.85 m, no error). About 1 us a call (E231)."""

    @functools.wraps(method)
    def guarded(self, *args, **kwargs):
        busy = self._busy
        if not busy.acquire(False):
            raise ConcurrentUseError(
                f"{type(self).__name__}.{method.__name__}: called from a second thread while another thread is inside "
                f"{self._one_at_a_time} of the same tracker; hold one threading.Lock around every such call of a "
                "tracker, or feed it from one thread through a queue (docs/deploying.md, decision E231; the waist "
                "trackers: E241)")
        try:
            return method(self, *args, **kwargs)
        finally:
            busy.release()

    return guarded


__all__ = ["OwnGuard", "new_guard", "one_call_at_a_time"]
