"""Decision B201's measurement (docs/decisions/bad-input.md; the adoption rule was committed before this ran):
how many sessions the 7 % rest-|acc| warning (``foot_rest.foot_scale_warning``) fires on.

    python experiments/foot_scale_b201.py SIMDIR [TRIAL_C_DIR]

SIMDIR holds fresh simulated sessions (``pdrlearn simulate --scenario D --rate 100 --user-seed U``, U = 2960-2979);
each is judged as simulated and with its foot accelerometer scaled x0.9 and x1.1 (in memory: the same statistic
``pdrlearn track`` / ``info`` judge). Also every recording with a foot unit in datasets/real and datasets/external,
and the trial's ``Ls_*`` copies when TRIAL_C_DIR is given. Prints one line per session and the counts.
"""

from __future__ import annotations

import sys
from pathlib import Path

from pdrlearn.io import Stream, read_session
from pdrlearn.track.foot_rest import foot_rest_stats, foot_scale_warning

ROOT = Path(__file__).resolve().parents[1]


def judged(session) -> tuple[float | None, bool]:
    stats = foot_rest_stats(session)
    return (stats or {}).get("rest_acc_g"), foot_scale_warning(stats, session.where) is not None


def scaled(session, k: float):
    acc = session.streams["fAccelerometer"]
    session.streams["fAccelerometer"] = Stream("fAccelerometer", acc.t, acc.values * k)
    return session


def main(sim_dir: str, trial_dir: str | None = None) -> None:
    real = sorted(p for d in ("datasets/real", "datasets/external") for p in (ROOT / d).iterdir()
                  if (p / "fAccelerometer.csv").is_file())
    warned = 0
    for p in real:
        g, w = judged(read_session(p))
        warned += w
        print(f"real {p.parent.name}/{p.name}: rest {g:.4f} g, warned {w}")
    print(f"real/external foot recordings: {warned} of {len(real)} warned")
    sims = sorted(p for p in Path(sim_dir).iterdir() if (p / "fAccelerometer.csv").is_file())
    counts = {1.0: 0, 0.9: 0, 1.1: 0}
    for p in sims:
        row = []
        for k in counts:
            g, w = judged(scaled(read_session(p), k) if k != 1.0 else read_session(p))
            counts[k] += w
            row.append(f"x{k:g} {g:.4f} g {'W' if w else '-'}")
        print(f"sim {p.name}: " + ", ".join(row))
    print(f"fresh simulated: unscaled {counts[1.0]} of {len(sims)} warned; x0.9 {counts[0.9]}, x1.1 {counts[1.1]}: "
          f"{counts[0.9] + counts[1.1]} of {2 * len(sims)} scaled copies warned")
    if trial_dir:
        trial = sorted(Path(trial_dir).glob("Ls_*"))
        n = 0
        for p in trial:
            g, w = judged(read_session(p))
            n += w
            print(f"trial {p.name}: rest {g:.4f} g, warned {w}")
        print(f"trial copies: {n} of {len(trial)} warned")


if __name__ == "__main__":
    main(*sys.argv[1:])
