"""Decision W510 (docs/decisions/waist.md, session 45): waist-pll's step length below seed 000's linear walking range
(1.5-2.2 Hz): today's line extrapolated (`frequency_lengths`) against the candidate that holds the line's walk ratio
at 1.5 Hz constant below it, measured against W510's rule (written and committed before this run).

(a) users 12740-12747, `stand:3, straight:8, stand:3`, 0.3 m steps at 1.6 / 1.8 / 2.0 / 2.2 s (two users each),
    `bounce="pendulum"`, `rocker="smooth"`, 100 Hz, seed 0 (W504's walks), uncalibrated waist-pll with
    `pll_slow_follow`: distance error vs the nominal 8 m (W504's measure);
(b) users 12740-12749, scenario A at `slow` and `normal`, 100 Hz, uncalibrated waist-pll: `distance_error_pct`;
(c) the mobgap recordings, experiments/waist.py's external protocol for `waist-pll (A-HE)`: pooled median bout errors;
(d) read after the rule's measurement, not judged: the slow walkers calibrated on a 12 m walk of their own pace.

    PYTHONPATH=$PWD .venv/bin/python experiments/waist_pll_slow_end_s45.py [--external datasets/external]

Its printed output is committed as experiments/results/waist_pll_slow_end_s45.txt.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.waist.lengths as lengths_mod
import pdrlearn.waist.steplength as sl_mod
from pdrlearn.sim import Stand, Straight, UserProfile, simulate, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

ROOT = Path(__file__).resolve().parents[1]
from waist import external_runs, pooled, real  # noqa: E402

SLOW_WALKS = list(zip(range(12740, 12748), np.repeat([1.6, 1.8, 2.0, 2.2], 2), strict=True))
A_USERS = list(range(12740, 12750))
WALK_M = 8.0
FOLLOW = {"options": {"pll_slow_follow": True}}
ORIGINAL = sl_mod.frequency_lengths


def walk_ratio_slow_end(f_hz, p, *, running=None):
    """W510's candidate: the walking line below ``WALK_MIN_HZ`` (W118's dimensionless frequency) at the walk ratio it
    has at ``WALK_MIN_HZ`` (Sekiya & Nagasaki 1998, W100): ``SL(WALK_MIN_HZ) f / WALK_MIN_HZ``; elsewhere unchanged."""
    base = ORIGINAL(f_hz, p, running=running)
    f = np.asarray(f_hz, dtype=np.float64) * p.frequency_scale()
    run = f >= sl_mod.RUN_SPLIT_HZ if running is None else np.asarray(running, dtype=bool)
    at_min = float(ORIGINAL(np.array([sl_mod.WALK_MIN_HZ / p.frequency_scale()]), p,
                            running=np.zeros(1, dtype=bool))[0])
    slow = ~run & (f < sl_mod.WALK_MIN_HZ)
    return np.where(slow, np.clip(at_min * f / sl_mod.WALK_MIN_HZ, 0.0, None), base)


@contextlib.contextmanager
def candidate(on: bool):
    fn = walk_ratio_slow_end if on else ORIGINAL
    sl_mod.frequency_lengths, lengths_mod.frequency_lengths = fn, fn
    try:
        yield
    finally:
        sl_mod.frequency_lengths, lengths_mod.frequency_lengths = ORIGINAL, ORIGINAL


def slow_walk(user: int, step_s: float, *, seed: int = 0, metres: float = WALK_M):
    u = UserProfile.from_seed(user)
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(u, step_length_m=0.3 / f_len, class_step_length_m=u.step_length_m,
                            step_time_s=step_s / f_time)
    return simulate_path([Stand(3), Straight(metres), Stand(3)], u, speed="normal", rate_hz=100.0, seed=seed,
                         bounce="pendulum", rocker="smooth")


def part_a() -> pd.DataFrame:
    rows = []
    for u, step_s in SLOW_WALKS:
        s = slow_walk(u, float(step_s))
        row = {"user": u, "step_s": step_s, "true_contacts": len(s.extras["ics"])}
        for label, on in (("before", False), ("after", True)):
            with candidate(on):
                r = get_pipeline("waist-pll")(s, params=FOLLOW)
            d = float(r.steps["length_m"].sum())
            walking = r.steps[r.steps["has_next"]]
            row |= {f"contacts_{label}": len(r.steps), f"dist_{label}_m": round(d, 4),
                    f"err_{label}_pct": round(100 * (d - WALK_M) / WALK_M, 2),
                    f"median_step_{label}_m": round(float(walking["length_m"].median()), 4)}
        rows.append(row)
    return pd.DataFrame(rows)


def part_d() -> pd.DataFrame:
    """Read after W510's measurement, not judged: each slow walker calibrated (`waist-pll`, `pll_slow_follow`) on a
    12 m walk of its own at the same pace (seed 1) and tracked on part (a)'s walk (seed 0), today's line."""
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    rows = []
    for u, step_s in SLOW_WALKS:
        cal, test = slow_walk(u, float(step_s), seed=1, metres=12.0), slow_walk(u, float(step_s))
        base, _ = resolve_params(cal, None)
        base.options = dict(FOLLOW["options"])
        p = calibrate([cal], "waist-pll", distances=[12.0], params=base)
        r = get_pipeline("waist-pll")(test, params=p)
        d = float(r.steps["length_m"].sum())
        rows.append({"user": u, "step_s": step_s, "contacts": len(r.steps), "a_walk": round(p.a_walk, 3),
                     "b_walk": round(p.b_walk, 3), "err_pct": round(100 * (d - WALK_M) / WALK_M, 2)})
    return pd.DataFrame(rows)


def part_b() -> pd.DataFrame:
    rows = []
    for u in A_USERS:
        for speed in ("slow", "normal"):
            s = simulate("A", u, speed, rate_hz=100.0)
            row = {"user": u, "speed": speed}
            for label, on in (("before", False), ("after", True)):
                with candidate(on):
                    r = get_pipeline("waist-pll")(s)
                row[f"err_{label}_pct"] = round(float(evaluate_track(r, s)["distance_error_pct"]), 3)
            rows.append(row)
    return pd.DataFrame(rows)


def part_c(ext: Path) -> pd.DataFrame:
    out = []
    for label, on in (("before", False), ("after", True)):
        bouts: list = []
        with candidate(on):
            df = real(ext, runs=external_runs(ext), configs=[("waist-pll (A-HE)", "waist-pll", {})], bouts=bouts)
        b = pd.DataFrame(bouts)
        p = pooled(df, b)[["test", "params", "bout_err_median_pct", "bout_err_strides_median_pct"]]
        out.append(p.assign(code=label))
    return pd.concat(out, ignore_index=True)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    a = ap.parse_args(argv)
    if not any(a.external.glob("mobgap_*_Test5_Trial*")):
        raise SystemExit(f"error: {a.external}: no mobgap recordings; run `pdrlearn fetch mobgap` first")
    logging.disable(logging.WARNING)
    pd.set_option("display.width", 250)
    ra = part_a()
    print("(a) slow walks, uncalibrated waist-pll with pll_slow_follow\n" + ra.to_markdown(index=False))
    worse = (ra.err_after_pct.abs() - ra.err_before_pct.abs())
    print(f"(a) median |error| {ra.err_before_pct.abs().median():.2f} -> {ra.err_after_pct.abs().median():.2f} %; "
          f"largest worsening {worse.max():+.2f} points")
    rb = part_b()
    print("\n(b) scenario A, uncalibrated waist-pll\n" + rb.to_markdown(index=False))
    for speed, g in rb.groupby("speed"):
        print(f"(b) {speed}: median |error| {g.err_before_pct.abs().median():.3f} -> "
              f"{g.err_after_pct.abs().median():.3f} %")
    rc = part_c(a.external)
    print("\n(c) mobgap, waist-pll (A-HE), pooled\n" + rc.to_markdown(index=False))
    print("\n(d, read after the rule's measurement, not judged) calibrated on a 12 m walk at the same pace\n"
          + part_d().to_markdown(index=False))


if __name__ == "__main__":
    main()
