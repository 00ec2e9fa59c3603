"""Decision W618: what spreads the uncalibrated lower-back distance error across simulated subjects (issue 8, trial
s52t3: -1.8 to -22.9 %), the tool or the simulator.

Per fresh user (``UserProfile.from_seed``), trial s52t3's route ``stand:3, straight:20, turn:180, straight:20,
stand:3`` (every third user slow, as the trial's week-12 visits), simulated with each ``--bounce`` mode, tracked by
``waist-pendulum`` on the lower back alone with the meta.json defaults (W46's K), and once more with meta.json cut to
what an imported lower-back export gives (``height_m`` only: ``import --subject-height``; ``none``: nothing;
``sensor``: height and the waist unit's height, no ``leg_length_m``, so L = the unit's height as for the real
recordings). ``len_over_Kg_max``: the largest steady step length / (K g pause_factor), 1 when nothing caps a step. Error
= distance / truth - 1, truth = the sum of steps.csv's stride lengths (the trial's ``truth.py``). Per user also what
meta.json draws (height, waist-unit height, leg, step length, cadence, pelvis bounce), the truth pelvis excursion h
per steady step (peak to peak of trajectory.csv's z between contacts), the pipeline's ``h_m``, the gain s / (2
sqrt(2 L h - h^2)) the pendulum would need (seed 003 eq. 1, F = 0; L = the waist unit's height, as mobgap's K0 is
fitted) and the ratio a constant bounce predicts from meta.json alone: K0 x 2 sqrt(2 L b - b^2) / step length (b
= ``pelvis_bounce_m``, L = the leg the tool uses). The real rows: every mobgap lower-back recording's INDIP bouts
(``pelvis_excursion.real_rows``), the gain each needs and how h grows with s.

    PYTHONPATH=. python experiments/waist_subject_spread_s52_w618.py --users 19450-19479 [--rate 100]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

import pelvis_excursion  # experiments/ sibling (S73's measures)
from pdrlearn.kernels import waist as K
from pdrlearn.waist.params import DEFAULT_K

ROUTE = "stand:3, straight:20, turn:180, straight:20, stand:3"  # trial s52t3's mk_sim.sh


def _imported(ses, keep: tuple[str, ...]):
    """The session as a lower-back-only import gives it: meta.json with only the keys ``keep`` (and the rate)."""
    from dataclasses import replace

    meta = {k: v for k, v in (ses.meta or {}).items() if k in (*keep, "rate_hz", "session")}
    return replace(ses, meta=meta)


def one_user(u: int, rate_hz: float, bounces: tuple[str, ...]) -> dict:
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    user = UserProfile.from_seed(u)
    speed = "slow" if u % 3 == 0 else "normal"
    row = {"user": u, "speed": speed, "height": user.height_m, "sensor_h": user.sensor_height_m,
           "leg": user.leg_length_m, "step_m": user.step_length(speed), "cadence": 60.0 / user.step_time(speed),
           "bounce_cm": 100 * user.pelvis_bounce_m}
    for bounce in bounces:
        ses = simulate_path(parse_route(ROUTE), user, speed=speed, seed=1, rate_hz=rate_hz, bounce=bounce)
        truth = float(ses.steps["length_m"].abs().sum())
        variants = [("meta", ses)]
        if bounce == "constant":
            variants += [("height", _imported(ses, ("height_m",))), ("none", _imported(ses, ())),
                         ("sensor", _imported(ses, ("height_m", "sensor_height_m")))]
        for tag, s in variants:
            p, _ = resolve_params(s, None)
            res = track_waist(s, pipeline="waist-pendulum", params=p)
            row[f"err_{bounce}_{tag}"] = 100 * (res.distance_m / truth - 1)
            if tag != "meta":
                continue
            tr = ses.trajectory
            t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
            ics = np.sort(ses.extras["ics"]["ic_s"].to_numpy(float))
            first = ics[ics < ics[0] + 8.0][3:-1]  # the first straight's steady steps (before the turn)
            h = np.array([np.ptp(z[(t >= a) & (t <= b)]) for a, b in zip(first[:-1], first[1:], strict=True)])
            xy = tr[["x", "y"]].to_numpy(float)
            pos = np.array([np.interp(first, t, xy[:, 0]), np.interp(first, t, xy[:, 1])]).T
            s_step = np.linalg.norm(np.diff(pos, axis=0), axis=1)
            st = res.steps[res.steps["has_next"]]
            kg = DEFAULT_K * st["g_m"].to_numpy(float) * st["pause_factor"].to_numpy(float)
            row["len_over_Kg_max"] = float(np.max(st["length_m"].to_numpy(float) / np.maximum(kg, 1e-9)))
            mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
            hp = st["h_m"].to_numpy(float)[(mid > first[0]) & (mid < first[-1])]
            row[f"s_{bounce}"] = float(np.median(s_step))
            row[f"h_{bounce}_cm"] = 100 * float(np.median(h))
            row[f"hp_{bounce}_cm"] = 100 * float(np.median(hp)) if hp.size else np.nan
            g = pelvis_excursion.gain(s_step, np.median(hp), user.sensor_height_m)
            row[f"gain_{bounce}"] = float(np.nanmedian(g))
            row["leg_used"] = p.leg_m
    b = user.pelvis_bounce_m
    row["pred_constant"] = 100 * (DEFAULT_K * float(K.pendulum_length(np.array([b]), row["leg_used"])[0])
                                  / row["step_m"] - 1)
    row["pred_h_truth"] = 100 * (DEFAULT_K * float(K.pendulum_length(np.array([row["h_constant_cm"] / 100]),
                                                                     row["leg_used"])[0]) / row["s_constant"] - 1)
    return row


def _r(x, y) -> float:
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y)
    return float(np.corrcoef(x[ok], y[ok])[0, 1])


def _spread(v) -> str:
    v = np.asarray(v, float)
    q1, q3 = np.percentile(v, [25, 75])
    return (f"median {np.median(v):+.2f} %, IQR {q3 - q1:.2f}, SD {np.std(v, ddof=1):.2f}, "
            f"min {v.min():+.2f}, max {v.max():+.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="19450-19479")
    ap.add_argument("--rate", type=float, default=100.0)
    ap.add_argument("--bounce", default="constant,pendulum,population")
    ap.add_argument("--external", default="datasets/external")
    ap.add_argument("--no-real", action="store_true")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, hi = (int(v) for v in a.users.split("-"))
    bounces = tuple(a.bounce.split(","))
    rows = [one_user(u, a.rate, bounces) for u in range(lo, hi + 1)]
    import pandas as pd

    df = pd.DataFrame(rows)
    with pd.option_context("display.width", 250, "display.max_columns", 40, "display.float_format", "{:.3f}".format):
        print(f"users {lo}-{hi}, {a.rate:g} Hz, route {ROUTE!r}, waist-pendulum defaults (K {DEFAULT_K:.4f})")
        print(df.to_string(index=False))
    print("\nspread of the distance error over the users:")
    for c in [c for c in df.columns if c.startswith("err_")]:
        print(f"  {c:26s} {_spread(df[c])}")
    print("\nconstant bounce (meta.json defaults): Pearson r of the error with")
    for c in ("height", "sensor_h", "leg", "step_m", "cadence", "bounce_cm", "s_constant", "h_constant_cm",
              "hp_constant_cm", "gain_constant", "pred_constant", "pred_h_truth"):
        print(f"  {c:16s} r = {_r(df[c], df['err_constant_meta']):+.3f}")
    for c in ("pred_constant", "pred_h_truth"):
        d = df.err_constant_meta - df[c]
        print(f"  measured - {c}: median {np.median(d):+.2f} points, SD {np.std(d, ddof=1):.2f}")
    for bounce in bounces:
        lh, ls = np.log(df[f"hp_{bounce}_cm"]), np.log(df[f"s_{bounce}"])
        print(f"sim {bounce:10s} across users: gain median {df[f'gain_{bounce}'].median():.3f} "
              f"(min {df[f'gain_{bounce}'].min():.3f}, max {df[f'gain_{bounce}'].max():.3f}, SD "
              f"{df[f'gain_{bounce}'].std():.3f}); log h_pipe on log s slope {np.polyfit(ls, lh, 1)[0]:+.2f}, "
              f"r {_r(ls, lh):+.3f}; error r with bounce_cm {_r(df['bounce_cm'], df[f'err_{bounce}_meta']):+.3f}, "
              f"with step_m {_r(df['step_m'], df[f'err_{bounce}_meta']):+.3f}")
    if a.no_real:
        return
    real = pelvis_excursion.real_rows(Path(a.external), "mobgap_*")
    print("\nreal lower back, per INDIP reference bout (L = meta.json sensor_height_m):")
    print(f"  {'bout':44s} {'s m':>6s} {'h pipe cm':>9s} {'gain':>6s} {'ratio':>6s} {'n':>3s}")
    for name, r in real:
        print(f"  {name:44s} {r['s']:6.3f} {100 * r['h_pipe']:9.2f} {r['gain_pipe']:6.3f} {r['ratio']:6.3f} "
              f"{r['n']:3d}")
    ok = [r for _, r in real if r["n"] >= 4 and np.isfinite(r["gain_pipe"])]
    s = np.array([r["s"] for r in ok])
    h = np.array([r["h_pipe"] for r in ok])
    g = np.array([r["gain_pipe"] for r in ok])
    print(f"real bouts with >= 4 steps: {len(ok)}; gain median {np.median(g):.3f} (min {g.min():.3f}, max "
          f"{g.max():.3f}, SD {np.std(g, ddof=1):.3f}); log h on log s slope "
          f"{np.polyfit(np.log(s), np.log(h), 1)[0]:+.2f}, "
          f"r {_r(np.log(s), np.log(h)):+.3f}; ratio median {np.median([r['ratio'] for r in ok]):.3f}")
    for subj in sorted({n.split('_')[1] for n, _ in real}):
        sel = [r for n, r in real if n.split("_")[1] == subj and r["n"] >= 4 and np.isfinite(r["gain_pipe"])]
        if len(sel) >= 3:
            ss, hh = np.log([r["s"] for r in sel]), np.log([r["h_pipe"] for r in sel])
            print(f"  {subj}: {len(sel)} bouts, s {np.exp(ss).min():.3f}-{np.exp(ss).max():.3f} m, h "
                  f"{100 * np.exp(hh).min():.2f}-{100 * np.exp(hh).max():.2f} cm, log h on log s slope "
                  f"{np.polyfit(ss, hh, 1)[0]:+.2f}, r {_r(ss, hh):+.3f}")


if __name__ == "__main__":
    main()
