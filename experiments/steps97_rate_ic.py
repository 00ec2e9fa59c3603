"""Steps decision 97 (session 53, FG; trial s53t3 F1): does the foot's IC move with the sampling rate, before
(main's detector) and with ``AccelStepDetector(event_power=True)`` (the RMS envelope), by the rule written in
docs/decisions/steps.md before measuring.

(a) Real gaitmap walks resampled with scipy ``resample_poly`` (as trial s53t3's resample.py) to ~100 / 200 / 400 /
1000 Hz: per recording and rate, the native ICs whose nearest IC on the copy lies more than 10 ms away ("moved").
(b) Native rate: ``score_steps_events`` (F1, IC timing vs mocap) and ``track --toe-off`` stride-length error.
(c) Fresh simulated users 20600-20619 (``stand:3, straight:30, stand:3``, 100 / 50 / 25 Hz, fForce* deleted),
``track --toe-off`` (before: no ``--detector``; after: ``--detector accel:event_power=true``): the straight-stride
stance bias per user and rate, and its spread across the rates.

Run ``python experiments/steps97_rate_ic.py [real|sim|all]`` (work files under /tmp/fg_s53); it prints the tables and
writes experiments/results/steps97_rate_ic.txt (all).
"""
from __future__ import annotations

import contextlib
import io
import json
import logging
import math
import shutil
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.steps.detectors import AccelStepDetector
from pdrlearn.steps.evaluate import score_steps_events

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import RESULTS  # noqa: E402

WORK = Path("/tmp/fg_s53")
SHARED = Path("/work/shared/data")
EXTERNAL = Path(__file__).resolve().parents[1] / "datasets" / "external"
REAL = [SHARED / "gaitmap_level_left", SHARED / "gaitmap_level_right", EXTERNAL / "gaitmap_ms_left",
        EXTERNAL / "gaitmap_ms_right", EXTERNAL / "gaitmap_walk4x10_left", EXTERNAL / "gaitmap_walk4x10_right",
        EXTERNAL / "gaitmap_lwalk"]
TARGETS = (100, 200, 400, 1000)
USERS = range(20600, 20620)
SIM_RATES = (100, 50, 25)
VARIANTS = {"before": {}, "after": {"event_power": True}}
SPEC = {"before": [], "after": ["--detector", "accel:event_power=true"]}


def resample(src: Path, target: float) -> Path:
    """``src``'s foot streams resampled (resample_poly, padtype line) to the rate nearest ``target`` (a ratio with a
    denominator up to 20); the native rate is the folder itself."""
    from scipy.signal import resample_poly

    meta = json.loads((src / "meta.json").read_text())
    r0 = float(meta["rate_hz"])
    fr = Fraction(target / r0).limit_denominator(20)
    if fr == 1:
        return src
    up, down = fr.numerator, fr.denominator
    rate = r0 * up / down
    out = WORK / "rs" / f"{src.name}_{rate:g}"
    if (out / "meta.json").exists():
        return out
    out.mkdir(parents=True, exist_ok=True)
    for f in src.iterdir():
        if f.is_file() and f.name not in ("fAccelerometer.csv", "fGyroscope.csv", "meta.json"):
            shutil.copy(f, out)
    for name in ("fAccelerometer.csv", "fGyroscope.csv"):
        d = pd.read_csv(src / name)
        x = resample_poly(d[["x", "y", "z"]].to_numpy(float), up, down, axis=0, padtype="line")
        t = float(d["timestamp"].iloc[0]) + np.arange(len(x)) * 1000.0 / rate
        pd.DataFrame({"timestamp": t, "x": x[:, 0], "y": x[:, 1], "z": x[:, 2]}).to_csv(out / name, index=False)
    meta.update(rate_hz=rate, n_samples=len(x), session=f"{meta.get('session', src.name)}_{rate:g}Hz")
    (out / "meta.json").write_text(json.dumps(meta, indent=1))
    return out


def events(d: Path, kw: dict) -> np.ndarray:
    return np.sort(np.asarray(AccelStepDetector(**kw).detect(read_session(d))["event_s"], float))


def real_moves() -> pd.DataFrame:
    rows = []
    for src in REAL:
        for name, kw in VARIANTS.items():
            base = events(src, kw)
            for target in TARGETS:
                d = resample(src, target)
                ev = events(d, kw)
                diff = np.array([np.min(np.abs(ev - x)) if len(ev) else math.inf for x in base]) * 1000
                moved = int((diff > 10).sum())
                rows.append({"recording": src.name, "variant": name, "rate": json.loads((d / "meta.json").read_text())
                             ["rate_hz"], "n": len(base), "moved": moved, "allowed": math.ceil(2 / 32 * len(base)),
                             "max_ms": round(float(diff.max()), 1)})
    return pd.DataFrame(rows)


