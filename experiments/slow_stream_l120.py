"""Decision L120's measurement (rule written before it, docs/decisions/localization.md): streamed vs offline foot
strides on slow simulated walks, and the streamed default stance gap (0.03 s before, 0.2 s candidate) on normal
walks. Fresh users 420-424. Run: ``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/slow_stream_l120.py``."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.io import read_session
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys, track_streaming

USERS = range(420, 425)
SLOW = [(0.45, 1.0), (0.3, 1.0), (0.15, 1.5)]
ROUTE = "stand:3, straight:12, stand:3"


def _sim(out: Path, user: int, rate: int, gait=None) -> Path:
    args = ["simulate", "--route", ROUTE, "--user-seed", str(user), "--rate", str(rate), "--out", str(out)]
    if gait:
        args += ["--step-length", str(gait[0]), "--step-time", str(gait[1])]
    assert cli(args) == 0
    return out


def _run(session, **kw) -> tuple[int, float]:
    res = track_streaming(session, **kw) if kw.pop("_streaming", True) else track_plasys(session)
    s = track_summary(res, session)
    return len(res.steps), float(s["distance_error_pct"])


def main() -> int:
    tmp = Path(tempfile.mkdtemp(prefix="l120_"))
    rows = []
    for user in USERS:
        for gait in SLOW:
            s = read_session(_sim(tmp / f"slow_{user}_{gait[0]}_{gait[1]}", user, 100, gait))
            off = _run(s, _streaming=False)
            old = _run(s, params={"stance_gap_s": 0.03})
            new = _run(s)
            rows.append(("slow", user, f"{gait[0]}/{gait[1]} 100Hz", off, old, new))
            print(*rows[-1], flush=True)
        for rate in (100, 20):
            s = read_session(_sim(tmp / f"normal_{user}_{rate}", user, rate))
            off = _run(s, _streaming=False)
            old = _run(s, params={"stance_gap_s": 0.03})
            new = _run(s)
            rows.append(("normal", user, f"normal {rate}Hz", off, old, new))
            print(*rows[-1], flush=True)
    slow = [r for r in rows if r[0] == "slow"]
    normal = [r for r in rows if r[0] == "normal"]
    a1 = all(abs(r[5][0] - r[3][0]) <= 1 for r in slow)
    m_off = np.mean([abs(r[3][1]) for r in slow])
    m_new = np.mean([abs(r[5][1]) for r in slow])
    m_old_slow = np.mean([abs(r[4][1]) for r in slow])
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
