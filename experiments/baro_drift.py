"""Decision L172's measurement: floors and ascent on flat long walks with the barometer's weather drift and on stair
routes, today's rule (the pdrlearn given by ``--old``, e.g. /work/main/.venv/bin/pdrlearn) against this checkout's.

Simulate first (see L172's adoption rule): ``SIM/flat_<user>`` and ``SIM/stairs_<user>``; real folders are given by
``--real``. Prints one line per track and the rule's three counts.

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/baro_drift.py --sim /tmp/fix_baro/sim \
        --old /work/main/.venv/bin/pdrlearn --real ../shared/data/mobgap_HA001_Test5_Trial1 ...
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

TRACKS = {"waist-pll": ["--pipeline", "waist-pll"], "waist-pendulum": ["--pipeline", "waist-pendulum"],
          "plasys": [], "plasys-fused": ["--altitude", "fused"]}


def _track(cmd: list[str], folder: Path, args: list[str], out: Path) -> dict:
    res = subprocess.run([*cmd, "track", str(folder), *args, "--out", str(out), "--json"], capture_output=True,
                         text=True, check=True)
    d = json.loads(res.stdout)
    d["_warned_baro"] = "disagrees with the waist barometer" in res.stderr
    return d


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sim", type=Path, required=True)
    ap.add_argument("--old", required=True, help="the pdrlearn command of today's rule")
    ap.add_argument("--out", type=Path, default=Path("out/baro_drift"))
    ap.add_argument("--real", nargs="*", default=[], type=Path)
    a = ap.parse_args()
    cmds = {"old": [a.old], "new": [sys.executable, "-m", "pdrlearn"]}
    flat_floors = {"old": 0, "new": 0}
    exact = {(v, t): 0 for v in cmds for t in TRACKS}
    n_stairs = 0
    for folder in sorted(a.sim.iterdir()):
        kind = folder.name.split("_")[0]
        for name, args in TRACKS.items():
            row = {}
            for v, cmd in cmds.items():
                d = _track(cmd, folder, args, a.out / v / f"{folder.name}_{name}")
                row[v] = d
                if kind == "flat":
                    flat_floors[v] += int(d["floors_up"] + d["floors_down"] > 0)
                else:
                    exact[(v, name)] += int((d["floors_up"], d["floors_down"])
                                            == (d.get("floors_up_ref"), d.get("floors_down_ref")))
            n_stairs += kind == "stairs"
            o, n = row["old"], row["new"]
            print(f"{folder.name} {name}: ref ({o.get('floors_up_ref')}, {o.get('floors_down_ref')}) "
                  f"old ({o['floors_up']}, {o['floors_down']}) asc {o['ascent_m']:.2f} / desc {o['descent_m']:.2f} "
                  f"warn {o['_warned_baro']}; new ({n['floors_up']}, {n['floors_down']}) asc {n['ascent_m']:.2f} / "
                  f"desc {n['descent_m']:.2f} warn {n['_warned_baro']}; altitude_change {n['altitude_change_m']:+.2f} "
                  f"ref {n.get('altitude_change_ref_m')}", flush=True)
    for folder in a.real:
        for name in ("waist-pll", "waist-pendulum"):
            o, n = (_track(cmds[v], folder, TRACKS[name], a.out / v / f"real_{folder.name}_{name}") for v in cmds)
            print(f"real {folder.name} {name}: old ({o['floors_up']}, {o['floors_down']}) asc {o['ascent_m']:.2f} "
                  f"desc {o['descent_m']:.2f}; new ({n['floors_up']}, {n['floors_down']}) asc {n['ascent_m']:.2f} "
                  f"desc {n['descent_m']:.2f}", flush=True)
    print(f"flat tracks with a floor: old {flat_floors['old']}, new {flat_floors['new']}")
    for name in TRACKS:
        print(f"stairs exact {name}: old {exact[('old', name)]}, new {exact[('new', name)]} "
              f"of {n_stairs // len(TRACKS)}")


if __name__ == "__main__":
    main()
