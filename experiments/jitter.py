"""Decision B33: sampling jitter on the real foot recordings.

Every gaitmap foot recording (datasets/real, datasets/external) is resampled (linear interpolation of the native
stream) to a clean 100 Hz copy (t = 10 ms * i) and to copies sampled at jittered true times (t = 10 ms * i +
U(-4, 4) ms, seeds 0 and 1: a phone's sensor events). `pdrlearn track` (plasys, no model) runs on each, with the
jittered accelerometer/gyroscope on their own clock (default) and, with ``--uniform``, interpolated onto a uniform
clock (``read_session(uniform_clock=True)``). Printed: stride-length MAE % against the motion-capture strides
(level walks) and (distance m, strides).

    PYTHONPATH=. python experiments/jitter.py [--uniform] [--only level] [--out /tmp/jitter]
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
# ``--uniform``: every session read puts its jittered streams on a uniform clock, as read_session(uniform_clock=True)
# (B33's option) does, also where the CLI reads with the default (decision E251: a stand-in, no module switch)
RUN = ("import sys; import pdrlearn.io.plasys as P; on = sys.argv.pop(1) == '1'; warn = P._warn_jitter; "
       "P._warn_jitter = (lambda s, f: (warn(s, f), P._uniform_clocks(s, f))) if on else warn; "
       "from pdrlearn.cli import run; sys.argv[0] = 'pdrlearn'; sys.exit(run())")


def sources() -> list[Path]:
    seen, out = set(), []
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(base.glob("gaitmap_*")):
            if d.name not in seen and (d / "fAccelerometer.csv").exists():
                seen.add(d.name)
                out.append(d)
    return out


def make(src: Path, out: Path, jitter_ms: float, seed: int) -> Path:
    d = out / f"{src.name}__{'jit' if jitter_ms else 'clean'}{seed}"
    if d.exists():
        return d
    d.mkdir(parents=True)
    acc, gyr = (pd.read_csv(src / f"{n}.csv") for n in ("fAccelerometer", "fGyroscope"))
    t0 = max(acc.timestamp.iloc[0], gyr.timestamp.iloc[0])
    t1 = min(acc.timestamp.iloc[-1], gyr.timestamp.iloc[-1])
    grid = np.arange(t0 + 10, t1 - 10, 10.0)
    t = grid + np.random.default_rng(seed).uniform(-jitter_ms, jitter_ms, grid.size) if jitter_ms else grid
    for name, df in (("fAccelerometer", acc), ("fGyroscope", gyr)):
        tab = pd.DataFrame({"timestamp": t})
        for c in "xyz":
            tab[c] = np.interp(t, df.timestamp, df[c])
        tab.to_csv(d / f"{name}.csv", index=False, float_format="%.10g")
    shutil.copy(src / "steps.csv", d / "steps.csv")
    meta = json.loads((src / "meta.json").read_text())
    meta["rate_hz"] = 100.0
    meta["units"]["timestamp"] = "ms"
    (d / "meta.json").write_text(json.dumps(meta))
    return d


def track(d: Path, out: Path, uniform: bool) -> tuple[str, float | None, tuple]:
    res = out / ("uniform" if uniform else "own") / d.name
    r = subprocess.run([sys.executable, "-c", RUN, "1" if uniform else "0", "track", str(d), "--out", str(res),
                        "--force", "--json"], capture_output=True, text=True)
    s = json.loads(r.stdout)
    return d.name, s.get("stride_length_mae_pct"), (round(s["distance_m"], 3), s["n_steps"])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--uniform", action="store_true")
    ap.add_argument("--out", type=Path, default=Path("/tmp/pdrlearn_jitter"))
    ap.add_argument("--only", default="", help="recordings whose name contains this text")
    a = ap.parse_args()
    dirs = [make(s, a.out / "data", j, seed) for s in sources() if a.only in s.name
            for j, seed in ((0, 0), (4.0, 0), (4.0, 1))]
    with ThreadPoolExecutor(2) as ex:
        for name, mae, dist in ex.map(lambda d: track(d, a.out, a.uniform), dirs):
            print(f"{name:45s} {'-' if mae is None else round(mae, 3)} {dist}", flush=True)


if __name__ == "__main__":
    main()
