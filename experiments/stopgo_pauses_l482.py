"""Decision L482's cases (docs/decisions/localization.md): the foot track's walking bouts and pauses with the rhythm
bounded by the rows' own stride windows, on simulated users 9540-9555 (stop-and-go routes with known walks / stands,
and continuous walks at normal gait and 0.4 m/s) and the real recordings of datasets/real (a check, not tuned on).

L482 was adopted and L500 refined it (L501); W413 removed their module switches, so this prints the rule as it is.
L482's measurement against L104's median alone ran with ``clinical.STRIDE_WINDOW_RHYTHM``, which commit d3ffb129
holds (``git show d3ffb129:experiments/stopgo_pauses_l482.py``)."""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline, resolve_pipeline
from pdrlearn.track.evaluate import track_summary

ROOT = Path(__file__).resolve().parents[1]
#: the trial's sg1 route (T2 finding 1): 8 walks, 7 stands
SG1 = ("stand:3, straight:0.7, stand:2, straight:1.4, stand:2, straight:0.7, stand:2, straight:2.1, stand:2, "
       "backward:1, stand:2, straight:0.7, stand:2, backward:1, stand:2, straight:1.4, stand:3")
#: six 1-step walks: 6 walks, 5 stands between them
ONE_STEP = "stand:2, " + ", ".join(["straight:0.35, stand:2"] * 6)
#: L104's measured route (continuous walking with 2 stands of 3 s and turns)
L104 = ("stand:2, straight:8, stand:3, straight:8, turn:180, straight:8, turn:90, straight:6, turn:-45, straight:6, "
        "stand:3, straight:6, curve:90:8, straight:3, stand:2")
SLOW = ["--step-length", "0.3", "--step-time", "0.75"]
CASES = ([(u, "sg1", SG1, [], (8, 7)) for u in range(9540, 9544)]
         + [(u, "one-step", ONE_STEP, [], (6, 5)) for u in range(9544, 9548)]
         + [(u, "L104 normal", L104, [], None) for u in range(9548, 9552)]
         + [(u, "L104 0.4 m/s", L104, SLOW, None) for u in range(9552, 9556)])
KEYS = ("n_walking_bouts", "n_pauses", "pause_time_s", "walking_time_s")


def counts(session) -> dict:
    """The session tracked (pipeline auto) and its summary's :data:`KEYS`."""
    s = track_summary(get_pipeline(resolve_pipeline("auto", session))(session), session)
    return {k: s.get(k) for k in KEYS}


def line(name: str, new: dict) -> str:
    return name + ": " + ", ".join(f"{k} {new[k]:.2f}" if isinstance(new[k], float) else f"{k} {new[k]}" for k in KEYS)


def run_cases(cases) -> tuple[int, int]:
    """Each (user, label, route, extra simulate options, truth (bouts, pauses) or None) of ``cases`` simulated at
    100 Hz and counted, one printed line each: (cases with a truth counted right, cases without one with a pause)."""
    right, paused = 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        for user, label, route, extra, truth in cases:
            out = Path(tmp) / f"u{user}"
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(user),
                            "--rate", "100", "--out", str(out), *extra], check=True, capture_output=True)
            new = counts(read_session(out))
            ok = ""
            if truth:
                hit = (new["n_walking_bouts"], new["n_pauses"]) == truth
                right += hit
                ok = f" (truth {truth[0]} / {truth[1]}: {'right' if hit else 'WRONG'})"
            else:
                paused += new["n_pauses"] > 0
            print(line(f"u{user} {label}", new) + ok, flush=True)
    return right, paused


def real() -> None:
    """The real recordings of datasets/real, one printed line each (a check, not tuned on)."""
    for p in sorted((ROOT / "datasets/real").iterdir()):
        if p.is_dir():
            print(line(p.name, counts(read_session(p))), flush=True)


def main() -> None:
    right, _ = run_cases(CASES)
    print(f"stop-and-go users with the right bout / pause counts: {right} of 8", flush=True)
    real()


if __name__ == "__main__":
    sys.exit(main())
