"""Decision L712's adoption rule (docs/decisions/localization.md): the foot gyroscope's bias interpolated in time
between the stands over 30 s (``rest_drift`` true) against the set-up standstill's one bias (false, = main).

(a) / (b) / (f): fresh simulated users 15500-15539, four walking bouts each ended by a 30-60 s stand; (c) short walks
of the same users with a 20 s stand; (d) the real gaitmap foot recordings; (e) the demo table's scenario D (user 1);
for information T2's long_nw (L711) when its folder is given: ``python experiments/foot_rest_drift_l712.py [LONG_NW]``.
``--tau TAU`` (information, after the rule's run): (a) / (b) only, on the same users simulated with S110's bounded
gyroscope bias drift (``gyro_bias_tau_s`` TAU).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys

USERS = range(15500, 15540)
SHORT = "stand:5, straight:60, stand:20, straight:60, stand:5"
DATA = Path("/work/shared/data")


def long_route(user: int) -> str:
    """``stand:10`` then 4 x (straight 100 m, a 90 deg curve of 10 m, straight 80 m, a stand of 30-60 s)."""
    bouts = [f"straight:100, curve:90:10, straight:80, stand:{30 + 10 * ((user + b) % 4)}" for b in range(4)]
    return "stand:10, " + ", ".join(bouts)


def heading_errors(result, session) -> np.ndarray:
    """Per stride (deg): the track's heading (unwrapped, less its first stride's) against the simulated
    trajectory's heading at the stride's middle (less the same at the first stride)."""
    st, tr = result.steps, session.trajectory
    mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
    h = np.unwrap(st["heading_rad"].to_numpy(float))
    ht = np.interp(mid, tr["t"].to_numpy(float), np.unwrap(tr["heading_rad"].to_numpy(float)))
    return np.degrees((h - h[0]) - (ht - ht[0]))


def track(session, on: bool, extra: dict | None = None, **kw):
    """The plasys track with ``rest_drift`` ``on``; ``extra``: more foot settings with it on (L731's
    ``rest_drift_by``)."""
    params = {"rest_drift": on, **(extra or {} if on else {})}
    return track_plasys(session, method=kw.pop("method", "M3"), model=kw.pop("model", "oracle"), params=params, **kw)


def strides_change(a, b) -> float:
    """Largest |change| of the strides' length_m and heading_rad (inf when the stride counts differ)."""
    if len(a.steps) != len(b.steps):
        return float("inf")
    return max(float(np.max(np.abs(a.steps[c].to_numpy(float) - b.steps[c].to_numpy(float)), initial=0.0))
               for c in ("length_m", "heading_rad"))


def measure(user: int, rate_hz: float = 20.0, extra: dict | None = None):
    """One user's row ``(user, h0, h1, p0, p1, f0, f1, c)`` (false -> true: foot-only final heading error, deg, and
    final position error, m; the fused track's final position error; (c)'s largest short-walk stride change) and the
    fused tracks (false, true), the long route and the short walk simulated at ``rate_hz``; ``extra``: as
    :func:`track`."""
    s = simulate_path(parse_route(long_route(user)), UserProfile.from_seed(user), seed=0, rate_hz=rate_hz)
    off, on = track(s, False, heading="foot"), track(s, True, extra, heading="foot")
    h0, h1 = heading_errors(off, s)[-1], heading_errors(on, s)[-1]
    p0, p1 = (float(track_summary(r, s)["final_position_error_m"]) for r in (off, on))
    fused = (track(s, False), track(s, True, extra))
    f0, f1 = (float(track_summary(r, s)["final_position_error_m"]) for r in fused)
    short = simulate_path(parse_route(SHORT), UserProfile.from_seed(user), seed=0, rate_hz=rate_hz)
    c = strides_change(track(short, False, heading="foot"), track(short, True, extra, heading="foot"))
    return (user, h0, h1, p0, p1, f0, f1, c), fused


def heading_growth(r: np.ndarray):
    """(a) / (b)'s numbers from :func:`measure`'s rows: mean |final heading error| false, true, each session's growth
    of it and the row of the largest."""
    grow = np.abs(r[:, 2]) - np.abs(r[:, 1])
    return np.mean(np.abs(r[:, 1])), np.mean(np.abs(r[:, 2])), grow, int(np.argmax(grow))


