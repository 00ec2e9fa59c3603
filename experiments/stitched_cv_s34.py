"""Decision L405 (session 34): the stride-time CV of a stitched foot track (L365's partial fallback, L397).

Usage:
    PYTHONPATH=. .venv/bin/python experiments/stitched_cv_s34.py

Fresh simulated users 7710-7717. (A) the route ``straight:10, turn:90, straight:10, turn:90, straight:10`` at the
simulator's default rate, clean and with both force files 300 ms late (L397's recipe); (B) scenario A at 100 Hz, clean
and with both force channels at 0 N from 15 to 17 s (L365's recipe). Per copy: strides, distance, whether the track
is stitched (``contact_source`` rows from both detectors), ``stride_time_cv_pct`` and ``n_cv_strides`` of the
summary, and a hash of the ``stride_time_s`` column (must not change). Prints the table; writes nothing.
It prints the summary of the code it runs on: L405's "after" column was session 34's branch with the rule on; L405
was not adopted, and since decision L594 the rule is the keyword ``clinical.steady_rows(steps, one_source=True)``,
which the summary does not pass (this script now prints the default, the "before" column).
"""

from __future__ import annotations

import hashlib
import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.track.plasys import track_plasys

USERS = range(7710, 7718)
ROUTE = "straight:10, turn:90, straight:10, turn:90, straight:10"


def edited(session, edit):
    """``session`` with ``edit(t, values) -> (t, values)`` applied to its force streams."""
    import copy

    out = copy.copy(session)
    out.streams = dict(session.streams)
    for n in ("fForceA", "fForceB"):
        s = session.streams[n]
        t, v = edit(s.t.copy(), s.values.copy())
        out.streams[n] = type(s)(s.name, t, v)
    return out


def late(t, v):  # L397: both force files 300 ms late
    return t + 0.3, v


def zero(t, v):  # L365: both channels at 0 N from 15 to 17 s
    v[(t >= 15.0) & (t < 17.0)] = 0.0
    return t, v


def row(user: int, case: str, session) -> str:
    res = track_plasys(session)
    summ = res.summary(session)
    src = res.steps["contact_source"].astype(str) if "contact_source" in res.steps else None
    stitched = "yes" if src is not None and {"force", "imu"} <= set(src) else "no"
    st = np.round(res.steps["stride_time_s"].to_numpy(float), 9)
    digest = hashlib.sha1(np.nan_to_num(st, nan=-1.0).tobytes()).hexdigest()[:8]
    cv = summ.get("stride_time_cv_pct")
    return (f"{user} {case:10s} strides {len(res.steps):3d} distance {res.distance_m:7.3f} m stitched {stitched:3s} "
            f"CV {'-' if cv is None else f'{cv:5.2f}'} % over {summ.get('n_cv_strides')} stride_time_s {digest}")


def main() -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    from pdrlearn.sim.route import parse_route

    for user in USERS:
        a = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user))
        print(row(user, "A clean", a))
        print(row(user, "A +300ms", edited(a, late)))
        b = simulate("A", UserProfile.from_seed(user), "normal", rate_hz=100.0)
        print(row(user, "B clean", b))
        print(row(user, "B 0N 15-17", edited(b, zero)))


if __name__ == "__main__":
    main()
