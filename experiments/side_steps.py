"""Decisions L218 / L219: what the tracks make of side steps (simulator decision S49). Fresh simulated users
3980-3999 walk ``straight:10, side:3, straight:10`` (a walk, 3 m side-stepping left, a walk), ``side:-4`` (4 m to
the right only) and ``straight:23`` (a control); ``plasys`` (foot, defaults), ``waist-pendulum`` and ``waist-pll``
track them. Per route and pipeline: the median (min-max) over the users of the track's distance and the
reference's, the final position error, the track's end point in the truth's start frame (forward x, left y; truth
beside it), the heading change start to end, the turns of turns.csv (L200; number and median |angle|), the steps
counted (both feet) against the true contacts, and how many tracks give decision L219's sideways line.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps.py [--out experiments/results/side_steps.txt]
    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps.py --controls   # L219 (b), (c)
    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps.py --candidate  # L219's adoption rule
"""

from __future__ import annotations

import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.frame_inference import foot_travel_angles
from pdrlearn.track.sideways import sideways_runs

USERS = range(3980, 4000)
ROUTES = ("straight:10, side:3, straight:10", "side:-4", "straight:23")  # the last: a control without side steps
PIPELINES = ("plasys", "waist-pendulum", "waist-pll")
COLUMNS = ("distance_m", "distance_ref_m", "final_position_error_m", "end_x_m", "end_y_m", "true_x_m", "true_y_m",
           "heading_change_deg", "n_turns", "median_turn_deg", "steps", "true_steps")


def _end(traj, t0: float, t1: float, heading0: float) -> tuple[float, float]:
    """The displacement t0 -> t1 of a trajectory (t, x, y) in the frame of ``heading0`` (forward, left)."""
    p = [np.array([np.interp(t, traj["t"], traj[c]) for c in ("x", "y")]) for t in (t0, t1)]
    d = p[1] - p[0]
    c, s = np.cos(heading0), np.sin(heading0)
    return float(c * d[0] + s * d[1]), float(-s * d[0] + c * d[1])


def measure(route: str, pipeline: str, user: int) -> tuple[dict, bool]:
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")
    res = get_pipeline(pipeline)(s)
    ev = evaluate_track(res, s)
    tr, gt, st = res.trajectory, s.trajectory, res.steps
    t0, t1 = float(tr["t"].iloc[0]), float(tr["t"].iloc[-1])
    h = st["heading_rad"].to_numpy(float) if len(st) else np.zeros(1)
    g0 = float(np.interp(t0, gt["t"], gt["heading_rad"]))  # both ends in the truth's start frame (forward, left):
    # the simulated walker starts facing east (0), where the waist tracks start and the foot track's compass points
    turns = turn_table(st)
    row = {"distance_m": ev["distance_m"], "distance_ref_m": ev.get("distance_ref_m", np.nan),
           "final_position_error_m": ev.get("final_position_error_m", np.nan),
           "heading_change_deg": float(np.degrees(np.unwrap(h)[-1] - h[0])),
           "n_turns": len(turns), "median_turn_deg": float(turns["angle_deg"].abs().median()) if len(turns) else 0.0,
           "steps": ev.get("n_steps_both_feet") or np.nan, "true_steps": len(s.extras["ics"])}
    row["end_x_m"], row["end_y_m"] = _end(tr, t0, t1, g0)
    row["true_x_m"], row["true_y_m"] = _end(gt, t0, t1, g0)
    side_line = any("decision L219" in w for w in res.info.get("warnings", []))
    return row, side_line


def main(out: str | None = None) -> None:
    logging.disable(logging.WARNING)
    lines = [f"users {USERS.start}-{USERS.stop - 1}, seed 1, 20 Hz; median (min..max) over the users"]
    for route in ROUTES:
        for p in PIPELINES:
            rows, warned = [], 0
            for u in USERS:
                r, w = measure(route, p, u)
                rows.append(r)
                warned += w
            lines.append(f"{route!r} {p}: L219 line on {warned} of {len(rows)} tracks")
            for c in COLUMNS:
                v = np.array([r[c] for r in rows], float)
                lines.append(f"    {c:24s} {np.nanmedian(v):8.2f} ({np.nanmin(v):.2f}..{np.nanmax(v):.2f})")
            print("\n".join(lines[-len(COLUMNS) - 1:]), flush=True)
    if out:
        with open(out, "w") as f:
            f.write("\n".join(lines) + "\n")


