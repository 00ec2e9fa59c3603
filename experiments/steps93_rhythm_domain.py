"""Steps decisions 91, 93, 94 (session 48, FM; trial R2-F1 / F2 / F7): the domain of steps 91's rhythm re-take of a
short stride's impact, measured by the rules written in docs/decisions/steps.md before measuring.

Walks (fresh simulated users, each simulated once per rate and detected by every variant): children 16100-16111 (steps
87 / 88 / 91's command: ``--route "stand:3, straight:20, stand:3" --rocker smooth --height H --leg-length 0.523 H
--step-length 0.323 H --step-time T``, H cycling 1.15 / 1.25 / 1.30 / 1.35 / 1.45 m and T 0.34 / 0.36 / 0.38 / 0.40 /
0.42 / 0.44 s by the user's index), race walkers 16112-16121 (trial R2's ``race_ics.py``: a step of 0.90-1.05 m
(capped at the simulator's 1 m) in 0.27-0.33 s drawn from the user's seed, ``stand:3, straight:60, stand:3``), adults
16122-16127 (the drawn adult) and 16128-16133 (``--speed fast``) on ``stand:3, straight:30, stand:3``; every walk at
50 and 100 Hz; fForce* deleted. Variants: ``dec3`` (``short_period_s=0``, decision 3 alone), ``s91`` (steps 91, the
default before: both gates 0), ``s93`` (``short_min_rate_hz=90``), ``s94`` (``short_max_amp=65``, the default since
steps 94) and ``s93+94`` (both). Each of the instrumented foot's ics.csv contacts is matched to the nearest detected
``event_s`` within 0.3 s; early = an error under -50 ms, late = over +25 ms; CV = the detected IC-to-IC stride times'
CV between the second and the second-last true contact, its truth the true contacts' (trial R2's scripts). The real
gaitmap recordings are scored by ``score_steps_events``.

Run ``python experiments/steps93_rhythm_domain.py`` (sessions under /tmp/fm_s48/sim, kept between runs); it prints
the per-walk rows, the per-group summaries and the real recordings and writes
experiments/results/steps93_rhythm_domain.txt.
"""
from __future__ import annotations

import contextlib
import io
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.steps.detectors import AccelStepDetector
from pdrlearn.steps.evaluate import score_steps_events

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import RESULTS  # noqa: E402

SIM = Path("/tmp/fm_s48/sim")
REAL = Path("/work/shared/data")
CHILDREN = range(16100, 16112)
RACE = range(16112, 16122)
ADULTS = range(16122, 16128)
FAST = range(16128, 16134)
RATES = (50, 100)
VARIANTS = {"dec3": {"short_period_s": 0.0}, "s91": {"short_min_rate_hz": 0.0, "short_max_amp": 0.0},
            "s93": {"short_min_rate_hz": 90.0, "short_max_amp": 0.0},
            "s94": {"short_min_rate_hz": 0.0, "short_max_amp": 65.0},
            "s93+94": {"short_min_rate_hz": 90.0, "short_max_amp": 65.0}}
HEIGHTS = (1.15, 1.25, 1.30, 1.35, 1.45)
STEP_TIMES = (0.34, 0.36, 0.38, 0.40, 0.42, 0.44)


def command(u: int, rate: int) -> tuple[str, list[str]]:
    """The group and the ``simulate`` options of user ``u`` at ``rate`` Hz."""
    base = ["--rocker", "smooth", "--rate", str(rate), "--user-seed", str(u)]
    if u in CHILDREN:
        i = u - CHILDREN.start
        h, t = HEIGHTS[i % len(HEIGHTS)], STEP_TIMES[i % len(STEP_TIMES)]
        return "child", base + ["--route", "stand:3, straight:20, stand:3", "--height", f"{h}", "--leg-length",
                                f"{0.523 * h:.4f}", "--step-length", f"{0.323 * h:.3f}", "--step-time", f"{t:.3f}"]
    if u in RACE:
        rng = np.random.default_rng(u)
        length, t = min(rng.uniform(0.90, 1.05), 1.0), rng.uniform(0.27, 0.33)  # simulate takes steps up to 1 m
        return "race", base + ["--route", "stand:3, straight:60, stand:3", "--step-length", f"{length:.3f}",
                               "--step-time", f"{t:.3f}"]
    speed = ["--speed", "fast"] if u in FAST else []
    return ("fast" if u in FAST else "adult"), base + ["--route", "stand:3, straight:30, stand:3"] + speed


