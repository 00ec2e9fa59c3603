"""Decisions L509/L512's adoption rule (docs/decisions/localization.md): each foot stride's ``speed_mps`` against the
simulator's steps.csv (the stride whose start..end holds the tracked ``event_s``; truth ``length_m / (end - start)``)
with the old speed (``|length_m| / stride_time_s``, IC to IC) and the code's (L512: a stride after a rest over the
shorter of its own and the next stride's IC-to-IC; L509's first version measured 10000-10009), on fresh simulated
users from ``--first-user`` (10010 for L512): stop-and-go routes and continuous walks."""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.track.base import get_pipeline, resolve_pipeline  # noqa: E402
from pdrlearn.track.clinical import TOUCH_S  # noqa: E402
from pdrlearn.track.gait import resumed_times, stride_rows  # noqa: E402

logging.disable(logging.WARNING)
STOP_GO = ("stand:2, straight:4, stand:1, backward:3, stand:0.5, straight:4, stand:2, side:3, stand:1.5, straight:3, "
           "stand:2", "stand:2, straight:4:fast, stand:0.5, backward:4, stand:2.5, straight:6:fast, stand:1, "
           "side:-2, stand:0.8, straight:3:fast, stand:2")
CONTINUOUS = "stand:3, straight:20, stand:3"


def cases(first: int) -> list[tuple]:
    return ([(first + k, "stop-go", STOP_GO[k % 2], []) for k in range(6)]
            + [(first + 6, "slow", CONTINUOUS, ["--speed", "slow"]), (first + 7, "normal", CONTINUOUS, []),
               (first + 8, "fast", CONTINUOUS, ["--speed", "fast"]),
               (first + 9, "very slow", CONTINUOUS, ["--step-length", "0.25", "--step-time", "1.5"])])


def speeds(folder: Path) -> pd.DataFrame:
    """Per tracked stride: truth speed, old speed, L509 speed, whether it follows a rest."""
    session = read_session(folder)
    st = get_pipeline(resolve_pipeline("auto", session))(session).steps
    valid = stride_rows(st)
    s0, s1, stride = (st[c].to_numpy(float) for c in ("start_s", "end_s", "stride_time_s"))
    length = np.abs(st["length_m"].to_numpy(float))
    idx = np.flatnonzero(valid)
    after = np.zeros(len(st), bool)
    after[idx] = np.r_[True, s0[idx[1:]] > s1[idx[:-1]] + TOUCH_S] if len(idx) else []
    gt = pd.read_csv(folder / "steps.csv")
    a, b = gt["start_ms"].to_numpy(float) / 1000, gt["end_ms"].to_numpy(float) / 1000
    truth = np.full(len(st), np.nan)
    for i, ev in enumerate(st["event_s"].to_numpy(float)):
        k = np.flatnonzero((a <= ev) & (b >= ev))
        if len(k):
            truth[i] = gt["length_m"].iloc[k[0]] / (b[k[0]] - a[k[0]])
    with np.errstate(invalid="ignore", divide="ignore"):
        return pd.DataFrame({"truth": truth, "old": length / stride,
                             "new": length / resumed_times(s0, s1, stride, valid), "after": after & valid})


def err(v: pd.Series, truth: pd.Series) -> tuple[int, float]:
    e = (100 * np.abs(v / truth - 1)).dropna()
    return len(e), float(np.median(e)) if len(e) else float("nan")


def main() -> None:
    frames = {}
    with tempfile.TemporaryDirectory() as tmp:
        first = int(sys.argv[sys.argv.index("--first-user") + 1]) if "--first-user" in sys.argv else 10000
        for user, label, route, extra in cases(first):
            out = Path(tmp) / f"u{user}"
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(user),
                            "--out", str(out), *extra], check=True, capture_output=True)
            d = speeds(out)
            frames.setdefault(label, []).append(d)
            r, o = d[d["after"]], d[~d["after"]]
            same = bool(np.array_equal(o["old"].to_numpy(), o["new"].to_numpy(), equal_nan=True))
            print(f"u{user} {label}: after a rest old {err(r['old'], r['truth'])} new {err(r['new'], r['truth'])} "
                  f"(n, median |err| %); others identical {same}; all strides old {err(d['old'], d['truth'])} "
                  f"new {err(d['new'], d['truth'])}", flush=True)
    d = pd.concat(frames.pop("stop-go"))
    r = d[d["after"]]
    print(f"stop-go strides after a rest: old {err(r['old'], r['truth'])} new {err(r['new'], r['truth'])}")
    for label, fs in frames.items():
        d = pd.concat(fs)
        print(f"continuous {label}: all strides old {err(d['old'], d['truth'])} new {err(d['new'], d['truth'])}")


if __name__ == "__main__":
    sys.exit(main())
