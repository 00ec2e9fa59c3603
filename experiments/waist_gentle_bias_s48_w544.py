"""Decision W544 (session 48, FN, review R2 F3): W543's gentle curves judged on the stride rate less W105's reading
at rest, before (W543's default) and after (``gentle_rest_bias``), with ``gentle_curves`` off beside, on fresh users
16140-16159: W543's routes and its route C with a vertical gyro bias of 0-3 deg/s in three starts, and the real
mobgap lower-back check. The rule was written and committed first (docs/decisions/waist.md W544).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_gentle_bias_s48_w544.py [--users 20]
Output: experiments/results/waist_gentle_bias_s48_w544.txt (the printed lines).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from waist import turn_error_deg
from waist_gentle_curves_s48_w543 import ROUTES, real, run

FIRST_USER = 16140
BIASES_DEG = (0.0, 0.5, 1.0, 2.0, 3.0)
C = ROUTES["C"]
STARTS = {"default": (C, {}), "stand": ("stand:10, " + C + ", stand:5", {}), "none": (C, {"stand_s": 0.5})}
CASES = {"off": {"gentle_curves": False}, "before": {"gentle_rest_bias": False}, "after": {"gentle_rest_bias": True}}
OUT = Path("experiments/results/waist_gentle_bias_s48_w544.txt")
LINES: list[str] = []


def say(line: str) -> None:
    print(line, flush=True)
    LINES.append(line)


def _session(route: str, u: int, bias_deg: float, knobs: dict):
    s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed="normal", rate_hz=50.0, seed=u,
                      name=f"w544_{u}", scenario="route", bounce="pendulum", **knobs)
    if bias_deg:
        g = s.streams["wGyroscope"]
        g.values = g.values + np.array([0.0, np.radians(bias_deg), 0.0])  # waist frame: y up (as W543's Cb)
    return s


def _walk(s) -> dict[str, tuple[float, float]]:
    out = {}
    for case, kw in CASES.items():
        r = track_waist(s, pipeline="waist-pendulum", **kw)
        out[case] = (evaluate_track(r, s)["final_position_error_m"], turn_error_deg(r, s))
    return out


def _summary(label: str, rows: list[dict]) -> None:
    f = {c: np.array([r[c][0] for r in rows]) for c in CASES}
    h = {c: np.array([r[c][1] for r in rows]) for c in CASES}
    d = f["after"] - f["before"]
    say(f"{label} ({len(rows)} walks): mean final error off {f['off'].mean():.3f} / before {f['before'].mean():.3f} "
        f"-> after {f['after'].mean():.3f} m ({100 * (f['after'].mean() / f['before'].mean() - 1):+.1f} % vs "
        f"before, {100 * (f['after'].mean() / f['off'].mean() - 1):+.1f} % vs off), after - before largest "
        f"{d.max():+.3f} smallest {d.min():+.3f} m; mean end heading error off {np.nanmean(h['off']):.2f} / before "
        f"{np.nanmean(h['before']):.2f} -> after {np.nanmean(h['after']):.2f} deg")


def simulated(n_users: int, first: int) -> None:
    rows: dict[str, list[dict]] = {}
    users = range(first, first + n_users)
    for u in users:
        for route in ("G1", "G2", "G3", "C", "S"):
            rows.setdefault(route, []).append(_walk(_session(ROUTES[route], u, 0.0, {})))
        for start, (route, knobs) in STARTS.items():
            for b in BIASES_DEG:
                rows.setdefault(f"C {start} {b:g} deg/s", []).append(_walk(_session(route, u, b, knobs)))
        say(f"user {u} done: C default 2 deg/s before {rows['C default 2 deg/s'][-1]['before'][0]:.2f} after "
            f"{rows['C default 2 deg/s'][-1]['after'][0]:.2f} m")
    say("")
    for label in ("G1", "G2", "G3"):
        _summary(label, rows[label])
    _summary("G1+G2+G3", rows["G1"] + rows["G2"] + rows["G3"])
    for label in ("C", "S"):
        _summary(label, rows[label])
    for start in STARTS:
        for b in BIASES_DEG:
            _summary(f"C {start} {b:g} deg/s", rows[f"C {start} {b:g} deg/s"])


def main() -> None:
    run(20, FIRST_USER, lambda: real("gentle_rest_bias", say), simulated, OUT, LINES)


if __name__ == "__main__":
    main()
