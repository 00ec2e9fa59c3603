"""Decision L223 (docs/decisions/localization.md; amends D23, docs/decisions/aided.md): how much evidence D23's
refusal of a reversed foot frame rests on - the strides (> 0.2 m) and the mean resultant of their directions that
the frame check (:func:`pdrlearn.track.frame_inference.check_declared_frame`, first 300 s) measured - on fresh
simulated users (normal, slow and crawl walks) and the real foot recordings. Per session: n strides, resultant,
whether the RIGHT frame (the simulator's) is refused (a false refusal) and whether the frame turned 180 deg about
up (forward reversed: what D23 is for) is refused.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/frame_check_evidence.py [--users 4110-4119]``
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.errors import DataError  # noqa: E402
from pdrlearn.io.plasys import read_session  # noqa: E402
from pdrlearn.track.frame_inference import CHECK_SPAN_S, _turned, check_declared_frame, infer_session_frame  # noqa: E402,I001

#: the first part of the navigation trial's R1 (session 28): level, turns, stairs
ROUTE = "stand:5, straight:20, turn:90, straight:15, up:17, turn:180, up:17, straight:10, turn:-90, straight:25"
#: step length (m) / step time (s): the simulator's own gait, the trial's 70 and 60 steps/min walks, its 40 steps/min
#: crawl (finding 5), and a 50 steps/min walk between them
GAITS = (None, ("0.35", "0.85"), ("0.3", "1.0"), ("0.3", "1.2"), ("0.25", "1.5"))


def evidence(folder: Path) -> str:
    s = read_session(folder)
    frame = s.frames.get("foot")
    if frame is None:
        return "no declared foot frame"
    try:
        f = infer_session_frame(s, "foot", max_s=CHECK_SPAN_S)
        n, r = f.n_strides, f.resultant
    except DataError as exc:
        n, r = getattr(exc, "n_strides", None), getattr(exc, "resultant", None)
    right = check_declared_frame(s, "foot", frame).refuse
    rev = check_declared_frame(s, "foot", _turned(frame, {"forward", "left"})).refuse
    return (f"strides {n}, resultant {r if r is None else round(r, 2)}, right frame refused {right}, "
            f"reversed refused {rev}")


def sim(out: Path, user: int, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--user-seed", str(user), "--out", str(out), *args],
                   check=True, capture_output=True, env=env)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="4110-4119")
    a, b = (int(x) for x in ap.parse_args().users.split("-"))
    tmp = Path(tempfile.mkdtemp(prefix="l223_"))
    for u in range(a, b + 1):
        for sc in "ABCD":
            d = tmp / f"{sc}_{u}"
            sim(d, u, "--scenario", sc)
            print(f"u{u} scenario {sc}: {evidence(d)}", flush=True)
        for g in GAITS:
            d = tmp / f"r_{u}_{'default' if g is None else '_'.join(g)}"
            sim(d, u, "--route", ROUTE, *(() if g is None else ("--step-length", g[0], "--step-time", g[1])))
            spm = "default" if g is None else f"{g[0]} m / {g[1]} s ({120 / float(g[1]) / 2:.0f} steps/min)"
            print(f"u{u} route {spm}: {evidence(d)}", flush=True)
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(p for p in base.iterdir() if p.is_dir() and p.name.startswith("gaitmap")):
            print(f"{d.name}: {evidence(d)}", flush=True)


if __name__ == "__main__":
    main()
