"""Tracks at 10, 12.5 and 15 Hz: is a refusal under 15 Hz (decision B404) earned? (decision B416, review R0 finding 2).

B404 refused sessions sampled under 15 Hz on copies made by a trial's degrader that is not in the repository
(10 Hz: distance -99.7 %). Review R0 found anti-aliased 10 / 12.5 Hz copies tracking within ~2.5 %. Here the copies
are made two ways, both in this script: ``scipy.signal.decimate`` (FIR, zero phase; integer factor, so a 204.8 Hz
recording goes to 10.24 / 12.8 / 14.63 Hz) and pdrlearn's own resampler (``io.resample.resample_session``, the one
``--resample`` and the runtime use). Each copy is tracked by the pipeline ``track`` picks (``auto``) offline and
streamed (as ``track`` and ``track --streaming``) and scored by ``track_summary`` (step F1 against the labelled
strides; distance error against the simulated path, or the real recording's labelled stride lengths where it has
them).

Sessions: simulated users 10760-10769 on B404's route (stand:3, straight:40, turn:90, straight:20, stand:3 at 100 Hz,
not seen before), the 11 real foot recordings (gaitmap, /work/shared/data and datasets/external) and, for the waist,
the 9 mobgap recordings (waist track, streamed = ``--realtime``: step F1 against ics.csv; reported, not in the
rule).

Adoption rule (decision B416, docs/decisions/bad-input.md, written before the run): a copy fails when step F1 < 0.9 or
|distance error| > 10 % (B404's criterion); a real recording counts only where its native-rate track has F1 >= 0.9.
A tested rate is *unusable* when, for BOTH downsamplers and BOTH modes, 8 or more of the 10 simulated copies fail, or
8 or more of the counted real foot recordings fail in proportion (>= 80 %). The refusal floor is the lowest tested
rate that is not unusable, provided every tested rate below it is unusable; if 10 Hz is not unusable, nothing is
refused for its rate (B23's warning stays, for every command alike) and the floor is removed.

Usage::

    .venv/bin/python experiments/low_rate_track.py   # ~10 min; experiments/results/low_rate_track.md, .csv
"""

from __future__ import annotations

import logging
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.signal import decimate

from pdrlearn.io import read_session
from pdrlearn.io.resample import resample_session
from pdrlearn.io.session import Session, Stream
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "experiments" / "results"
RATES = (10.0, 12.5, 15.0)
USERS = range(10760, 10770)
ROUTE = "stand:3, straight:40, turn:90, straight:20, stand:3"  # decision B404's route
F1_MIN, DIST_MAX_PCT, UNUSABLE = 0.9, 10.0, 0.8  # B404's failure criterion; 8 of 10


def decimated(s: Session, rate: float) -> Session:
    """Every IMU stream decimated by the integer factor nearest to its rate / ``rate`` (scipy's FIR, zero phase)."""
    out = s.copy()
    for name, st in s.streams.items():
        q = int(round(st.rate_hz / rate))
        if q > 1 and len(st) > 30 * q:
            v = decimate(np.asarray(st.values, float), q, ftype="fir", axis=0, zero_phase=True)
            out.streams[name] = Stream(name, np.asarray(st.t)[::q][:len(v)], v[:len(st.t[::q])])
    return out


def resampled(s: Session, rate: float) -> Session:
    return resample_session(s, {n: rate for n in s.streams})


def sessions(tmp: Path) -> list[tuple[str, Path]]:
    from pdrlearn.cli import main

    out = []
    for u in USERS:
        d = tmp / f"sim_u{u}"
        main(["simulate", "--route", ROUTE, "--user-seed", str(u), "--rate", "100", "--out", str(d)])
        out.append(("sim", d))
    seen = set()
    for base in (Path("/work/shared/data"), ROOT / "datasets" / "external"):
        for d in sorted(base.glob("*")):
            if d.name in seen or not (d / "meta.json").exists():
                continue
            if d.name.startswith("gaitmap_") and (d / "steps.csv").exists():
                out.append(("real foot", d))
            elif d.name.startswith("mobgap_") and (d / "ics.csv").exists():
                out.append(("real waist", d))
            seen.add(d.name)
    return out


