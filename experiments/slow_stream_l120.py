"""Decision L120's measurement (rule written before it, docs/decisions/localization.md): streamed vs offline foot
strides on slow simulated walks, and the streamed default stance gap (0.03 s before, 0.2 s candidate) on normal
walks. Users 420-424 (first candidate), 430-434 (the amended one): ``OMP_NUM_THREADS=1 PYTHONPATH=. python
experiments/slow_stream_l120.py [FIRST_USER LAST_USER]``."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.errors import DataError

USERS = range(int(sys.argv[1]), int(sys.argv[2]) + 1) if len(sys.argv) > 2 else range(420, 425)
SLOW = [(0.45, 1.0), (0.3, 1.0), (0.15, 1.5)]
ROUTE = "stand:3, straight:12, stand:3"


def _sim(out: Path, user: int, rate: int, gait=None) -> Path:
    args = ["simulate", "--route", ROUTE, "--user-seed", str(user), "--rate", str(rate), "--out", str(out)]
    if gait:
        args += ["--step-length", str(gait[0]), "--step-time", str(gait[1])]
    assert cli(args) == 0
    return out


def _run(folder: Path, *, streaming: bool = True, params: Path | None = None) -> tuple:
    """``pdrlearn track [--streaming] [--params]`` (no model): (rows of steps.csv, distance error %), or (None,
    the error line) when the track fails (the old segmenter's false stance can fail the foot frame check)."""
    try:
        out = track_session(folder, track_settings(pipeline="plasys", streaming=streaming, params=params))
    except DataError as exc:
        return None, str(exc)[:60]
    return len(out["result"].steps), round(float(out["summary"]["distance_error_pct"]), 2)


def main() -> int:
    tmp = Path(tempfile.mkdtemp(prefix="l120_"))
    old_gap = tmp / "old.json"  # L120 off: the stance survives the fixed stance_gap_s alone
    old_gap.write_text('{"stance_gap_swing_frac": 0.0}')
    rows = []
    for user in USERS:
        for gait in SLOW:
            s = _sim(tmp / f"slow_{user}_{gait[0]}_{gait[1]}", user, 100, gait)
            off, old, new = _run(s, streaming=False), _run(s, params=old_gap), _run(s)
            rows.append(("slow", user, f"{gait[0]}/{gait[1]} 100Hz", off, old, new))
            print(*rows[-1], flush=True)
        for rate in (100, 20):
            s = _sim(tmp / f"normal_{user}_{rate}", user, rate)
            off, old, new = _run(s, streaming=False), _run(s, params=old_gap), _run(s)
            rows.append(("normal", user, f"normal {rate}Hz", off, old, new))
            print(*rows[-1], flush=True)
    slow = [r for r in rows if r[0] == "slow"]
    normal = [r for r in rows if r[0] == "normal"]
    ok = [r for r in slow if r[3][0] is not None and r[5][0] is not None]
    a1 = len(ok) == len(slow) and all(abs(r[5][0] - r[3][0]) <= 1 for r in slow)
    m_off = np.mean([abs(r[3][1]) for r in slow])
    m_new = np.mean([abs(r[5][1]) for r in slow])
    old_ok = [r for r in slow if r[4][0] is not None]
    m_old_slow = np.mean([abs(r[4][1]) for r in old_ok])
    print(f"old segmenter failed on {len(slow) - len(old_ok)} slow walk(s); its mean over the others")
    b1 = all(r[4][0] == r[5][0] for r in normal)
    n_old = np.mean([abs(r[4][1]) for r in normal])
    n_new = np.mean([abs(r[5][1]) for r in normal])
    print(f"(a) slow streamed counts within 1 of offline on every walk: {a1}; mean |dist err| offline {m_off:.2f} %, "
          f"streamed old {m_old_slow:.2f} %, candidate {m_new:.2f} % -> {m_new <= m_off + 3}")
    print(f"(b) normal streamed counts unchanged: {b1}; mean |dist err| old {n_old:.2f} %, candidate {n_new:.2f} % "
          f"-> {n_new <= n_old + 0.3}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
