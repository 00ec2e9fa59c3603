"""Robustness of the foot and lower-back pipelines to plausible differences of unseen recordings.

Each perturbation is applied alone to the real sessions (datasets/real/gaitmap_level_* and the foot and
lower-back sessions of datasets/external, ``make external``), the session is written to disk in the
PLASYS layout (``write_session``) and read back with ``read_session`` -- so the reader's checks run too --
and the standard evaluations are re-run:

- foot (gaitmap level left/right, walk4x10 left/right, lwalk, ms left/right): stride F1 of the ``accel``
  detector (``pdrlearn steps``: ``get_detector`` + ``score_steps``), stride-length MAE and distance error
  of ``track_plasys(method="M3", model="oracle", steps="detector")`` (``pdrlearn track --model oracle``)
  where a reference length exists (level walks), and for every session the tracked distance relative to
  the unperturbed one (self-consistency: the sessions without a length reference);
- lower back (mobgap HA001, HA002, MS001 Test5/Test11): the waist-pendulum protocol of
  ``experiments/waist.py`` (``waist.real`` with its ``external_runs``: per-user calibration on the
  perturbed Test5 walks, test on the other perturbed recordings; same device and mounting; one gap row
  perturbs the test recordings only), the magnetometer and barometer left out (the waist pipelines do
  not read them): step F1 pooled with ``waist.pooled``, per-run distance error in the reference bouts,
  the median |bout distance error|.

Perturbations (each alone): mounting rotations (a multiple of 90 degrees is declared truthfully in
``meta.json`` ``frames`` -- the only axis information the pipelines read (``pdrlearn.io.frames``); other
angles cannot be declared and keep the nominal frame; "undeclared" rows show a 90-degree turn the
meta.json does not describe), anti-aliased resampling (``scipy.signal.resample_poly``), a clock that
does not start at 0, accelerometer/gyroscope scale and bias errors, doubled white noise, timestamp
jitter, a 0.5 s gap and duplicated timestamps.

Usage::

    .venv/bin/python experiments/robustness.py [--only REGEX] [--unit foot|waist|both] [--keep DIR]

Writes experiments/results/robustness.md and robustness.csv (one row per perturbation x session/run, plus
the pooled waist rows). ~5 min CPU. Reading guide: docs/robustness.md.
"""

# ruff: noqa: E501  (report tables are long lines)
from __future__ import annotations

import argparse
import logging
import re
import shutil
import sys
import tempfile
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.signal import resample_poly
from scipy.spatial.transform import Rotation

from pdrlearn.io import read_session
from pdrlearn.io.frames import _DIRECTIONS, AxisFrame
from pdrlearn.io.plasys import DEFAULT_TIME_COLUMNS, write_session
from pdrlearn.io.session import Session, Stream
from pdrlearn.steps import get_detector, score_steps
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
import waist as waist_exp  # noqa: E402  (experiments/waist.py: the waist protocol, reused)

OUT = ROOT / "experiments" / "results"
REAL = ROOT / "datasets" / "real"
EXTERNAL = ROOT / "datasets" / "external"
FOOT = [REAL / "gaitmap_level_left", REAL / "gaitmap_level_right",
        EXTERNAL / "gaitmap_walk4x10_left", EXTERNAL / "gaitmap_walk4x10_right", EXTERNAL / "gaitmap_lwalk",
        EXTERNAL / "gaitmap_ms_left", EXTERNAL / "gaitmap_ms_right"]
WAIST_CONFIG = [c for c in waist_exp.CONFIGS if c[0] == "waist-pendulum"]
UNIT_STREAMS = {"foot": ("fAccelerometer", "fGyroscope", "fMagneticField"),
                "waist": ("wAccelerometer", "wGyroscope", "wMagneticField")}

log = logging.getLogger("robustness")


# -- perturbations ------------------------------------------------------------------------------------
def _time_columns(df: pd.DataFrame) -> list[str]:
    cols = df.attrs.get("time_columns") or DEFAULT_TIME_COLUMNS
    return [c for c in cols if c in df.columns]


