"""Decision W106's rule (docs/decisions/waist.md): the offline waist IC detector's sequence rules on sub-sample
times of the vertical maxima, before (whole samples) and after, on (a) the nine real mobgap lower-back recordings
at 100 Hz, (b) their 2x decimations (50 Hz) and (c) simulated users 860-879, scenario B, at 25 / 50 / 100 Hz.

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_rate_w106.py --w107

"before" = every rule on whole samples (``peak_positions`` patched to the samples); "after" = this code: W107, the
sub-sample times in W20's pruning only. W106's candidate (every rule on sub-sample times, not adopted) is commit
851ab10 of branch waistrate; run this script there for its numbers.
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.kernels import waist as K
from pdrlearn.sim import simulate
from pdrlearn.track import get_pipeline

EXT = Path(__file__).resolve().parents[1] / "datasets" / "external"
REAL = [f"mobgap_{s}_Test5_Trial{k}" for s in ("HA001", "HA002", "MS001") for k in (1, 2)] + \
       [f"mobgap_{s}_Test11_Trial1" for s in ("HA001", "HA002", "MS001")]
USERS = range(860, 880)
SIM_RATES = (25.0, 50.0, 100.0)


@contextlib.contextmanager
def whole_samples():
    """The detector as before W106: the rules time each maximum at its sample."""
    keep = K.peak_positions
    K.peak_positions = lambda x, idx: np.asarray(idx, dtype=np.float64)
    try:
        yield
    finally:
        K.peak_positions = keep


def decimated(session, k: int = 2):
    """Every k-th sample of the waist's inertial streams (the phone trial's clean decimation)."""
    streams = dict(session.streams)
    for name in ("wAccelerometer", "wGyroscope", "wMagneticField"):
        if name in streams:
            s = streams[name]
            streams[name] = Stream(s.name, s.t[::k].copy(), s.values[::k].copy())
    meta = dict(session.meta)
    if "rate_hz" in meta:
        meta["rate_hz"] = float(meta["rate_hz"]) / k
    return dataclasses.replace(session, streams=streams, meta=meta)


def run(session) -> tuple[int, float, float, float, float]:
    r = get_pipeline("waist-pendulum")(session)
    s = r.summary(session)
    fp = s["final_position"]
    return int(s["n_steps"]), float(s["distance_m"]), float(s.get("step_f1") or np.nan), fp["x"], fp["y"]


def main() -> None:
    logging.disable(logging.WARNING)
    print("after = W107 (W20 pruning on sub-sample times)" if "--w107" in sys.argv else
          "after = this code (W107); W106's candidate is commit 851ab10")
    res: dict[str, dict] = {"before": {}, "after": {}}
    real = {n: read_session(EXT / n) for n in REAL}
    sims = {(u, fs): simulate("B", u, "normal", rate_hz=fs) for u in USERS for fs in SIM_RATES}
    for label in ("before", "after"):
        ctx = whole_samples() if label == "before" else contextlib.nullcontext()
        with ctx:
            for n, s in real.items():
                res[label][(n, 100)] = run(s)
                res[label][(n, 50)] = run(decimated(s))
            for key, s in sims.items():
                res[label][key] = run(s)
    print("(a)+(b) real: steps / distance m / step_f1 / final (x, y) at 100 Hz and 50 Hz, before -> after")
    for label in ("before", "after"):
        tot = 0
        for n in REAL:
            a, b = res[label][(n, 100)], res[label][(n, 50)]
            tot += abs(a[0] - b[0])
            print(f"  {label:6s} {n:26s} 100 Hz {a[0]:3d} {a[1]:7.3f} {a[2]:.3f} ({a[3]:6.2f},{a[4]:6.2f})"
                  f" | 50 Hz {b[0]:3d} {b[1]:7.3f} {b[2]:.3f} ({b[3]:6.2f},{b[4]:6.2f})")
        print(f"  {label}: sum |steps 50 - steps 100| = {tot}")
    worst_f1 = max(abs(res["after"][(n, 100)][2] - res["before"][(n, 100)][2]) for n in REAL)
    worst_d = max(abs(res["after"][(n, 100)][1] / res["before"][(n, 100)][1] - 1) * 100 for n in REAL)
    print(f"(a) 100 Hz: largest |step_f1 change| {worst_f1:.4f}, largest |distance change| {worst_d:.3f} %")
    print("(c) simulated users 860-879, scenario B normal: steps at 25/50/100 Hz")
    for label in ("before", "after"):
        spread = sum(max(res[label][(u, f)][0] for f in SIM_RATES) - min(res[label][(u, f)][0] for f in SIM_RATES)
                     for u in USERS)
        f1 = [np.nanmean([res[label][(u, f)][2] for u in USERS]) for f in SIM_RATES]
        print(f"  {label}: sum over users of (max - min) steps = {spread}; mean step_f1 "
              + " / ".join(f"{x:.4f}" for x in f1))
        print("   " + " ".join("{}:{}".format(u, "/".join(str(res[label][(u, f)][0]) for f in SIM_RATES))
                              for u in USERS))


if __name__ == "__main__":
    main()
