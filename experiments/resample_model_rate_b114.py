"""Decision B114: is ``--resample`` (B113) a better default for ``track --model`` / ``evaluate`` on a session
recorded at another rate than the model's? The rule is in docs/decisions/bad-input.md (B114), committed before
this script was run.

Simulated: fresh users 420-439, scenario D at 50 and 100 Hz, the 20 Hz ``make demo`` model (out/models/u1 of the
main checkout, or ``--model``). Real (reported only): the 204.8 Hz gaitmap foot recordings not used for
training, at 102.4 and 409.6 Hz (``scipy.signal.resample_poly``), with the terrain model trained on the three
204.8 Hz left-foot recordings of datasets/real (as ``experiments/real_sweep.py``).

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/resample_model_rate_b114.py --work /tmp/b114 \
        [--model out/models/u1] [--part sim|real|both]

Prints the tables; writes experiments/results/resample_model_rate_b114.md.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
USERS = range(420, 440)
RATES = (50, 100)
TRAIN_REAL = ["gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]


def cli(*args: str) -> dict | None:
    """``python -m pdrlearn ARGS --json`` -> its JSON (None when it failed)."""
    p = subprocess.run([sys.executable, "-m", "pdrlearn", *args, "--json"], capture_output=True, text=True,
                       cwd=ROOT)
    if p.returncode != 0:
        print("FAILED:", " ".join(args), p.stderr.strip().splitlines()[-1:], file=sys.stderr)
        return None
    return json.loads(p.stdout)


def compare(sessions: list[Path], model: Path, work: Path, tag: str) -> dict:
    """Per mode (native / resampled): evaluate accuracy per task over ``sessions`` and each session's distance
    error from ``track --model``."""
    out = {}
    for mode, extra in (("native", []), ("resample", ["--resample"])):
        ev = cli("evaluate", str(model), *map(str, sessions), *extra)
        acc = {t: r["accuracy"] for t, r in (ev or {}).get("tasks", {}).items()}
        errs = []
        for s in sessions:
            tr = cli("track", str(s), "--model", str(model), "--out", str(work / f"trk_{tag}_{mode}_{s.name}"),
                     "--force", *extra)
            if tr is not None and tr.get("distance_error_pct") is not None:
                errs.append(float(tr["distance_error_pct"]))
        out[mode] = {"accuracy": acc, "distance_errors": errs,
                     "median_abs_dist_pct": float(np.median(np.abs(errs))) if errs else math.nan}
    return out


def simulated(work: Path, model: Path) -> dict:
    res = {}
    for rate in RATES:
        sessions = []
        for u in USERS:
            d = work / f"D_u{u}_{rate}"
            if not (d / "meta.json").exists():
                subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--scenario", "D", "--user-seed",
                                str(u), "--rate", str(rate), "--out", str(d), "--json"], check=True,
                               capture_output=True, cwd=ROOT)
            sessions.append(d)
        res[rate] = compare(sessions, model, work, f"sim{rate}")
    return res


def real_copies(work: Path) -> dict[float, list[Path]]:
    """The held-out 204.8 Hz gaitmap foot recordings at 102.4 and 409.6 Hz (resample_poly 1:2 and 2:1)."""
    from scipy.signal import resample_poly

    from pdrlearn.io import Session, Stream, read_session, write_session

    src = [ROOT / "datasets" / "real" / "gaitmap_level_right"]
    src += sorted(p for p in (ROOT / "datasets" / "external").glob("gaitmap_*") if (p / "meta.json").exists())
    out: dict[float, list[Path]] = {102.4: [], 409.6: []}
    for p in src:
        s = read_session(p)
        fs = s.streams["fAccelerometer"].rate_hz
        if abs(fs - 204.8) > 0.01 * 204.8:
            continue
        for rate, (up, down) in ((102.4, (1, 2)), (409.6, (2, 1))):
            d = work / f"{p.name}_{rate:g}"
            if not (d / "meta.json").exists():
                streams = {}
                for n, st in s.streams.items():
                    v = resample_poly(st.values, up, down, axis=0)
                    streams[n] = Stream(n, st.t[0] + np.arange(len(v)) / rate, v)
                meta = {**s.meta, "rate_hz": rate}
                write_session(Session(name=s.name, streams=streams, steps=s.steps, trajectory=s.trajectory,
                                      extras=s.extras, meta=meta, frames=s.frames), d)
            out[rate].append(d)
    return out


def real(work: Path) -> dict:
    model = work / "rmodel"
    if not (model / "manifest.json").exists():
        subprocess.run([sys.executable, "-m", "pdrlearn", "train", *[str(ROOT / "datasets" / "real" / n)
                                                                     for n in TRAIN_REAL],
                        "--tasks", "terrain", "--cv", "5", "--out", str(model), "--json"], check=True,
                       capture_output=True, cwd=ROOT)
    return {rate: compare(sessions, model, work, f"real{rate:g}") for rate, sessions in real_copies(work).items()}


def table(res: dict, label: str) -> list[str]:
    lines = [f"| {label} | mode | accuracy per task (%) | median abs distance error (%) | sessions tracked |",
             "|---|---|---|---|---|"]
    for rate, r in res.items():
        for mode in ("native", "resample"):
            m = r[mode]
            acc = ", ".join(f"{t} {100 * a:.1f}" for t, a in m["accuracy"].items())
            lines.append(f"| {rate:g} Hz | {mode} | {acc} | {m['median_abs_dist_pct']:.2f} | "
                         f"{len(m['distance_errors'])} |")
    return lines


def verdict(res: dict) -> str:
    ok = True
    for rate, r in res.items():
        n, s = r["native"], r["resample"]
        gain = {t: 100 * (s["accuracy"].get(t, math.nan) - a) for t, a in n["accuracy"].items()}
        dd = s["median_abs_dist_pct"] - n["median_abs_dist_pct"]
        a_ok = bool(gain) and all(g >= 2.0 for g in gain.values())
        d_ok = dd <= 0.5
        print(f"{rate} Hz: accuracy gain (pp) {', '.join(f'{t} {g:+.1f}' for t, g in gain.items())} -> "
              f"{'met' if a_ok else 'not met'}; median |dist| change {dd:+.2f} pp -> {'met' if d_ok else 'not met'}")
        ok = ok and a_ok and d_ok
    return "ADOPTED" if ok else "NOT ADOPTED"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", type=Path, required=True)
    ap.add_argument("--model", type=Path, default=Path("/work/main/out/models/u1"))
    ap.add_argument("--part", choices=("sim", "real", "both"), default="both")
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    lines = ["# B114: --resample as the default of track --model / evaluate (rule: docs/decisions/bad-input.md)", ""]
    if a.part in ("sim", "both"):
        res = simulated(a.work, a.model)
        lines += ["Simulated, scenario D, users 420-439, 20 Hz model:", "", *table(res, "session rate"), ""]
        v = verdict(res)
        lines += [f"Rule (B114): {v}", ""]
        (a.work / "sim.json").write_text(json.dumps(res, indent=1, default=str))
    if a.part in ("real", "both"):
        res = real(a.work)
        lines += ["Real gaitmap foot recordings (held out), 204.8 Hz terrain model (reported, not in the rule):", "",
                  *table(res, "copy rate"), ""]
        (a.work / "real.json").write_text(json.dumps(res, indent=1, default=str))
    print("\n".join(lines))
    out = ROOT / "experiments" / "results" / "resample_model_rate_b114.md"
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