def real_and_demo_checks(extra: dict | None = None) -> None:
    """(d) the real gaitmap foot recordings, (e) the demo table's scenario D: every stride with false and true
    (``extra``: :func:`track`'s)."""
    for p in sorted(DATA.glob("gaitmap_*")):
        s = read_session(p)
        print(f"(d) {p.name}: largest stride change {strides_change(track(s, False), track(s, True, extra)):.3g}",
              flush=True)
    d = simulate("D", user_seed=1)
    for m in ("M1", "M2", "M3"):
        a, b = track(d, False, method=m), track(d, True, extra, method=m)
        da, db = (float(track_summary(x, d)["distance_error_pct"]) for x in (a, b))
        print(f"(e) scenario D {m}: distance error {da:.3f} -> {db:.3f} %, largest stride change "
              f"{strides_change(a, b):.3g}", flush=True)


def bounded(tau: float) -> None:
    """Information: (a) / (b)'s foot-only heading with S110's Gauss-Markov drift of correlation time ``tau``."""
    rows = []
    for user in USERS:
        s = simulate_path(parse_route(long_route(user)), UserProfile.from_seed(user), seed=0, gyro_bias_tau_s=tau)
        h0, h1 = (heading_errors(track(s, v, heading="foot"), s)[-1] for v in (False, True))
        rows.append((h0, h1))
        print(f"u{user} gm:{tau:g}: foot heading final error {h0:+.2f} -> {h1:+.2f} deg", flush=True)
    r = np.array(rows)
    grow = np.abs(r[:, 1]) - np.abs(r[:, 0])
    print(f"gm:{tau:g} mean |final heading error| {np.mean(np.abs(r[:, 0])):.2f} -> "
          f"{np.mean(np.abs(r[:, 1])):.2f} deg, "
          f"mean signed {np.mean(r[:, 0]):+.2f} -> {np.mean(r[:, 1]):+.2f}; largest growth {grow.max():+.2f} deg, "
          f"sessions grown > 20 deg: {int(np.sum(grow > 20))}", flush=True)


def main() -> None:
    if len(sys.argv) > 2 and sys.argv[1] == "--tau":
        return bounded(float(sys.argv[2]))
    rows = []
    for user in USERS:
        row, _ = measure(user)
        rows.append(row)
        _, h0, h1, p0, p1, f0, f1, c = row
        print(f"u{user}: foot heading final error {h0:+.2f} -> {h1:+.2f} deg, final position {p0:.2f} -> {p1:.2f} m; "
              f"fused final position {f0:.2f} -> {f1:.2f} m; short walk max stride change {c:.3g}", flush=True)
    r = np.array(rows)
    mh0, mh1, grow, worst = heading_growth(r)
    print(f"(a) mean |final heading error| {mh0:.2f} -> {mh1:.2f} deg ({100 * (mh1 / mh0 - 1):+.1f} %); mean final "
          f"position error {np.mean(r[:, 3]):.2f} -> {np.mean(r[:, 4]):.2f} m", flush=True)
    print(f"(b) largest |final heading error| growth {grow[worst]:+.2f} deg (u{int(r[worst, 0])}); sessions grown "
          f"> 20 deg: {int(np.sum(grow > 20))}", flush=True)
    print(f"(c) short walks: largest stride change {np.max(r[:, 7]):.3g}", flush=True)
    print(f"(f) fused mean final position error {np.mean(r[:, 5]):.3f} -> {np.mean(r[:, 6]):.3f} m "
          f"({100 * (np.mean(r[:, 6]) / np.mean(r[:, 5]) - 1):+.2f} %)", flush=True)
    real_and_demo_checks()
    if len(sys.argv) > 1:
        s = read_session(sys.argv[1])
        e = [heading_errors(track(s, v, heading="foot"), s)[-1] for v in (False, True)]
        print(f"long_nw (information): foot heading final error {e[0]:+.2f} -> {e[1]:+.2f} deg", flush=True)


if __name__ == "__main__":
    sys.exit(main())
