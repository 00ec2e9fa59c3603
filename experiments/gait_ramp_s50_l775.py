"""Decision L775 (session 50, FI; docs/decisions/localization.md): ramp strides out of `gait`'s level headline, measured
on fresh users 17680-17709.

Per user (the trial's slow persona, drawn from the user id: step length 0.45-0.60 m, step time 0.55-0.65 s,
``--bounce pendulum --rate 100``), both feet of a ramp walk (1:12, 8 m) and of a level walk; ``gait`` (offline,
toe-off) before (``ramps`` off: L746's code) and after (``ramps=True``). Rule (a): no tracked level-headline step
lands on a truth ramp stride (label ``height_m`` >= 0.06 m, contact within 0.1 s) on >= 27 of 30 ramp walks; (b)
every level walk's headline ``walk`` (tracked and reference) unchanged; (c) the real gaitmap level pair unchanged.
Run: ``PYTHONPATH=. python experiments/gait_ramp_s50_l775.py [WORK] [--users 17680-17709]``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

USERS = range(17680, 17710)
RAMP = "stand:3, straight:3, slope:8:8.33, straight:2, stand:3"
LEVEL = "stand:3, straight:20, turn:180, straight:20, stand:3"
TRUTH_RAMP_M = 0.06
NEAR_S = 0.1


def persona(uid: int) -> tuple[float, float]:
    rng = np.random.default_rng([uid, 775])
    return round(float(rng.uniform(0.45, 0.60)), 3), round(float(rng.uniform(0.55, 0.65)), 3)


def simulate_pair(uid: int, route: str, folder: Path) -> None:
    from pdrlearn.cli import main

    sl, st = persona(uid)
    for foot in ("left", "right"):
        if (folder / foot / "meta.json").exists():
            continue
        rc = main(["simulate", "--route", route, "--step-length", str(sl), "--step-time", str(st), "--bounce",
                   "pendulum", "--rate", "100", "--user-seed", str(uid), "--foot", foot, "--out",
                   str(folder / foot), "--force"])
        assert rc == 0, (uid, route, foot)


def both_ways(left: Path, right: Path) -> tuple[dict, dict]:
    """(before, after): gait of the pair without and with ``ramps`` (L775's keyword; off, the code is L746's), each
    foot tracked once. The printed numbers of L775 came from this script's first version, which took "before" as the
    tracks with ``raw_dz_m`` dropped while the rule was on by default: the same computation."""
    from pdrlearn.track.bilateral import offline_foot_track, pair_sessions

    cache: dict = {}

    def track(session, ignore_force):
        key = (str(session.where), bool(ignore_force))
        if key not in cache:
            cache[key] = offline_foot_track(session, ignore_force)
        return cache[key]

    after = pair_sessions(left, right, track_foot=track, ramps=True)
    before = pair_sessions(left, right, track_foot=track)
    return before, after


def truth_ramp_ics(folder: Path) -> dict[str, np.ndarray]:
    import pandas as pd

    out = {}
    for foot in ("left", "right"):
        s = pd.read_csv(folder / foot / "steps.csv")
        s = s[s["foot"] == foot] if "foot" in s else s
        out[foot] = s.loc[s["height_m"].abs() >= TRUTH_RAMP_M, "ic_ms"].to_numpy(float) / 1000.0
    return out


def leaks(res: dict, truth: dict[str, np.ndarray]) -> int:
    st = res["steps"]
    n = 0
    for _, row in st[st["kind"] == "level"].iterrows():
        t = truth[row["side"]]
        n += int(len(t) > 0 and np.min(np.abs(t - row["ic_s"])) < NEAR_S)
    return n


def same(a, b) -> bool:
    return json.dumps(a, sort_keys=True, default=str) == json.dumps(b, sort_keys=True, default=str)


def main(argv: list[str]) -> None:
    work = Path(argv[0]) if argv and not argv[0].startswith("--") else Path("/tmp/gait_ramp_l775")
    users = USERS
    if "--users" in argv:
        a, b = argv[argv.index("--users") + 1].split("-")
        users = range(int(a), int(b) + 1)
    ramp_ok, level_same, ref_same, rows = 0, 0, 0, []
    for uid in users:
        rd, ld = work / f"u{uid}" / "ramp", work / f"u{uid}" / "level"
        simulate_pair(uid, RAMP, rd)
        simulate_pair(uid, LEVEL, ld)
        truth = truth_ramp_ics(rd)
        rb, ra = both_ways(rd / "left", rd / "right")
        lb, la = both_ways(ld / "left", ld / "right")
        n_before, n_after = leaks(rb, truth), leaks(ra, truth)
        ramp_ok += n_after == 0
        tracked_same = same(lb["walk"], la["walk"])
        reference_same = same((lb.get("reference") or {}).get("walk"), (la.get("reference") or {}).get("walk"))
        level_same += tracked_same
        ref_same += reference_same
        kinds = ra["by_kind"].get("ramp") or {}
        row = (f"u{uid} {persona(uid)}: truth ramp contacts {len(truth['left'])}/{len(truth['right'])}, level "
               f"headline steps on the ramp before {n_before} after {n_after}; ramp kind steps "
               f"{kinds.get('n_steps_left', 0)}/{kinds.get('n_steps_right', 0)}; level walk headline same: "
               f"tracked {tracked_same} reference {reference_same}; level-walk ramp steps "
               f"{(la['by_kind'].get('ramp') or {}).get('n_steps_left', 0)}/"
               f"{(la['by_kind'].get('ramp') or {}).get('n_steps_right', 0)}")
        print(row, flush=True)
        rows.append(row)
    n = len(users)
    print(f"(a) ramp walks with no level-headline step on the ramp: {ramp_ok} of {n}")
    print(f"(b) level walks' headline unchanged: tracked {level_same} of {n}, reference {ref_same} of {n}")
    real = Path(__file__).resolve().parents[1] / "datasets" / "real"
    gb, ga = both_ways(real / "gaitmap_level_left", real / "gaitmap_level_right")
    keys = ("walk", "bouts", "by_kind")
    print("(c) gaitmap level pair unchanged: " + ", ".join(f"{k} {same(gb[k], ga[k])}" for k in keys)
          + f", reference {same(*[{k: (r.get('reference') or {}).get(k) for k in keys} for r in (gb, ga)])}")
    ok = ramp_ok >= 0.9 * n and level_same == n and ref_same == n and all(same(gb[k], ga[k]) for k in keys)
    print(f"L775 rule (a, b, c): {'passes' if ok else 'fails'}")


if __name__ == "__main__":
    main(sys.argv[1:])