def shift_time(s: Session, dt: float) -> Session:
    """Every stream and label time + ``dt`` seconds (one clock: labels stay aligned)."""
    s = s.copy()
    for k, st in s.streams.items():
        s.streams[k] = Stream(st.name, st.t + dt, st.values)
    for df in [t for t in (s.steps, *s.extras.values()) if t is not None]:
        for c in _time_columns(df):
            df[c] = df[c].astype(float) + dt
    if s.trajectory is not None:
        s.trajectory["t"] = s.trajectory["t"] + dt
    return s


def _axis_in_sensor(frame: AxisFrame, direction: str) -> np.ndarray:
    """Unit vector (sensor coordinates) of a body direction."""
    return frame.matrix().T @ np.array(_DIRECTIONS[direction])


def _frame_of(matrix: np.ndarray) -> AxisFrame | None:
    """The AxisFrame whose matrix is ``matrix`` (a signed permutation), else None."""
    names = []
    for j in range(3):
        col = matrix[:, j]
        hit = [d for d, v in _DIRECTIONS.items() if np.allclose(col, v, atol=1e-9)]
        if not hit:
            return None
        names.append(hit[0])
    return AxisFrame(*names)


def rotate(s: Session, placement: str, about: str, deg: float, *, declare: bool = True) -> Session:
    """Mount the ``placement`` unit rotated by ``deg`` about the body direction ``about`` (right-hand rule).

    A physical vector's components in the new sensor frame are ``R^T v`` (R = the rotation expressed in
    the old sensor frame); the declared frame becomes ``M R``. When that is a signed permutation and
    ``declare`` is true, meta.json's ``frames`` says so (what a user would truthfully write); otherwise the
    nominal frame stays (a tilt or an odd yaw cannot be declared)."""
    s = s.copy()
    frame = s.frames[placement]
    R = Rotation.from_rotvec(np.radians(deg) * _axis_in_sensor(frame, about)).as_matrix()
    for name in UNIT_STREAMS[placement]:
        if name in s.streams:
            st = s.streams[name]
            s.streams[name] = Stream(name, st.t, st.values @ R)  # rows: (R^T v)^T = v^T R
    new = _frame_of(frame.matrix() @ R)
    if declare and new is not None:
        s.frames[placement] = new
        axes = dict(s.meta.get("axes", {}))
        axes.update({a: getattr(new, a) for a in "xyz"})
        axes["how_obtained"] = f"robustness experiment: unit remounted {deg:+g} deg about '{about}'"
        s.meta["axes"] = axes
    return s


def resample(s: Session, rate_hz: float) -> Session:
    """Anti-aliased polyphase resampling of every stream to ``rate_hz`` (uniform new clock)."""
    s = s.copy()
    for k, st in s.streams.items():
        fs = st.rate_hz
        ratio = Fraction(rate_hz / fs).limit_denominator(2000)
        if ratio == 1:
            continue
        v = resample_poly(st.values, ratio.numerator, ratio.denominator, axis=0, padtype="line")
        t = st.t[0] + np.arange(len(v)) / rate_hz
        s.streams[k] = Stream(st.name, t, v)
    s.meta["rate_hz"] = rate_hz
    return s


