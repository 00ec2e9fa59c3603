"""Decision L500's adoption rule (docs/decisions/localization.md): the foot track's walking bouts and pauses with
L104's median alone, with L482's stride-window bound, and with L500's (movements, bound only when the intervals are
mostly stands), on fresh simulated users 9800-9817 (L482's stop-and-go routes and slow continuous walks at
0.15-0.4 m/s) and the real recordings of datasets/real (a check, not tuned on)."""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from experiments.stopgo_pauses_l482 import ONE_STEP, SG1  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.track import clinical  # noqa: E402
from pdrlearn.track.base import get_pipeline, resolve_pipeline  # noqa: E402
from pdrlearn.track.evaluate import track_summary  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
logging.disable(logging.WARNING)  # the slow walks' L95 speed lines
SLOW_ROUTE = "stand:3, straight:10, stand:3"
#: (speed label, step length m, step time s): 0.15-0.4 m/s
SPEEDS = [("0.15", "0.24", "1.6"), ("0.18", "0.25", "1.4"), ("0.20", "0.25", "1.25"), ("0.30", "0.3", "1.0"),
          ("0.40", "0.3", "0.75")]
CASES = ([(u, "sg1", SG1, [], (8, 7)) for u in range(9800, 9804)]
         + [(u, "one-step", ONE_STEP, [], (6, 5)) for u in range(9804, 9808)]
         + [(9808 + 2 * i + k, f"{v} m/s", SLOW_ROUTE, ["--step-length", sl, "--step-time", stt], None)
            for i, (v, sl, stt) in enumerate(SPEEDS) for k in range(2)])
#: (label, STRIDE_WINDOW_RHYTHM, RHYTHM_MOVEMENTS)
RULES = (("L104", False, False), ("L482", True, False), ("L500", True, True))


def counts(session) -> list[tuple]:
    result = get_pipeline(resolve_pipeline("auto", session))(session)
    out = []
    for _, a, b in RULES:
        clinical.STRIDE_WINDOW_RHYTHM, clinical.RHYTHM_MOVEMENTS = a, b
        s = track_summary(result, session)
        out.append((s["n_walking_bouts"], s["n_pauses"], round(s["pause_time_s"], 2), round(s["walking_time_s"], 2)))
    clinical.STRIDE_WINDOW_RHYTHM = clinical.RHYTHM_MOVEMENTS = True
    return out


def line(name: str, c: list[tuple]) -> str:
    return name + ": " + "; ".join(f"{r[0]} {b} bouts, {p} pauses ({t} s), walking {w} s"
                                   for r, (b, p, t, w) in zip(RULES, c, strict=True))


def main() -> None:
    right, more = 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        for user, label, route, extra, truth in CASES:
            out = Path(tmp) / f"u{user}"
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(user),
                            "--rate", "100", "--out", str(out), *extra], check=True, capture_output=True)
            c = counts(read_session(out))
            note = ""
            if truth:
                hit = c[2][:2] == truth
                right += hit
                note = f" (truth {truth[0]} / {truth[1]}: L500 {'right' if hit else 'WRONG'})"
            else:
                more += c[2][1] > c[0][1]
                note = f" (L500 pauses beyond L104's: {max(c[2][1] - c[0][1], 0)})"
            print(line(f"u{user} {label}", c) + note, flush=True)
    print(f"stop-and-go users right under L500: {right} of 8; slow walks with more pauses than L104: {more} of 10",
          flush=True)
    for p in sorted((ROOT / "datasets/real").iterdir()):
        if p.is_dir():
            print(line(p.name, counts(read_session(p))), flush=True)


if __name__ == "__main__":
    sys.exit(main())
