"""Small stand-ins and session edits shared by test files (session 48: one copy instead of one per file)."""

from __future__ import annotations

import numpy as np


class FakeWaistStream:
    rate_hz = 100.0


class FakeWaistSession:
    """What `labelled_asymmetry.track_asymmetry` reads of a session: a 100 Hz lower-back accelerometer and `has`.
    Tests monkeypatch `waist_ic_contacts` to give its contacts."""

    streams = {"wAccelerometer": FakeWaistStream()}
    meta: dict = {}

    def has(self, *names):
        return True


def slow_foot_from(sim, t_change_s: float = 12.0, *, slow_first: bool = False) -> None:
    """B458's edit, in place: from `t_change_s` on (before it with `slow_first`), the foot unit runs at half its rate,
    each kept sample the mean of its pair (a unit that switched between 100 and 50 Hz mid-recording)."""
    from pdrlearn.io.session import Stream

    for name in ("fAccelerometer", "fGyroscope"):
        s = sim.streams[name]
        late = (s.t < s.t[0] + t_change_s) if slow_first else (s.t >= s.t[0] + t_change_s)
        keep = ~late | (np.arange(len(s)) % 2 == 0)
        v = s.values.copy()
        nxt = np.vstack([v[1:], v[-1:]])
        v[late & keep] = 0.5 * (v[late & keep] + nxt[late & keep])
        sim.streams[name] = Stream(name, s.t[keep], v[keep])