def sensor_error(s: Session, *, acc_scale: float = 1.0, gyr_scale: float = 1.0,
                 gyr_bias: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Session:
    s = s.copy()
    for k, st in s.streams.items():
        if st.kind == "accelerometer":
            s.streams[k] = Stream(k, st.t, st.values * acc_scale)
        elif st.kind == "gyroscope":
            s.streams[k] = Stream(k, st.t, st.values * gyr_scale + np.asarray(gyr_bias))
    return s


def white_noise_sd(st: Stream, window_s: float = 0.1) -> np.ndarray:
    """Per-axis white-noise sd: third differences / sqrt(20) (they suppress the gait signal: a 5 Hz
    component at 100 Hz keeps 3 % of its amplitude), robust (MAD) per 0.1 s window (short enough to fit
    in an MS patient's foot-flat), 5th percentile of the windows (the quietest periods). Approximate:
    an upper bound on recordings that never rest."""
    n = max(8, int(round(window_s * st.rate_hz)))
    d = np.diff(st.values, n=3, axis=0) / np.sqrt(20.0)
    sds = [1.4826 * np.median(np.abs(d[i:i + n] - np.median(d[i:i + n], axis=0)), axis=0)
           for i in range(0, len(d) - n, n)]
    return np.percentile(np.array(sds), 5, axis=0)


def more_noise(s: Session, rng: np.random.Generator, factor: float = 2.0) -> Session:
    """White noise added so that the accelerometer's and gyroscope's noise sd becomes ``factor`` x."""
    s = s.copy()
    for k, st in s.streams.items():
        if st.kind in ("accelerometer", "gyroscope"):
            sd = white_noise_sd(st) * np.sqrt(factor ** 2 - 1)
            s.streams[k] = Stream(k, st.t, st.values + rng.normal(size=st.values.shape) * sd)
    return s


def jitter(s: Session, rng: np.random.Generator, ms: float = 1.0) -> Session:
    """Timestamps +- ``ms`` (uniform); the samples stay where they were taken."""
    s = s.copy()
    for k, st in s.streams.items():
        t = st.t + rng.uniform(-ms, ms, size=len(st)) * 1e-3
        t[0], t[-1] = st.t[0], st.t[-1]
        s.streams[k] = Stream(k, t, st.values)
    return s


def _walking_middle(s: Session) -> float:
    st = s.steps
    if st is not None and len(st):
        return float(0.5 * (st["start_s"].min() + st["end_s"].max()))
    return 0.5 * (s.t_start + s.t_end)


def gap(s: Session, seconds: float = 0.5) -> Session:
    """Every stream loses the samples of ``seconds`` in the middle of the labelled walking."""
    s = s.copy()
    t0 = _walking_middle(s)
    for k, st in s.streams.items():
        keep = (st.t < t0) | (st.t >= t0 + seconds)
        s.streams[k] = Stream(k, st.t[keep], st.values[keep])
    return s


def duplicates(s: Session, n: int = 3) -> Session:
    """``n`` samples of every stream repeated with the same timestamp (a logger writing a row twice)."""
    s = s.copy()
    for k, st in s.streams.items():
        idx = np.sort(np.linspace(len(st) // 4, 3 * len(st) // 4, n).astype(int))
        rep = np.ones(len(st), int)
        rep[idx] = 2
        s.streams[k] = Stream(k, np.repeat(st.t, rep), np.repeat(st.values, rep, axis=0))
    return s


@dataclass
class Perturbation:
    category: str
    name: str
    units: tuple[str, ...]  # which evaluations it applies to
    fn: Callable[[Session, np.random.Generator, str], Session]  # (session, rng, placement)
    calibration: bool = True  # waist: perturb the calibration walks too (same device), else the tests only


def _tilts(unit: str, deg: int) -> list[Perturbation]:
    """Pitch and roll of ``unit``'s mount by +-``deg`` (undeclared: gravity levels them), and the unit
    upside down (roll 180, declared)."""
    out = [Perturbation("mounting", f"{unit} {label} {d:+d} deg", (unit,),
                        lambda s, r, p, a=about, d=d: rotate(s, p, a, d))
           for about, label in (("left", "pitch"), ("forward", "roll")) for d in (deg, -deg)]
    out.append(Perturbation("mounting", f"{unit} upside down (roll 180, declared)", (unit,),
                            lambda s, r, p: rotate(s, p, "forward", 180)))
    return out


def _perturbations() -> list[Perturbation]:
    P = Perturbation
    out = [P("baseline", "none (write + read back)", ("foot", "waist"), lambda s, r, p: s)]
    for deg in (30, -30, 90, -90, 180):
        out.append(P("mounting", f"foot yaw {deg:+d} deg", ("foot",), lambda s, r, p, d=deg: rotate(s, p, "up", d)))
    out.append(P("mounting", "foot yaw +90 deg undeclared", ("foot",),
                 lambda s, r, p: rotate(s, p, "up", 90, declare=False)))
    out += _tilts("foot", 20)
    out.append(P("mounting", "foot axes permuted (roll -90: z to the right, declared)", ("foot",),
                 lambda s, r, p: rotate(s, p, "forward", -90)))
    for deg in (90, -90, 30, -30, 15):
        out.append(P("mounting", f"waist yaw {deg:+d} deg (belt at the side)" if abs(deg) == 90 else
                     f"waist yaw {deg:+d} deg", ("waist",), lambda s, r, p, d=deg: rotate(s, p, "up", d)))
    out.append(P("mounting", "waist yaw +90 deg undeclared", ("waist",),
                 lambda s, r, p: rotate(s, p, "up", 90, declare=False)))
    out += _tilts("waist", 15)
    for hz in (100.0, 128.0, 60.0):
        out.append(P("rate", f"foot resampled to {hz:g} Hz", ("foot",), lambda s, r, p, h=hz: resample(s, h)))
    for hz in (50.0, 64.0, 128.0, 200.0):
        out.append(P("rate", f"waist resampled to {hz:g} Hz", ("waist",), lambda s, r, p, h=hz: resample(s, h)))
    out.append(P("rate", "clock starts at 1000 s", ("foot", "waist"), lambda s, r, p: shift_time(s, 1000.0)))
    out.append(P("rate", "clock = Unix time (1.7e9 s)", ("foot", "waist"),
                 lambda s, r, p: shift_time(s, 1.7e9)))
    for sc in (1.03, 0.97):
        out.append(P("sensor", f"accelerometer scale {100 * (sc - 1):+.0f} %", ("foot", "waist"),
                     lambda s, r, p, k=sc: sensor_error(s, acc_scale=k)))
        out.append(P("sensor", f"gyroscope scale {100 * (sc - 1):+.0f} %", ("foot", "waist"),
                     lambda s, r, p, k=sc: sensor_error(s, gyr_scale=k)))
    out.append(P("sensor", "gyroscope bias (+0.03, -0.03, +0.03) rad/s", ("foot", "waist"),
                 lambda s, r, p: sensor_error(s, gyr_bias=(0.03, -0.03, 0.03))))
    out.append(P("sensor", "white noise x2 (acc, gyr)", ("foot", "waist"), lambda s, r, p: more_noise(s, r)))
    out.append(P("timing", "timestamp jitter +-1 ms", ("foot", "waist"), lambda s, r, p: jitter(s, r)))
    out.append(P("timing", "0.5 s gap mid-walk", ("foot", "waist"), lambda s, r, p: gap(s)))
    out.append(P("timing", "0.5 s gap mid-walk, test recordings only", ("waist",), lambda s, r, p: gap(s),
                 calibration=False))
    out.append(P("timing", "3 duplicated timestamps", ("foot", "waist"), lambda s, r, p: duplicates(s)))
    return out


def _rng(*keys: str) -> np.random.Generator:
    return np.random.default_rng(zlib.crc32("|".join(keys).encode()))


def _roundtrip(s: Session, folder: Path) -> Path:
    if folder.exists():
        shutil.rmtree(folder)
    write_session(s, folder)
    return folder


def _waist_imu_only(s: Session) -> Session:
    s.streams = {k: v for k, v in s.streams.items() if k in ("wAccelerometer", "wGyroscope")}
    return s


def _error(exc: Exception) -> str:
    return f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"


# -- evaluations ------------------------------------------------------------------------------------------
def foot_eval(folder: Path) -> dict:
    s = read_session(folder)
    sc = score_steps(get_detector("accel").detect(s), s)
    res = track_plasys(s, method="M3", model="oracle", steps="detector")
    ev = evaluate_track(res, s)
    return {"f1": sc["f1"], "tp": sc["true_positives"], "detected": sc["scored_count"],
            "reference": sc["reference_count"], "ground_truth": sc["ground_truth"],
            "n_strides": ev["n_steps"], "distance_m": ev["distance_m"],
            "dist_err_pct": ev.get("distance_error_pct", np.nan),
            "stride_mae_pct": ev.get("stride_length_mae_pct", np.nan),
            "warnings": "; ".join(res.info.get("warnings", []))}


def run_foot(perts: list[Perturbation], work: Path) -> pd.DataFrame:
    base = {p.name: read_session(p) for p in FOOT if p.exists()}
    rows = []
    for pert in perts:
        if "foot" not in pert.units:
            continue
        for name, s0 in base.items():
            row = {"unit": "foot", "category": pert.category, "perturbation": pert.name, "session": name}
            t0 = time.perf_counter()
            try:
                s = pert.fn(s0, _rng(pert.name, name), "foot")
                row.update(foot_eval(_roundtrip(s, work / "foot" / name)))
            except Exception as exc:  # noqa: BLE001  (the row records what the pipeline said)
                row["error"] = _error(exc)
            row["seconds"] = time.perf_counter() - t0
            rows.append(row)
        log.info("foot: %s done", pert.name)
    return pd.DataFrame(rows)


def run_waist(perts: list[Perturbation], work: Path) -> tuple[pd.DataFrame, pd.DataFrame]:
    runs = waist_exp.external_runs(EXTERNAL)
    names = sorted({n for cal, test in runs for n in (*cal, test)})
    # the magnetometer and barometer are not read by the waist pipelines: left out (faster round trip)
    base = {n: _waist_imu_only(read_session(EXTERNAL / n)) for n in names}
    runs_rows, pool_rows = [], []
    for pert in perts:
        if "waist" not in pert.units:
            continue
        t0 = time.perf_counter()
        folder = work / "waist"
        try:
            for n, s0 in base.items():
                _roundtrip(pert.fn(s0, _rng(pert.name, n), "waist"), folder / n)
            prun = runs
            if not pert.calibration:  # clean calibration walks, perturbed copies of the test recordings
                for n, s0 in base.items():
                    _roundtrip(s0, folder / n)
                    _roundtrip(pert.fn(s0, _rng(pert.name, n), "waist"), folder / f"{n}p")
                prun = [(cal, f"{test}p") for cal, test in runs]
            bouts: list = []
            df = waist_exp.real(folder, prun, configs=WAIST_CONFIG, bouts=bouts)
            df["test"] = df["test"].str.rstrip("p")
            df = df[df.params == "calibrated"]
            pool = waist_exp.pooled(df, pd.DataFrame(bouts)[lambda b: b.params == "calibrated"])
            for r in df.to_dict("records"):
                runs_rows.append({"unit": "waist", "category": pert.category, "perturbation": pert.name,
                                  "session": f"{r['subject']} {r['test']}", "f1": r["step_f1"], "tp": r["tp"],
                                  "detected": r["n_detected"], "reference": r["n_reference"],
                                  "dist_err_pct": r["dist_err_pct"], "bout_err_median_pct": r["bout_err_median_pct"],
                                  "stride_mae_m": r["stride_mae_m"]})
            for r in pool.to_dict("records"):
                pool_rows.append({"category": pert.category, "perturbation": pert.name, "test": r["test"],
                                  "step_f1": r["step_f1"], "bout_err_median_pct": r["bout_err_median_pct"],
                                  "bout_err_signed_median_pct": r["bout_err_signed_median_pct"],
                                  "stride_mae_m": r["stride_mae_m"], "ic_mean_ms": r["ic_mean_ms"]})
        except Exception as exc:  # noqa: BLE001
            runs_rows.append({"unit": "waist", "category": pert.category, "perturbation": pert.name,
                              "session": "all", "error": _error(exc)})
            pool_rows.append({"category": pert.category, "perturbation": pert.name, "test": "all",
                              "error": _error(exc)})
        log.info("waist: %s done in %.1f s", pert.name, time.perf_counter() - t0)
    return pd.DataFrame(runs_rows), pd.DataFrame(pool_rows)


# -- report -------------------------------------------------------------------------------------------
def _f(x, nd=2) -> str:
    return "" if x is None or (isinstance(x, float) and not np.isfinite(x)) else f"{x:.{nd}f}"


def foot_summary(df: pd.DataFrame) -> pd.DataFrame:
    base = df[df.category == "baseline"].set_index("session")
    rows = []
    for (cat, pert), g in df.groupby(["category", "perturbation"], sort=False):
        if "error" in g and g["error"].notna().any():
            errs = g["error"].dropna().unique()
            rows.append({"category": cat, "perturbation": pert, "error": errs[0]})
            continue
        g = g.set_index("session")
        lvl = [n for n in g.index if n.startswith("gaitmap_level")]
        rel = 100 * (g["distance_m"] / base.loc[g.index, "distance_m"] - 1)
        rows.append({"category": cat, "perturbation": pert,
                     "f1_pooled": 2 * g.tp.sum() / (g.detected.sum() + g.reference.sum()),
                     "f1_min": g.f1.min(), "f1_min_session": g.f1.idxmin(),
                     "level_stride_mae_pct": g.loc[lvl, "stride_mae_pct"].mean(),
                     "level_dist_err_pct": g.loc[lvl, "dist_err_pct"].abs().mean(),
                     "dist_vs_base_median_pct": rel.abs().median(), "dist_vs_base_max_pct": rel.abs().max(),
                     "dist_vs_base_max_session": rel.abs().idxmax()})
    return pd.DataFrame(rows)


def report(foot: pd.DataFrame, waist_runs: pd.DataFrame, waist_pool: pd.DataFrame, seconds: float,
           cpu_s: float = float("nan")) -> str:
    lines = ["# Robustness to unseen-recording differences", "",
             f"Generated by `experiments/robustness.py{' ' + ' '.join(sys.argv[1:]) if sys.argv[1:] else ''}` "
             f"in {seconds:.0f} s wall, {cpu_s:.0f} s CPU. Each perturbation alone; every session written and read back "
             "(`write_session` / `read_session`). See the module docstring for the protocol and "
             "docs/robustness.md for what the pipelines tolerate.", ""]
    if len(foot):
        fs = foot_summary(foot)
        lines += ["## Foot (gaitmap level L/R, walk4x10 L/R, lwalk, ms L/R)", "",
                  "f1 = `accel` detector strides vs steps.csv (pooled 2TP/(det+ref); min over sessions); "
                  "level MAE / dist = `track_plasys` M3 oracle on detector strides vs the mocap stride lengths "
                  "(mean over L/R; |distance error|); dist vs base = |tracked distance / unperturbed - 1| over "
                  "all 7 sessions (median, max).", "",
                  "| category | perturbation | F1 pooled | F1 min (session) | level stride MAE % | level |dist err| % | dist vs base median % | dist vs base max % (session) |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in fs.to_dict("records"):
            if isinstance(r.get("error"), str):
                lines.append(f"| {r['category']} | {r['perturbation']} | refused: {r['error']} | | | | | |")
                continue
            lines.append(f"| {r['category']} | {r['perturbation']} | {_f(r['f1_pooled'], 3)} | "
                         f"{_f(r['f1_min'], 3)} ({r['f1_min_session'].replace('gaitmap_', '')}) | "
                         f"{_f(r['level_stride_mae_pct'])} | {_f(r['level_dist_err_pct'])} | "
                         f"{_f(r['dist_vs_base_median_pct'])} | {_f(r['dist_vs_base_max_pct'])} "
                         f"({r['dist_vs_base_max_session'].replace('gaitmap_', '')}) |")
        lines.append("")
    if len(waist_pool):
        lines += ["## Lower back (mobgap HA001, HA002, MS001; waist-pendulum, per-user calibration)", "",
                  "The `experiments/waist.py` protocol on the perturbed recordings (7 runs: calibration walks "
                  "perturbed the same way -- same device and mounting -- unless the row says 'test recordings "
                  "only'); F1 pooled over subjects with `waist.pooled` (steps inside the reference bouts); "
                  "|dist err| = mean over the runs of |distance tracked in the reference bouts / their length "
                  "- 1|; bout err = median |per-bout error| pooled over the bouts (few bouts: it jumps from "
                  "bout to bout); max change = largest |dist err - unperturbed dist err| over the 7 runs (pp).",
                  "",
                  "| category | perturbation | Test5 F1 | Test5 mean |dist err| % | Test11 F1 | Test11 mean |dist err| % | Test11 median |bout err| % | max change pp (run) |",
                  "|---|---|---|---|---|---|---|---|"]
        base = waist_runs[waist_runs.category == "baseline"].set_index("session")["dist_err_pct"]
        for (cat, pert), g in waist_pool.groupby(["category", "perturbation"], sort=False):
            if "error" in g and g["error"].notna().any():
                lines.append(f"| {cat} | {pert} | refused: {g['error'].dropna().iloc[0]} | | | | | |")
                continue
            t5, t11 = g[g.test == "Test5"].iloc[0], g[g.test == "Test11"].iloc[0]
            r = waist_runs[waist_runs.perturbation == pert].set_index("session")
            kind = r.index.str.split(" ").str[1].str.split("_").str[0]
            d5 = r["dist_err_pct"][kind == "Test5"].abs().mean()
            d11 = r["dist_err_pct"][kind == "Test11"].abs().mean()
            ch = (r["dist_err_pct"] - base.loc[r.index]).abs()
            lines.append(f"| {cat} | {pert} | {_f(t5.step_f1, 3)} | {_f(d5, 1)} | {_f(t11.step_f1, 3)} | "
                         f"{_f(d11, 1)} | {_f(t11.bout_err_median_pct, 1)} | {_f(ch.max(), 1)} ({ch.idxmax()}) |")
        lines.append("")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=None, help="regex: run only the matching perturbations (+ baseline)")
    ap.add_argument("--unit", choices=("foot", "waist", "both"), default="both")
    ap.add_argument("--keep", type=Path, default=None, help="write the perturbed sessions here (kept)")
    ap.add_argument("--out", type=Path, default=OUT, help="results folder")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    for name in ("pdrlearn", "ahrs"):
        logging.getLogger(name).setLevel(logging.ERROR)
    if not any(EXTERNAL.glob("mobgap_*")) or not any(EXTERNAL.glob("gaitmap_*")):
        raise SystemExit(f"{EXTERNAL}: run `make external` first (mobgap_* and gaitmap_* sessions)")
    perts = _perturbations()
    if args.only:
        perts = [p for p in perts if p.category == "baseline" or re.search(args.only, p.name)]
    t0, c0 = time.perf_counter(), time.process_time()
    work = args.keep or Path(tempfile.mkdtemp(prefix="pdrlearn_robustness_"))
    try:
        foot = run_foot(perts, work) if args.unit in ("foot", "both") else pd.DataFrame()
        wruns, wpool = run_waist(perts, work) if args.unit in ("waist", "both") else (pd.DataFrame(),) * 2
    finally:
        if args.keep is None:
            shutil.rmtree(work, ignore_errors=True)
    seconds, cpu_s = time.perf_counter() - t0, time.process_time() - c0
    for df in (foot, wruns, wpool):  # error messages name the session folder, not the temporary root
        if "error" in df:
            df["error"] = df["error"].str.replace(str(work), "<work>", regex=False)
    args.out.mkdir(parents=True, exist_ok=True)
    allrows = pd.concat([foot, wruns, wpool.assign(unit="waist pooled", session=wpool.get("test"))],
                        ignore_index=True)
    allrows.to_csv(args.out / "robustness.csv", index=False, float_format="%.5g")
    text = report(foot, wruns, wpool, seconds, cpu_s)
    (args.out / "robustness.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
