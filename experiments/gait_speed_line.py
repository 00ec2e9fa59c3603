"""Decision L353: L350's candidate line (``pdrlearn.track.gait.gait_speed_warning``) measured once against its
adoption rule: fresh simulated normal walkers (users 6651-6670) and slow walkers (6671-6680) with 2-4 turns and 2-3 s
pauses, tracked with ``--pipeline plasys`` and ``--pipeline waist-pendulum``; the real recordings with ``track DIR``.

    python experiments/gait_speed_line.py WORKDIR [--reread]

``--reread`` reads WORKDIR's tracks of an earlier run again (no simulation, no tracking): the lines of the current
functions on the same summaries (L353's amendment for L179's stair walks).

Each track's summary.json is read and L95's line (``gait_range_warning``) and the candidate's are computed on it, the
same functions `track` calls. Prints one row per track and the counts the rule names.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from pdrlearn.track.gait import gait_range_warning, gait_speed_warning

ROOT = Path(__file__).resolve().parent.parent
NORMAL, SLOW = range(6651, 6671), range(6671, 6681)
SLOW_ARGS = ["--step-length", "0.3", "--step-time", "0.75", "--bounce", "pendulum"]  # simulate --help's 0.4 m/s walker


def route(user: int) -> str:
    """L353's route: 2 + user % 3 turns (90 / 180 deg), a 2 or 3 s pause before each, straights of 6-10 m."""
    lengths, parts = (8, 6, 10, 7, 9), [f"straight:{8 + user % 3}"]
    for i in range(2 + user % 3):
        parts += [f"stand:{2 + (user + i) % 2}", f"turn:{90 if i % 2 == 0 else 180}", f"straight:{lengths[i]}"]
    return ", ".join(parts)


def cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True, cwd=ROOT)


def verdict(out: Path) -> tuple[dict, bool, bool]:
    s = json.loads((out / "summary.json").read_text())
    l95 = gait_range_warning(s)
    return s, l95 is not None and "slower" in l95, gait_speed_warning(s) is not None


def row(name: str, s: dict, l95: bool, cand: bool) -> str:
    f = lambda k: "-" if s.get(k) is None else f"{s[k]:.2f}"  # noqa: E731
    return (f"{name:42s} gait {f('gait_speed_mps')} straight {f('median_speed_straight_mps')} "
            f"(n {s.get('n_straight_strides')}) cadence {f('median_cadence_spm')} "
            f" L95-slow {int(l95)}  L353 {int(cand)}")


def main(work: Path, reread: bool = False) -> None:
    counts: dict = {}
    for group, users, extra in (("normal", NORMAL, []), ("slow", SLOW, SLOW_ARGS)):
        for u in users:
            sim = work / f"sim_{u}"
            if not reread and not (sim / "meta.json").exists():
                cli("simulate", "--route", route(u), "--user-seed", str(u), *extra, "--out", str(sim))
            for pipe in ("plasys", "waist-pendulum"):
                out = work / f"tr_{u}_{pipe}"
                if not reread:
                    cli("track", str(sim), "--pipeline", pipe, "--out", str(out), "--json")
                s, l95, cand = verdict(out)
                c = counts.setdefault(group, {"tracks": 0, "L353": 0, "L95_slow": 0, "either": 0, "both": 0})
                c["tracks"] += 1
                c["L353"] += cand
                c["L95_slow"] += l95
                c["either"] += l95 or cand
                c["both"] += l95 and cand
                print(row(f"{group} {u} {pipe}", s, l95, cand), flush=True)
    real = sorted((ROOT / "datasets" / "real").glob("*/meta.json")) + \
        sorted((ROOT / "datasets" / "external").glob("*/meta.json"))
    seen: set = set()
    for meta in real:
        d = meta.parent
        if d.name in seen:  # the same recording in both folders
            continue
        seen.add(d.name)
        out = work / f"real_{d.name}"
        if not reread:
            cli("track", str(d), "--out", str(out), "--json")
        s, l95, cand = verdict(out)
        print(row(d.name, s, l95, cand), flush=True)
    for group, c in counts.items():
        print(f"{group}: {c['tracks']} tracks, L353 line {c['L353']}, L95 slow line {c['L95_slow']}, "
              f"a slow line {c['either']}, both {c['both']}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), "--reread" in sys.argv[2:])