CONTROLS = ("A", "C", "D", "straight:5, backward:6, straight:5")


def controls() -> None:
    """Decision L219's criteria (b) and (c): tracks with a sideways line on walks without side steps."""
    from pathlib import Path

    from pdrlearn.io import read_session
    from pdrlearn.sim import simulate

    logging.disable(logging.WARNING)
    for c in CONTROLS:
        n, warned = 0, {p: 0 for p in PIPELINES}
        for u in USERS:
            s = (simulate(c, u, rate_hz=20.0, seed=1) if len(c) == 1 else
                 simulate_path(parse_route(c), UserProfile.from_seed(u), rate_hz=20.0, seed=1, scenario="route"))
            n += 1
            for p in PIPELINES:
                warned[p] += any("decision L219" in w for w in get_pipeline(p)(s).info["warnings"])
        print(f"{c!r}, users {USERS.start}-{USERS.stop - 1}: " + ", ".join(f"{p} {w} of {n}" for p, w in warned.items())
              + " tracks with an L219 line", flush=True)
    real = sorted({d.resolve(): d for d in [*Path("datasets/real").glob("gaitmap_*"),
                                            *Path("datasets/external").glob("gaitmap_*")]}.values())
    for d in real:
        s = read_session(d)
        lines = [w for w in get_pipeline("plasys")(s).info["warnings"] if "decision L219" in w]
        # the cue itself (plasys says it only with a waist heading; these recordings have no waist unit)
        strides = foot_travel_angles(s)
        runs = "no declared foot frame" if strides is None else (
            f"{len(sideways_runs(*strides[2:]))} sideways run(s) in {len(strides[0])} strides, max |angle| of the "
            f"strides "
            f"over 0.15 m {np.degrees(np.abs(strides[2][strides[3] > 0.15])).max(initial=0):.0f} deg")
        print(f"{d}: plasys {len(lines)} L219 line(s); cue: {runs}", flush=True)


def candidate() -> None:
    """Decision L219's adoption rule for ``plasys.SIDE_TRAVEL_HEADING``: (1), (2) on the side routes, (3) on the
    controls (distance and final position with the option off and on)."""
    from pdrlearn.sim import simulate
    from pdrlearn.track import plasys

    logging.disable(logging.WARNING)

    def run(route: str, user: int, on: bool) -> dict:
        plasys.SIDE_TRAVEL_HEADING = on
        try:
            s = (simulate(route, user, rate_hz=20.0, seed=1) if len(route) == 1 else
                 simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1,
                               scenario="route"))
            res = get_pipeline("plasys")(s)
            ev = evaluate_track(res, s)
            return {"err": ev.get("final_position_error_m", np.nan), "dist": ev["distance_m"],
                    "end": res.trajectory[["x", "y"]].to_numpy(float)[-1],
                    "line": any("decision L219" in w for w in res.info["warnings"])}
        finally:
            plasys.SIDE_TRAVEL_HEADING = False

    for route in ROUTES[:2]:
        off = [run(route, u, False) for u in USERS]
        on = [run(route, u, True) for u in USERS]
        e0, e1 = np.array([r["err"] for r in off]), np.array([r["err"] for r in on])
        print(f"{route!r} plasys final_position_error_m: off median {np.median(e0):.2f} (max {e0.max():.2f}), on "
              f"median {np.median(e1):.2f} (max {e1.max():.2f}); largest growth {np.max(e1 - e0):+.2f} m; distance "
              f"on median {np.median([r['dist'] for r in on]):.2f} m; L219 lines on {sum(r['line'] for r in on)}",
              flush=True)
    for route in (*CONTROLS, ROUTES[2]):
        same = 0
        for u in USERS:
            a, b = run(route, u, False), run(route, u, True)
            same += abs(a["dist"] - b["dist"]) <= 1e-9 and bool(np.all(np.abs(a["end"] - b["end"]) <= 1e-9))
        print(f"{route!r}: plasys identical with the option on in {same} of {len(USERS)} tracks", flush=True)


if __name__ == "__main__":
    if "--candidate" in sys.argv[1:]:
        candidate()
    elif "--controls" in sys.argv[1:]:
        controls()
    else:
        main(sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else None)
