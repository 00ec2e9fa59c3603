"""Decisions L480 / L481: L474's speed range taken over, and compared on, the cruise strides (rule B: touching both
neighbours), on simulated users (docs/decisions/localization.md).

Per user: the three calibration exercises are simulated and ``train``-ed; a normal walk with pauses and a very slow
walk (0.33-0.39 m/s) are tracked offline with the model; it prints the flagged strides (steps.csv
``speed_out_of_range``) of each. L480 / L481 were adopted and W413 removed their module switches
(``SPEED_CRUISE``, ``CRUISE_CONTIGUOUS``), so this prints the rule as it is; the "old" arm (every stride) and rule A
they measured are at commit d3ffb129 (``git show d3ffb129:experiments/speed_cruise_l480.py``).

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/speed_cruise_l480.py --out /tmp/l480   # ~8 min
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pandas as pd

from fused_ramp_l478 import run  # noqa: E402
from slopes import users  # noqa: E402

NORMAL = "stand:3, straight:30, stand:5, straight:20, turn:90, straight:20, stand:5, straight:15, stand:3"
SLOW = "stand:3, straight:15, stand:3"
#: L480: (--step-length m, --step-time s) of the slow walk, one per user in turn: 0.33-0.39 m/s
SLOW_GAITS = [(0.20, 0.55), (0.18, 0.55), (0.22, 0.60), (0.20, 0.60), (0.24, 0.62)]


def simulate(root: Path, name: str, user: int, args: list[str]) -> Path:
    out = root / name
    if not (out / "meta.json").exists():
        run(["simulate", *args, "--user-seed", str(user), "--out", str(out), "--force"])
    return out


def flagged(sim: Path, model: Path, out: Path) -> tuple[int, int]:
    run(["track", str(sim), "--model", str(model), "--out", str(out), "--force"])
    st = pd.read_csv(out / "steps.csv")
    col = st["speed_out_of_range"].astype(str).str.lower() == "true" if "speed_out_of_range" in st else st.index < 0
    return int(col.sum()), len(st)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="9495-9499")
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    total = [0, 0, 0, 0]
    for i, u in enumerate(users(a.users)):
        cal = [simulate(a.out, f"cal_{ex}_u{u}", u, ["--scenario", ex]) for ex in ("terrain", "direction", "length")]
        sl, stime = SLOW_GAITS[i % len(SLOW_GAITS)]
        normal = simulate(a.out, f"normal_u{u}", u, ["--route", NORMAL])
        slow = simulate(a.out, f"slow_u{u}", u, ["--route", SLOW, "--step-length", str(sl), "--step-time", str(stime)])
        model = a.out / f"m_u{u}"
        if not (model / "manifest.json").exists():
            run(["train", *map(str, cal), "--out", str(model), "--force"])
        rng = json.loads((model / "manifest.json").read_text())["training_data"]["distance_calibration"]
        n_n, m_n = flagged(normal, model, a.out / f"t_normal_u{u}")
        n_s, m_s = flagged(slow, model, a.out / f"t_slow_u{u}")
        total = [t + v for t, v in zip(total, (n_n, m_n, n_s, m_s), strict=True)]
        print(u, f"range {rng['speed_range_mps']} normal {n_n}/{m_n} slow {n_s}/{m_s} ({sl / stime:.2f} m/s)",
              flush=True)
    n_n, m_n, n_s, m_s = total
    print(f"normal walks {n_n} of {m_n} strides flagged; slow walks {n_s} of {m_s} ({100 * n_s / max(m_s, 1):.1f} %)")

if __name__ == "__main__":
    main()
