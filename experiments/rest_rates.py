"""Real gaitmap foot terrain, 10-fold CV, given vs rest step boundaries at the native and block-averaged rates.

The four gaitmap foot sessions of ``datasets/real`` (94 strides with a terrain class), foot unit, methods
dtw / svm / nn / ensemble (decision C14), seeds 0-2. ``--blocks k`` averages blocks of k samples first
(k=10: 204.8 -> 20.48 Hz, the PLASYS firmware's averaging, thesis ch. 4.2.3; k=4: 51.2 Hz). Prints one
line per boundary mode; the numbers of decision C15 (docs/decisions/classifiers.md).

    .venv/bin/python experiments/rest_rates.py --blocks 1 4 10
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

from pdrlearn.classify import train_user
from pdrlearn.io import Stream, read_session
from pdrlearn.sim.kernels import block_mean

ROOT = Path(__file__).resolve().parents[1]
NAMES = ("level_left", "level_right", "stairs_up_left", "stairs_down_left")
METHODS = ("dtw", "svm", "nn", "ensemble")


def sessions_at(k: int) -> list:
    out = []
    for n in NAMES:
        s = read_session(ROOT / "datasets" / "real" / f"gaitmap_{n}")
        if k > 1:
            for name, st in list(s.streams.items()):
                s.streams[name] = Stream(name, block_mean(st.t, k), block_mean(st.values, k))
        out.append(s)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--blocks", type=int, nargs="+", default=[1, 4, 10], help="block-average sizes (1 = native)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    args = ap.parse_args(argv)
    warnings.filterwarnings("ignore")
    for k in args.blocks:
        sessions = sessions_at(k)
        rate = 1.0 / float(np.median(np.diff(sessions[0].streams["fGyroscope"].t)))
        for b in ("given", "rest"):
            acc: dict[str, list[float]] = {m: [] for m in METHODS}
            for seed in args.seeds:
                m = train_user(sessions, tasks=["terrain"], methods=list(METHODS), units=["foot"], cv=10,
                               seed=seed, boundaries=b)
                for meth in METHODS:
                    acc[meth].append(100 * m.tasks["terrain"].cv[meth]["foot"]["accuracy"])
            print(f"{rate:6.2f} Hz {b:5s} " + "  ".join(
                f"{meth} {'/'.join(f'{a:.1f}' for a in v)} (mean {np.mean(v):.1f})" for meth, v in acc.items()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
