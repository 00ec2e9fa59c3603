"""Decision W214's adoption rule, (a) and (b): the lower back's ``freeze_veto`` vs today's default on fresh simulated
users 5000-5039 (docs/decisions/waist.md W214; (c) is ``experiments/waist.py --external ... --freeze-veto``).

(a) routes with a freeze of 3-8 Hz at the trial's amplitudes: the detected contacts inside the true freezes, pooled,
must fall by 80 % or more; (b) routes without a freeze (plain walk, TUG, W111's daily route, slow shuffling, fast
walks): on every route the true contacts matched with the veto are at least 99.5 % of those matched without it.

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_freeze_veto.py
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pdrlearn.track.waist import track_waist  # noqa: E402
from waist_stand import SIM_ROUTES, matched_truth  # noqa: E402

USERS = range(5000, 5040)  # the lead's fresh users for W214
FREEZE_ROUTE = "stand:3, straight:4, freeze:10:{hz}:{acc}, straight:4, stand:3"
TRIAL_GAIT = (0.2, 0.55)  # the trial's step length (m) and step time (s), pendulum bounce
SHUFFLES = ((0.2, 0.8), (0.2, 0.55), (0.25, 0.6), (0.3, 0.65))  # 0.25, 0.36, 0.42, 0.46 m/s
PLAIN = {  # route name: (route, simulate_path keywords, users, gait (step length, step time) by user or None)
    "walk": (SIM_ROUTES["walk"][0], SIM_ROUTES["walk"][1], range(5000, 5008), None),
    "tug": (SIM_ROUTES["tug"][0], SIM_ROUTES["tug"][1], range(5008, 5016), None),
    "daily": (SIM_ROUTES["daily"][0], SIM_ROUTES["daily"][1], range(5016, 5024), None),
    "shuffle": ("stand:3, straight:8, stand:3", {"bounce": "pendulum"}, range(5024, 5032),
                lambda u: SHUFFLES[u % 4]),
    "fast": ("stand:3, straight:20, stand:3", {"speed": "fast"}, range(5032, 5040), None),
}


def simulate(route: str, kw: dict, user: int, gait: tuple[float, float] | None = None):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.user import SPEED_FACTORS

    profile = UserProfile.from_seed(user)
    if gait is not None:  # as `simulate --step-length L --step-time T` (decision S30) at the route's speed
        f_len, f_time = SPEED_FACTORS[kw.get("speed", "normal")]
        profile = dataclasses.replace(profile, step_length_m=gait[0] / f_len, step_time_s=gait[1] / f_time)
    return simulate_path(parse_route(route), profile, rate_hz=100, seed=user, **kw)


def contacts(session, veto: bool) -> tuple[np.ndarray, dict]:
    # W215 was measured with no stand veto; W219 made stand_veto="walking" the offline default (it drops trembling
    # chained to a walk), so the recorded numbers are reproduced with it off
    res = track_waist(session, pipeline="waist-pendulum", freeze_veto=veto, stand_veto=False)
    return res.steps["event_s"].to_numpy(float), res.info


def freeze_check(users=USERS) -> bool:
    """(a): contacts inside the true freezes, off -> on, pooled; beside: true contacts lost, episodes found."""
    inside = np.zeros(2, dtype=int)
    matched = np.zeros(2, dtype=int)
    n_true, found, covered, total = 0, 0, 0.0, 0.0
    for u in users:
        hz, acc = 3 + u % 6, (7.0, 8.5, 10.0)[u % 3]
        s = simulate(FREEZE_ROUTE.format(hz=hz, acc=acc), {"bounce": "pendulum"}, u, TRIAL_GAIT)
        fz = s.extras["freezes"]
        a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
        truth = s.extras["ics"]["ic_s"].to_numpy(float)
        n_true += truth.size
        row = []
        for k, veto in enumerate((False, True)):
            ev, info = contacts(s, veto)
            n_in = int(((ev >= a) & (ev <= b)).sum())
            inside[k] += n_in
            matched[k] += int((matched_truth(ev, truth) >= 0).sum())
            row.append(n_in)
            if veto:
                eps = info.get("freezes") or []
                found += any(r["start_s"] < b and r["end_s"] > a for r in eps)
                covered += sum(max(0.0, min(r["end_s"], b) - max(r["start_s"], a)) for r in eps)
                total += b - a
        print(f"(a) user {u} {hz} Hz {acc:g} m/s^2: contacts inside the freeze {row[0]} -> {row[1]}", flush=True)
    drop = 1.0 - inside[1] / inside[0] if inside[0] else float("nan")
    ok = bool(inside[0]) and drop >= 0.80
    print(f"(a) pooled users {users.start}-{users.stop - 1}: contacts inside the freezes {inside[0]} -> {inside[1]} "
          f"({100 * drop:.1f} % fewer) -> {'met' if ok else 'NOT met'}")
    print(f"(a) beside: true contacts {n_true}, matched {matched[0]} -> {matched[1]}; freezes found {found} of "
          f"{len(users)}, {100 * covered / total:.1f} % of the freeze time inside an episode")
    return ok


def plain_check() -> bool:
    """(b): on every route without a freeze, matched true contacts with the veto >= 99.5 % of without."""
    ok = True
    for name, (route, kw, users, gait) in PLAIN.items():
        matched = np.zeros(2, dtype=int)
        n_true, n_eps, dropped = 0, 0, 0
        for u in users:
            s = simulate(route, kw, u, gait(u) if gait else None)
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            n_true += truth.size
            for k, veto in enumerate((False, True)):
                ev, info = contacts(s, veto)
                matched[k] += int((matched_truth(ev, truth) >= 0).sum())
                if veto:
                    n_eps += len(info.get("freezes") or [])
                    dropped += int(info.get("n_frozen_contacts") or 0)
        share = matched[1] / matched[0] if matched[0] else float("nan")
        good = share >= 0.995
        ok &= bool(good)
        print(f"(b) {name} users {users.start}-{users.stop - 1}: true {n_true}, matched {matched[0]} -> {matched[1]} "
              f"({100 * share:.2f} %), freeze episodes {n_eps}, contacts dropped {dropped} -> "
              f"{'met' if good else 'NOT met'}", flush=True)
    return ok


def main() -> None:
    a = freeze_check()
    b = plain_check()
    print(f"W214 (a) {'met' if a else 'NOT met'}, (b) {'met' if b else 'NOT met'}; (c): experiments/waist.py "
          "--external datasets/external --no-real --freeze-veto")


if __name__ == "__main__":
    main()