def walk(u: int, rate: int) -> tuple[str, Path]:
    group, opts = command(u, rate)
    d = SIM / f"u{u}_{rate}"
    if not (d / "ics.csv").exists():
        with contextlib.redirect_stdout(io.StringIO()):
            code = main(["simulate", *opts, "-o", str(d), "--force"])
        if code:
            raise SystemExit(f"simulate {' '.join(opts)}: exit {code}")
        for n in ("fForceA.csv", "fForceB.csv"):
            (d / n).unlink(missing_ok=True)
    return group, d


def cv(x: np.ndarray) -> float:
    d = np.diff(x)
    return float(100 * np.std(d, ddof=1) / np.mean(d))


def score(d: Path) -> list[dict]:
    s = read_session(d)
    ics = pd.read_csv(d / "ics.csv")
    truth = np.sort(ics[ics.foot == s.meta.get("instrumented_foot", "right")]["ic_ms"].to_numpy(float) / 1000)
    rows = []
    for name, kw in VARIANTS.items():
        table = AccelStepDetector(**kw).detect(s)
        ev = np.sort(np.asarray(table["event_s"], float))
        err = np.array([ev[np.argmin(np.abs(ev - x))] - x for x in truth])
        m = np.abs(err) < 0.3
        e = err[m] * 1000
        inner = ev[(ev > truth[1] - 0.1) & (ev < truth[-2] + 0.1)]
        rows.append({"variant": name, "n_truth": len(truth), "matched": int(m.sum()), "early": int((e < -50).sum()),
                     "late": int((e > 25).sum()), "mean_ms": float(e.mean()), "sd_ms": float(e.std()),
                     "cv": cv(inner), "true_cv": cv(truth[1:-1]), "errs": e,
                     "amp_med": float(np.median(table["amplitude"]))})
    return rows


def summary(df: pd.DataFrame) -> pd.DataFrame:
    out = []
    for (group, rate, name), g in df.groupby(["group", "rate", "variant"], sort=False):
        e = np.concatenate(g["errs"].to_list())
        gap = (g["cv"] - g["true_cv"]).abs()
        out.append({"group": group, "rate": rate, "variant": name, "walks": len(g), "ics": len(e),
                    "early": int(g["early"].sum()), "late": int(g["late"].sum()),
                    "missed": int((g["n_truth"] - g["matched"]).sum()), "mean_ms": round(float(e.mean()), 2),
                    "sd_ms": round(float(e.std()), 2), "cv_gap_med": round(float(gap.median()), 2),
                    "within_1pt": int((gap <= 1).sum())})
    return pd.DataFrame(out)


def real() -> pd.DataFrame:
    out = []
    for d in sorted(REAL.glob("gaitmap_*")):
        s = read_session(d)
        for name, kw in VARIANTS.items():
            sc, _ = score_steps_events(AccelStepDetector(**kw).detect(s), s)
            out.append({"recording": d.name, "variant": name, "n": sc["count"], "f1": round(sc["f1"], 4),
                        "timing_mean_ms": round(1000 * sc["timing_error_mean_s"], 2),
                        "timing_sd_ms": round(1000 * sc["timing_error_sd_s"], 2)})
    return pd.DataFrame(out)


def run() -> str:
    logging.disable(logging.WARNING)
    rows = []
    for u in (*CHILDREN, *RACE, *ADULTS, *FAST):
        for rate in RATES:
            group, d = walk(u, rate)
            rows += [{"user": u, "group": group, "rate": rate, **r} for r in score(d)]
    df = pd.DataFrame(rows)
    walks = df.drop(columns="errs").round(2)
    text = ["# steps 91 / 93 / 94: per walk", walks.to_string(index=False), "",
            "# per group (pooled matched ICs; cv_gap_med = median |CV - true CV|, within_1pt = walks within 1 point)",
            summary(df).to_string(index=False), "", "# real gaitmap recordings (score_steps_events)",
            real().to_string(index=False)]
    return "\n".join(text) + "\n"


if __name__ == "__main__":
    report = run()
    print(report)
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "steps93_rhythm_domain.txt").write_text(report)