def native_scores() -> pd.DataFrame:
    rows = []
    for src in REAL:
        s = read_session(src)
        for name, kw in VARIANTS.items():
            sc, _ = score_steps_events(AccelStepDetector(**kw).detect(s), s)
            if not sc or not math.isfinite(sc.get("timing_error_mean_s", math.nan)):
                continue
            rows.append({"recording": src.name, "variant": name, "f1": round(sc["f1"], 4),
                         "timing_mean_ms": round(1000 * sc["timing_error_mean_s"], 2),
                         "timing_sd_ms": round(1000 * sc["timing_error_sd_s"], 2)})
    return pd.DataFrame(rows)


def track(d: Path, name: str) -> pd.DataFrame:
    out = WORK / "tr" / f"{d.name}_{name}"
    if not (out / "steps.csv").exists():
        with contextlib.redirect_stdout(io.StringIO()):
            code = main(["track", str(d), "--toe-off", "--no-plot", "--out", str(out), *SPEC[name]])
        if code:
            raise SystemExit(f"track {d} {name}: exit {code}")
    return pd.read_csv(out / "steps.csv")


def matched(steps: pd.DataFrame) -> pd.DataFrame:
    m = steps[steps["ref_match"].notna()]
    if "ref_composed" in m:
        m = m[~m["ref_composed"].fillna(False).astype(bool)]
    return m


def native_lengths() -> pd.DataFrame:
    rows = []
    for src in REAL[:2]:
        for name in VARIANTS:
            m = matched(track(src, name))
            e = (m["length_m"] - m["ref_length_m"]).dropna()
            st = (m["stance_time_s"] - m["ref_stance_time_s"]).dropna() * 1000
            rows.append({"recording": src.name, "variant": name, "n": len(e),
                         "length_abs_err_cm": round(100 * float(e.abs().mean()), 2),
                         "stance_bias_ms": round(float(st.mean()), 1)})
    return pd.DataFrame(rows)


def sim_walk(u: int, rate: int) -> Path:
    d = WORK / "sim" / f"u{u}_{rate}"
    if not (d / "ics.csv").exists():
        with contextlib.redirect_stdout(io.StringIO()):
            code = main(["simulate", "--route", "stand:3, straight:30, stand:3", "--rate", str(rate), "--user-seed",
                         str(u), "-o", str(d), "--force"])
        if code:
            raise SystemExit(f"simulate u{u} {rate} Hz: exit {code}")
        for n in ("fForceA.csv", "fForceB.csv"):
            (d / n).unlink(missing_ok=True)
    return d


def sim() -> tuple[pd.DataFrame, pd.DataFrame]:
    rows = []
    for u in USERS:
        for rate in SIM_RATES:
            d = sim_walk(u, rate)
            for name in VARIANTS:
                m = matched(track(d, name))
                if "turn_angle_rad" in m:
                    m = m[m["turn_angle_rad"].abs() < math.radians(15)]
                st = (m["stance_time_s"] - m["ref_stance_time_s"]).dropna() * 1000
                rows.append({"user": u, "rate": rate, "variant": name, "n": len(st),
                             "stance_bias_ms": round(float(st.mean()), 2) if len(st) else math.nan})
    df = pd.DataFrame(rows)
    spread = (df.groupby(["user", "variant"])["stance_bias_ms"].agg(lambda x: x.max() - x.min())
              .unstack("variant").round(2))
    return df, spread


def run(part: str) -> str:
    logging.disable(logging.WARNING)
    text = []
    if part in ("real", "all"):
        mv = real_moves()
        text += ["# (a) moved ICs (> 10 ms from the native IC) per recording, variant and rate",
                 mv.to_string(index=False), "", "# (b) native rate: score_steps_events",
                 native_scores().to_string(index=False), "",
                 "# (b) native rate: track --toe-off (matched non-composed strides)",
                 native_lengths().to_string(index=False), ""]
    if part in ("sim", "all"):
        df, spread = sim()
        piv = df.pivot_table(index="user", columns=["variant", "rate"], values="stance_bias_ms")
        text += ["# (c) straight-stride stance bias (ms) per user, variant, rate", piv.round(2).to_string(), "",
                 "# (c) spread across 100 / 50 / 25 Hz (max - min, ms) per user", spread.to_string(), "",
                 f"# (c) median spread: before {spread['before'].median():.2f} ms, "
                 f"after {spread['after'].median():.2f} ms",
                 ""]
    return "\n".join(text) + "\n"


if __name__ == "__main__":
    part = sys.argv[1] if len(sys.argv) > 1 else "all"
    report = run(part)
    print(report)
    if part == "all":
        RESULTS.mkdir(exist_ok=True)
        (RESULTS / "steps97_rate_ic.txt").write_text(report)
