"""Decision S73: why the uncalibrated waist pendulum reads simulated walkers short (session 33, T4 finding 3).

Per group, medians over the steady steps of a straight walk: the truth step length s (the waist unit's horizontal
travel between two initial contacts), the pelvis's vertical excursion h per step from the simulator's truth (peak to
peak of the waist unit's height between two contacts) and as the pipeline estimates it (``h_m``, W10), the "gain" a
pendulum would need to read s from each h (s / (2 sqrt(2 L h - h^2)), seed 003 eq. 1 with F = 0; the default K is
4.587/4, W46) and the uncalibrated pendulum's distance ratio (sum of step lengths / truth). The real rows use the
mobgap Test5 walks' INDIP reference bouts (bouts.csv length / detected steps in the bout).

    PYTHONPATH=. python experiments/pelvis_excursion.py --external datasets/external [--users 7390-7399]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.kernels import waist as K
from pdrlearn.waist.params import DEFAULT_K


def gain(s: np.ndarray, h: np.ndarray, leg: float) -> np.ndarray:
    g = K.pendulum_length(h, leg)  # seed 003 eq. 1, K = 1, F = 0
    return np.where(g > 0, s / np.maximum(g, 1e-9), np.nan)


def trial_user(u: int, wide: bool):
    """Decision W569: user ``u`` as trial s49t3 drew its bariatric walkers (height 1.60-1.80 m, 0.70-0.90 m/s at
    90-100 steps/min, feet 0.25-0.35 m apart; ``scripts/sweep.py``) with ``wide``, else the same stature at its own
    normal gait and step width (``simulate --height H [--step-length --step-time --step-width]``)."""
    from pdrlearn.cli.simulate import _custom_gait, scaled_user, with_step_width
    from pdrlearn.sim.user import UserProfile

    rng = np.random.default_rng(u)
    h, sp, cad, sw = rng.uniform(1.60, 1.80), rng.uniform(0.70, 0.90), rng.uniform(90, 100), rng.uniform(0.25, 0.35)
    user = scaled_user(UserProfile.from_seed(u), round(h, 2), None)
    if not wide:
        return user
    st = 60.0 / cad
    return _custom_gait(with_step_width(user, round(sw, 2)), "normal", round(sp * st, 3), round(st, 3), "route")


def sim_rows(users: range, speed: str, bounce: str, rate_hz: float, user_fn=None) -> dict:
    from pdrlearn.sim.path import Stand, Straight
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    s_all, ht_all, hp_all, gt_all, gp_all, ratio = [], [], [], [], [], []
    for u in users:
        user = UserProfile.from_seed(u) if user_fn is None else user_fn(u)
        ses = simulate_path([Stand(3), Straight(40), Stand(3)], user, speed=speed, seed=0, rate_hz=rate_hz,
                            bounce=bounce)
        tr = ses.trajectory
        t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
        xy = tr[["x", "y"]].to_numpy(float)
        ics = np.sort(ses.extras["ics"]["ic_s"].to_numpy(float))
        inner = ics[3:-3]  # steady steps: not the first or last three contacts
        pos = np.array([np.interp(inner, t, xy[:, 0]), np.interp(inner, t, xy[:, 1])]).T
        s = np.linalg.norm(np.diff(pos, axis=0), axis=1)
        h = np.array([np.ptp(z[(t >= a) & (t <= b)]) for a, b in zip(inner[:-1], inner[1:], strict=True)])
        p, _ = resolve_params(ses, None)
        res = track_waist(ses, pipeline="waist-pendulum", params=p)
        st = res.steps[res.steps["has_next"]]
        mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
        keep = (mid > inner[0]) & (mid < inner[-1])
        hp = st["h_m"].to_numpy(float)[keep]
        s_at = np.interp(mid[keep], 0.5 * (inner[:-1] + inner[1:]), s)
        s_all.append(s), ht_all.append(h), hp_all.append(hp)
        gt_all.append(gain(s, h, p.leg_m)), gp_all.append(gain(s_at, hp, p.leg_m))
        walked = float(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)))
        ratio.append(res.distance_m / walked)
    cat = np.concatenate
    return {"s": np.median(cat(s_all)), "h_truth": np.median(cat(ht_all)), "h_pipe": np.median(cat(hp_all)),
            "gain_truth": np.nanmedian(cat(gt_all)), "gain_pipe": np.nanmedian(cat(gp_all)),
            "ratio": np.median(ratio), "ratio_min": np.min(ratio), "ratio_max": np.max(ratio), "n": len(ratio)}


def real_rows(external: Path, pattern: str = "mobgap_*_Test5_*") -> list[tuple[str, dict]]:
    """Per INDIP reference bout of the recordings ``pattern`` matches under ``external`` (S73: Test5; W618: every
    mobgap test): s (bout length / detected steps), the pipeline's median h, the gain and the uncalibrated ratio."""
    from pdrlearn.io.plasys import read_session
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.evaluate import reference_bouts, steps_in_interval
    from pdrlearn.waist.params import resolve_params

    rows = []
    for folder in sorted(external.glob(pattern)):
        ses = read_session(folder)
        p, _ = resolve_params(ses, None)
        res = track_waist(ses, pipeline="waist-pendulum", params=p)
        st = res.steps[res.steps["has_next"]]
        bouts = reference_bouts(ses)
        for b in ([] if bouts is None else bouts.itertuples()):
            m = steps_in_interval(st, b.start_s, b.end_s)
            hp = st["h_m"].to_numpy(float)[m]
            s = float(b.length_m) / max(int(m.sum()), 1)
            rows.append((f"{folder.name}@{b.start_s:.0f}s", {
                "s": s, "h_pipe": float(np.median(hp)), "gain_pipe": float(np.nanmedian(gain(np.full(len(hp), s),
                                                                                               hp, p.leg_m))),
                "ratio": float(st["length_m"].to_numpy(float)[m].sum() / b.length_m), "leg": p.leg_m,
                "n": int(m.sum())}))
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", default="datasets/external")
    ap.add_argument("--users", default="7390-7399")
    ap.add_argument("--bounce", default="constant,pendulum")
    ap.add_argument("--rate", type=float, default=100.0, help="simulated rate (Hz); the real walks are 100 Hz")
    ap.add_argument("--no-real", action="store_true", help="the simulated rows only")
    ap.add_argument("--trial-w569", action="store_true", help="decision W569: trial s49t3's slow wide walkers "
                    "against the same statures at their own normal gait, instead of slow / normal / fast")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)  # the no-calibration and heading lines of every session
    lo, hi = (int(v) for v in a.users.split("-"))
    print(f"default K = {DEFAULT_K:.4f} (W46); gain = s / (2 sqrt(2 L h - h^2)), the K each h would need")
    print(f"{'group':34s} {'s m':>6s} {'h truth cm':>10s} {'h pipe cm':>9s} {'gain truth':>10s} {'gain pipe':>9s} "
          f"{'ratio (min-max)':>22s}")
    for bounce in a.bounce.split(","):
        groups = ([("wide-slow", "normal", lambda u: trial_user(u, True)),
                   ("own-normal", "normal", lambda u: trial_user(u, False))] if a.trial_w569 else
                  [(speed, speed, None) for speed in ("slow", "normal", "fast")])
        for label, speed, fn in groups:
            r = sim_rows(range(lo, hi + 1), speed, bounce, a.rate, fn)
            print(f"{f'sim {bounce} {label} {a.rate:g}Hz u{lo}-{hi}':34s} {r['s']:6.3f} {100 * r['h_truth']:10.2f} "
                  f"{100 * r['h_pipe']:9.2f} {r['gain_truth']:10.3f} {r['gain_pipe']:9.3f} "
                  f"{r['ratio']:8.3f} ({r['ratio_min']:.3f}-{r['ratio_max']:.3f})", flush=True)
    for name, r in ([] if a.no_real else real_rows(Path(a.external))):
        print(f"{name:34s} {r['s']:6.3f} {'':>10s} {100 * r['h_pipe']:9.2f} {'':>10s} {r['gain_pipe']:9.3f} "
              f"{r['ratio']:8.3f}  L {r['leg']:.3f} n {r['n']}", flush=True)


if __name__ == "__main__":
    main()
