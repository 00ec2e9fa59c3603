"""Decision W543 (session 48, I3, trial s47 T2 F7): the waist-pendulum gyro heading's gentle curves, seed 003 alone
(before) and with ``gentle_curves`` (after), on fresh users 15580-15619, and the real mobgap lower-back check.
The rule was written and committed first (docs/decisions/waist.md W543).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_gentle_curves_s48_w543.py [--users 40]
Output: experiments/results/waist_gentle_curves_s48_w543.txt (the printed lines).
"""
from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track, heading_change
from pdrlearn.track.waist import track_waist
from waist import turn_error_deg

ROUTES = {"G1": "straight:10, curve:90:15, straight:10, curve:90:25, straight:10",
          "G2": "straight:10, curve:-60:20, straight:10, curve:-90:35, straight:10",
          "G3": "straight:10, curve:180:12, straight:10",
          "C": "straight:60, turn:90, straight:40",
          "S": "straight:20, turn:90, straight:10, turn:-90, straight:20, turn:180, straight:20",
          "Cb": "straight:60, turn:90, straight:40"}
BIAS_RPS = np.radians(0.5)  # Cb: an uncalibrated vertical gyro bias
FIRST_USER = 15580
REAL = Path("datasets/external")
OUT = Path("experiments/results/waist_gentle_curves_s48_w543.txt")
LINES: list[str] = []


def say(line: str) -> None:
    print(line, flush=True)
    LINES.append(line)


def _session(route: str, u: int, bias: float):
    s = simulate_path(parse_route(ROUTES[route]), UserProfile.from_seed(u), speed="normal", rate_hz=50.0, seed=u,
                      name=f"{route}_{u}", scenario="route", bounce="pendulum")
    if bias:
        g = s.streams["wGyroscope"]
        g.values = g.values + np.array([0.0, bias, 0.0])  # waist frame: y up
    return s


def simulated(n_users: int, first: int) -> None:
    rows = {k: [] for k in ROUTES}
    for u in range(first, first + n_users):
        for route in ROUTES:
            s = _session(route, u, BIAS_RPS if route == "Cb" else 0.0)
            r = []
            for kw in ({"pipeline": "waist-pendulum", "gentle_curves": False},
                       {"pipeline": "waist-pendulum", "gentle_curves": True}, {"pipeline": "waist-pll"}):
                res = track_waist(s, **kw)
                r += [evaluate_track(res, s)["final_position_error_m"], turn_error_deg(res, s)]
            rows[route].append(r)
            say(f"user {u} {route}: final error before {r[0]:.2f} m after {r[2]:.2f} m (pll {r[4]:.2f} m); "
                f"end heading error before {r[1]:.1f} after {r[3]:.1f} deg (pll {r[5]:.1f})")
    say("")
    for group in (("G1",), ("G2",), ("G3",), ("G1", "G2", "G3"), ("C",), ("S",), ("Cb",)):
        a = np.array([r for g in group for r in rows[g]])
        worst = np.max(a[:, 2] - a[:, 0])
        say(f"{'+'.join(group)} ({len(a)} walks): mean final error {a[:, 0].mean():.3f} -> {a[:, 2].mean():.3f} m "
            f"({100 * (a[:, 2].mean() / a[:, 0].mean() - 1):+.1f} %), largest worsening {worst:+.2f} m; "
            f"mean end heading error {np.nanmean(a[:, 1]):.2f} -> {np.nanmean(a[:, 3]):.2f} deg "
            f"({100 * (np.nanmean(a[:, 3]) / np.nanmean(a[:, 1]) - 1):+.1f} %); waist-pll {a[:, 4].mean():.3f} m, "
            f"{np.nanmean(a[:, 5]):.2f} deg")


def _turn_errors(res, turns) -> list[float]:
    """||tracked heading change over each INDIP turn of >= 45 deg| - |its angle|| (deg)."""
    st = res.steps.sort_values("start_s")
    t, h = st["start_s"].to_numpy(float), np.unwrap(st["heading_rad"].to_numpy(float))
    out = []
    for tn in turns.itertuples():
        a0, a1 = tn.start_s, tn.end_s
        if abs(tn.angle_deg) < 45 or not (t <= a0).any() or not (t >= a1).any():
            continue
        change = np.degrees(h[t >= a1][0] - h[t <= a0][-1])
        out.append(abs(abs(change) - abs(tn.angle_deg)))
    return out


def real(option: str = "gentle_curves", say=say) -> None:
    """The real check on the mobgap lower-back recordings with the boolean ``option`` off -> on (W544 shares it)."""
    te = {False: [], True: []}
    for folder in sorted(REAL.glob("mobgap_*")):
        s = read_session(folder)
        res = {g: track_waist(s, pipeline="waist-pendulum", **{option: g}) for g in (False, True)}
        same = np.array_equal(res[False].steps["length_m"].to_numpy(), res[True].steps["length_m"].to_numpy())
        changed = int(np.sum(~np.isclose(res[False].steps["heading_rad"], res[True].steps["heading_rad"])))
        line = f"{folder.name}: {len(res[False].steps)} steps, lengths identical {same}, headings changed {changed}"
        if "Test5" in folder.name:
            ch = [abs(np.degrees(heading_change(res[g].steps["heading_rad"].to_numpy(float)[:-1], slice(None, 3),
                                                slice(-3, None)))) for g in (False, True)]
            line += f"; |heading change first -> last 3 steps| {ch[0]:.2f} -> {ch[1]:.2f} deg"
        else:
            turns = s.extras.get("turns")
            for g in (False, True):
                te[g] += _turn_errors(res[g], turns)
            line += f"; INDIP turns >= 45 deg: {len(_turn_errors(res[False], turns))}"
        say(line)
    say(f"Test11 median ||tracked turn| - |INDIP angle|| over {len(te[False])} turns: {np.median(te[False]):.2f} -> "
        f"{np.median(te[True]):.2f} deg")


def run(users: int, first_user: int, run_real, run_sim, out: Path, lines: list[str]) -> None:
    """The command line of W543's script and W544's: the real check, then ``run_sim(n_users, first)``; the printed
    lines are written to ``out`` only for the rule's own users."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, default=users)
    ap.add_argument("--no-sim", action="store_true")
    ap.add_argument("--first", type=int, default=first_user, help="first user (another only to try the script)")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    run_real()
    if not a.no_sim:
        run_sim(a.users, a.first)
    if a.users == users and a.first == first_user and not a.no_sim:
        out.write_text("\n".join(lines) + "\n")


def main() -> None:
    run(40, FIRST_USER, real, simulated, OUT, LINES)


if __name__ == "__main__":
    main()
