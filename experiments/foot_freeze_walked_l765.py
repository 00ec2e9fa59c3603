"""Decision L765 (docs/decisions/localization.md): foot freeze-index episodes filled by walking strides, measured
against the rule written before measuring. FRESH users 17590-17619, simulated with `pdrlearn simulate` at 50 Hz.

(a) slow shufflers 17590-17604 on a 20 m + 180 deg + 20 m walk: foot episodes without and with L765;
(b) users 17605-17619 on L617's freeze route (the first eight normal, the rest shufflers): sessions with an episode
    on the simulated freeze, without and with L765;
(c) a check on real recordings given as arguments (`pdrlearn track`'s foot episodes without and with L765).

Usage: python experiments/foot_freeze_walked_l765.py OUTDIR [REAL_DIR ...]
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import foot_vehicle_l615  # sibling: (b) is its (g) count

WALK = "stand:3, straight:20, turn:180, straight:20, stand:3"
FREEZE = "stand:3, straight:10, freeze:6, straight:10, stand:3"


def simulate(out: Path, route: str, user: int, shuffler: bool) -> Path:
    d = out / f"u{user}"
    if not (d / "meta.json").exists():
        gait = (["--step-length", f"{0.2 + 0.2 * ((user % 5) / 4):.3f}", "--step-time", f"{0.6 + 0.1 * (user % 5):.1f}",
                 "--swing-height", "0.06", "--bounce", "pendulum", "--bounce-scale", "0.5"] if shuffler else [])
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, *gait, "--rate", "50",
                        "--user-seed", str(user), "--seed", str(user), "--out", str(d)], check=True,
                       capture_output=True)
    return d


def episodes(session, steps, rule: bool) -> list[dict]:
    from pdrlearn.track.freezes import foot_freezes

    if rule:
        return foot_freezes(session, "plasys", steps, walked_strides=True)[0] or []
    return foot_freezes(session, "plasys", steps)[0] or []


def spans(eps) -> list[tuple]:
    return [(e["start_s"], e["end_s"], e["peak_fi"]) for e in eps]


def main(out: Path, real: list[Path]) -> None:
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    total = {False: 0, True: 0}
    for u in range(17590, 17605):
        s = read_session(simulate(out, WALK, u, True))
        steps = track_plasys(s).steps
        got = {rule: episodes(s, steps, rule) for rule in (False, True)}
        for rule in got:
            total[rule] += len(got[rule])
        print(f"(a) user {u}: without {len(got[False])} {spans(got[False])}, with {len(got[True])}")
    print(f"(a) shufflers' foot episodes in all: without L765 {total[False]}, with {total[True]}")
    freezes = ((u, read_session(simulate(out, FREEZE, u, u >= 17613))) for u in range(17605, 17620))
    foot_vehicle_l615.freeze_hits(freezes, episodes, "(b)", "L765")
    for d in real:
        s = read_session(d)
        steps = track_plasys(s).steps
        print(f"(c) {d.name}: without L765 {spans(episodes(s, steps, False))}, with {spans(episodes(s, steps, True))}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), [Path(p) for p in sys.argv[2:]])