def score(s: Session, streaming: bool) -> tuple[float, float]:
    try:
        # as `track`: plasys (--streaming: its streamed kernel), or waist-pendulum alone (its causal --realtime)
        kw = {"streaming": streaming} if s.has("fAccelerometer", "fGyroscope") else {"realtime": streaming}
        r = get_pipeline("auto")(s, **kw)
        m = track_summary(r, s)
    except Exception as e:  # noqa: BLE001  (a track that fails is a failed copy, said in the table)
        print(f"  {s.name}: {type(e).__name__}: {e}", file=sys.stderr)
        return 0.0, float("nan")
    f1 = m.get("step_f1")
    return (float("nan") if f1 is None else f1), float(m.get("distance_error_pct") or float("nan"))


def run() -> pd.DataFrame:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for kind, d in sessions(Path(tmp)):
            s0 = read_session(d)
            for streaming in (False, True):
                f1, err = score(s0, streaming)
                rows.append({"kind": kind, "session": d.name, "how": "native", "rate_hz": None,
                             "streaming": streaming, "f1": f1, "distance_error_pct": err})
                for how, fn in (("decimate", decimated), ("resample", resampled)):
                    for rate in RATES:
                        s = fn(s0, rate)
                        f1, err = score(s, streaming)
                        got = min(st.rate_hz for st in s.streams.values() if len(st) > 1)
                        rows.append({"kind": kind, "session": d.name, "how": how, "rate_hz": rate,
                                     "actual_hz": round(got, 2), "streaming": streaming, "f1": f1,
                                     "distance_error_pct": err})
                        print(kind, d.name, how, rate, "streamed" if streaming else "offline",
                              f"F1 {f1:.3f} distance {err:+.2f} %", flush=True)
    return pd.DataFrame(rows)


def failed(df: pd.DataFrame) -> pd.Series:
    return (df.f1.fillna(0) < F1_MIN) | (df.distance_error_pct.abs() > DIST_MAX_PCT)


def verdict(df: pd.DataFrame) -> tuple[dict, float | None]:
    """B416's rule: each rate's failing shares per (kind, downsampler, mode); the refusal floor (None: no floor)."""
    native = df[df.how == "native"].set_index(["session", "streaming"]).f1
    counted = df.apply(lambda r: r.kind == "sim" or native.get((r.session, r.streaming), 0) >= F1_MIN, axis=1)
    d = df[counted & (df.how != "native")].assign(fail=lambda x: failed(x))
    shares = {}
    for rate in RATES:
        for kind in ("sim", "real foot", "real waist"):
            for (how, streaming), g in d[(d.rate_hz == rate) & (d.kind == kind)].groupby(["how", "streaming"]):
                shares[(rate, kind, how, streaming)] = (int(g.fail.sum()), len(g))
    unusable = {r: any(all(shares.get((r, k, h, m), (0, 1))[0] >= UNUSABLE * shares.get((r, k, h, m), (0, 1))[1]
                           for h in ("decimate", "resample") for m in (False, True))
                       for k in ("sim", "real foot")) for r in RATES}
    floor = next((r for i, r in enumerate(RATES) if not unusable[r] and all(unusable[q] for q in RATES[:i])), None)
    return shares, (None if floor == RATES[0] else floor)


def main() -> None:
    logging.disable(logging.WARNING)
    warnings.simplefilter("ignore")
    df = run()
    OUT.mkdir(parents=True, exist_ok=True)
    df.to_csv(OUT / "low_rate_track.csv", index=False)
    shares, floor = verdict(df)
    lines = ["# Tracks at low sampling rates (decision B416)", "",
             "Generated by `experiments/low_rate_track.py`. Failing copies (step F1 < 0.9 or |distance error| > 10 %) "
             "per rate, kind, downsampler and mode; real recordings counted where their native track has F1 >= 0.9.",
             "", "| rate | kind | downsampler | mode | failing | F1 range | distance error range (%) |",
             "|---|---|---|---|---|---|---|"]
    for (rate, kind, how, streaming), (n, total) in shares.items():
        g = df[(df.rate_hz == rate) & (df.kind == kind) & (df.how == how) & (df.streaming == streaming)]
        e = g.distance_error_pct.dropna()
        er = f"{e.min():+.2f} to {e.max():+.2f}" if len(e) else "-"
        lines.append(f"| {rate:g} Hz | {kind} | {how} | {'streamed' if streaming else 'offline'} | {n} of {total} | "
                     f"{g.f1.min():.3f}-{g.f1.max():.3f} | {er} |")
    lines += ["", "Native rate: " + ", ".join(
        f"{k} F1 {g.f1.min():.3f}-{g.f1.max():.3f}" for k, g in df[df.how == "native"].groupby("kind")), "",
        f"Refusal floor by the rule: **{'none' if floor is None else f'{floor:g} Hz'}**.", ""]
    (OUT / "low_rate_track.md").write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
