"""Decision S127: the simulator's default pelvis bounce, ``constant`` (S29) or ``population`` (S74), judged by what the
lower back reads of simulated walkers (issue 8, W618).

Per fresh user (``UserProfile.from_seed``; speeds slow / normal / fast in turn by user), two routes - a straight walk
and a daily-activity-like one (turns, a sit, short and long steps, a curve, stands) - each simulated once with every
``--bounce`` mode (the same seeds), 100 Hz, and tracked by ``waist-pendulum`` on the lower back alone:

- uncalibrated: meta.json's defaults (W46's population K);
- calibrated: :func:`pdrlearn.waist.calibration.calibrate` on the user's own separate 20 m straight walk (simulated
  with the same bounce, its known length given), then the two routes tracked with the fitted parameters.

Error = distance / truth - 1, truth = the sum of steps.csv's stride lengths (W618's). Waist step F1:
:func:`pdrlearn.steps.evaluate.score_steps` (the lower back's contacts against ics.csv's contacts of both feet, one
to one within 0.25 s), true / false positives and negatives pooled over the sessions.

    PYTHONPATH=. python experiments/default_bounce_s53_s127.py --users 19700-19739

``--misses``: the diagnosis of S128 instead - the daily route's truth contacts the lower back misses (no detection
within 0.25 s), tallied by ics.csv's ``kind``, and each kind's simulated peak-to-peak bounce and heel-to-heel step
length (:func:`pdrlearn.sim.body.step_lengths`), per bounce mode.

``--knob bout_envelope --bounce step,contact`` (decision W619): the same measures for another simulator option's
values (``--bounce`` then lists that knob's values; the bounce stays the simulator's default).
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

ROUTES = {
    "straight": "stand:3, straight:30, stand:3",
    "daily": "stand:5, straight:8, turn:90, straight:5:short, stand:6, sit:8, straight:12:long, curve:90:2, "
             "straight:6, stand:4, turn:180, straight:10, stand:5",
}
CAL_ROUTE = "stand:3, straight:20, stand:3"  # the user's calibration walk of known length (20 m)
SPEEDS = ("slow", "normal", "fast")


def one_user(u: int, rate_hz: float, bounces: tuple[str, ...], knob: str = "bounce") -> list[dict]:
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile
    from pdrlearn.steps.evaluate import score_steps
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    user = UserProfile.from_seed(u)
    speed = SPEEDS[u % 3]
    rows = []
    for bounce in bounces:
        cal = simulate_path(parse_route(CAL_ROUTE), user, speed=speed, seed=7, rate_hz=rate_hz, **{knob: bounce})
        try:
            fitted = calibrate([cal], "waist-pendulum", distances=[20.0])
        except Exception as exc:  # noqa: BLE001 - a failed calibration is a row, not a crash
            fitted = None
            print(f"u{u} {bounce}: calibrate failed: {exc}")
        for i, (name, route) in enumerate(ROUTES.items()):
            ses = simulate_path(parse_route(route), user, speed=speed, seed=1 + i, rate_hz=rate_hz, **{knob: bounce})
            truth = float(ses.steps["length_m"].abs().sum())
            p, _ = resolve_params(ses, None)
            res = track_waist(ses, pipeline="waist-pendulum", params=p)
            sc = score_steps(res.steps, ses, unit="waist") or {}
            row = {"user": u, "speed": speed, "route": name, knob: bounce, "truth_m": truth,
                   "err_uncal": 100 * (res.distance_m / truth - 1),
                   "tp": sc.get("true_positives", 0), "fp": sc.get("false_positives", 0),
                   "fn": sc.get("false_negatives", 0)}
            if fitted is not None:
                rc = track_waist(ses, pipeline="waist-pendulum", params=fitted)
                row["err_cal"] = 100 * (rc.distance_m / truth - 1)
                row["k_cal"] = float(fitted.k) if getattr(fitted, "k", None) is not None else np.nan
            else:
                row["err_cal"] = np.nan
            rows.append(row)
    return rows


def misses(u: int, rate_hz: float, bounces: tuple[str, ...], knob: str = "bounce") -> list[dict]:
    """S128's diagnosis: per truth contact of the daily route, its kind, whether the lower back found it, the step's
    heel-to-heel length and its simulated bounce (peak to peak of the waist unit's height from this contact to the
    next)."""
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile
    from pdrlearn.steps.evaluate import match_events
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    user = UserProfile.from_seed(u)
    speed = SPEEDS[u % 3]
    rows = []
    for bounce in bounces:
        ses = simulate_path(parse_route(ROUTES["daily"]), user, speed=speed, seed=2, rate_hz=rate_hz,
                            **{knob: bounce})
        ics = ses.extras["ics"].sort_values("ic_s")
        ref = ics["ic_s"].to_numpy(float)
        res = track_waist(ses, pipeline="waist-pendulum", params=resolve_params(ses, None)[0])
        _, i_r = match_events(res.steps["start_s"].to_numpy(float), ref, 0.25)
        found = np.zeros(ref.size, bool)
        found[i_r] = True
        tr = ses.trajectory
        t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
        xy = tr[["x", "y"]].to_numpy(float)
        for k in range(ref.size - 1):
            m = (t >= ref[k]) & (t <= ref[k + 1])
            p0 = np.array([np.interp(ref[k], t, xy[:, 0]), np.interp(ref[k], t, xy[:, 1])])
            p1 = np.array([np.interp(ref[k + 1], t, xy[:, 0]), np.interp(ref[k + 1], t, xy[:, 1])])
            rows.append({"user": u, knob: bounce, "kind": ics["kind"].iloc[k], "found": bool(found[k]),
                         "h_cm": 100 * float(np.ptp(z[m])) if m.any() else np.nan,
                         "pelvis_m": float(np.linalg.norm(p1 - p0))})
    return rows


def _spread(v) -> str:
    v = np.asarray(v, float)
    v = v[np.isfinite(v)]
    if v.size < 2:
        return f"n {v.size}"
    q1, q3 = np.percentile(v, [25, 75])
    return (f"n {v.size}, median {np.median(v):+.2f} %, IQR {q3 - q1:.2f}, SD {np.std(v, ddof=1):.2f}, "
            f"min {v.min():+.2f}, max {v.max():+.2f}, median |err| {np.median(np.abs(v)):.2f}")


def _f1(d) -> str:
    tp, fp, fn = int(d.tp.sum()), int(d.fp.sum()), int(d.fn.sum())
    f1 = 2 * tp / max(2 * tp + fp + fn, 1)
    return f"F1 {f1:.4f} (tp {tp}, fp {fp}, fn {fn})"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="19700-19739")
    ap.add_argument("--rate", type=float, default=100.0)
    ap.add_argument("--bounce", default="constant,population", help="the values compared (of --knob)")
    ap.add_argument("--knob", default="bounce", help="the simulator option compared (W619: bout_envelope)")
    ap.add_argument("--misses", action="store_true", help="S128's diagnosis: the missed contacts by kind")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, hi = (int(v) for v in a.users.split("-"))
    bounces = tuple(a.bounce.split(","))
    import pandas as pd

    rows = []
    if a.misses:
        for u in range(lo, hi + 1):
            rows += misses(u, a.rate, bounces, a.knob)
        df = pd.DataFrame(rows)
        print(f"users {lo}-{hi}, {a.rate:g} Hz, daily route {ROUTES['daily']!r}: truth contacts by kind (the step "
              "from each contact to the next)")
        g = df.groupby(["kind", a.knob]).agg(contacts=("found", "size"), missed=("found", lambda f: int((~f).sum())),
                                               h_cm_median=("h_cm", "median"), pelvis_m_median=("pelvis_m", "median"))
        print(g.to_string())
        return
    for u in range(lo, hi + 1):
        rows += one_user(u, a.rate, bounces, a.knob)
        last = [r for r in rows if r["user"] == u]
        print("  ".join(f"u{u} {r['route']} {r[a.knob]} uncal {r['err_uncal']:+.2f} cal {r['err_cal']:+.2f}"
                        for r in last), flush=True)
    df = pd.DataFrame(rows)
    with pd.option_context("display.width", 250, "display.max_columns", 40, "display.float_format", "{:.3f}".format):
        print(f"\nusers {lo}-{hi}, {a.rate:g} Hz, waist-pendulum, routes {ROUTES}, calibration {CAL_ROUTE!r} (20 m)")
        print(df.to_string(index=False))
    for sel, d0 in [("all", df), *[(f"route {k}", df[df.route == k]) for k in ROUTES],
                    *[(f"speed {k}", df[df.speed == k]) for k in SPEEDS]]:
        print(f"\n{sel}:")
        for bounce in bounces:
            d = d0[d0[a.knob] == bounce]
            print(f"  {bounce:10s} uncalibrated {_spread(d.err_uncal)}")
            print(f"  {bounce:10s} calibrated   {_spread(d.err_cal)}")
            print(f"  {bounce:10s} waist steps  {_f1(d)}")


if __name__ == "__main__":
    main()
