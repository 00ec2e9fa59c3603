"""Decision L172's measurement: floors and ascent on flat long walks with the barometer's weather drift and on stair
routes, today's rule (the pdrlearn given by ``--old``, e.g. /work/main/.venv/bin/pdrlearn) against this checkout's.

Simulate first (see L172's adoption rule): ``SIM/flat_<user>`` and ``SIM/stairs_<user>``; real folders are given by
``--real``. ``--old`` is a checkout of today's code (e.g. ``git archive main``): each version tracks every session
in one process of its own (``pdrlearn.cli.main``, as ``pdrlearn track ... --json``). Prints one line per track and
the rule's three counts.

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/baro_drift.py --sim /tmp/fix_baro/sim \
        --old /tmp/main_copy --real ../shared/data/mobgap_HA001_Test5_Trial1 ...
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

TRACKS = {"waist-pll": ["--pipeline", "waist-pll"], "waist-pendulum": ["--pipeline", "waist-pendulum"],
          "plasys": [], "plasys-fused": ["--altitude", "fused"]}


def _worker(folders: list[str], out: str) -> None:
    """Track every folder with every track of :data:`TRACKS` in this process; one JSON line each."""
    import contextlib
    import io

    from pdrlearn.cli import main as cli

    for folder in folders:
        for name, args in TRACKS.items():
            buf = io.StringIO()
            with contextlib.redirect_stdout(buf):
                rc = cli(["track", folder, *args, "--out", f"{out}/{Path(folder).name}_{name}", "--json"])
            if rc or not buf.getvalue().strip():  # a waist-only real recording has no foot track
                continue
            d = json.loads(buf.getvalue())
            warned = any("disagrees with the waist barometer" in w for w in d.get("info", {}).get("warnings", []))
            print(json.dumps({"folder": folder, "track": name, "warned": warned,
                              **{k: d.get(k) for k in KEYS}}), flush=True)


KEYS = ("floors_up", "floors_down", "floors_up_ref", "floors_down_ref", "ascent_m", "descent_m",
        "altitude_change_m", "altitude_change_ref_m")


def _run(root: str, folders: list[str], out: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": root}
    res = subprocess.run([sys.executable, __file__, "--worker", str(out), *folders], capture_output=True, text=True,
                         env=env, check=True)
    rows = [json.loads(line) for line in res.stdout.splitlines() if line.startswith("{")]
    return {(Path(r["folder"]).name, r["track"]): r for r in rows}


def main() -> None:
    if sys.argv[1:2] == ["--worker"]:
        return _worker(sys.argv[3:], sys.argv[2])
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sim", type=Path, required=True)
    ap.add_argument("--old", required=True, help="a checkout of today's code")
    ap.add_argument("--out", type=Path, default=Path("out/baro_drift"))
    ap.add_argument("--real", nargs="*", default=[], type=Path)
    a = ap.parse_args()
    folders = [str(f) for f in sorted(a.sim.iterdir())] + [str(f.resolve()) for f in a.real]
    runs = {"old": _run(a.old, folders, a.out / "old"),
            "new": _run(str(Path(__file__).resolve().parents[1]), folders, a.out / "new")}
    flat = {v: 0 for v in runs}
    exact = {(v, t): 0 for v in runs for t in TRACKS}
    n_stairs = 0
    for key in runs["new"]:
        o, n = runs["old"].get(key), runs["new"][key]
        if o is None:
            print(f"{key[0]} {key[1]}: tracked by the new code only")
            continue
        kind = key[0].split("_")[0]
        print(f"{key[0]} {key[1]}: ref ({o.get('floors_up_ref')}, {o.get('floors_down_ref')}) old ({o['floors_up']}, "
              f"{o['floors_down']}) asc {o['ascent_m']:.2f} / desc {o['descent_m']:.2f} warn {o['warned']}; new "
              f"({n['floors_up']}, {n['floors_down']}) asc {n['ascent_m']:.2f} / desc {n['descent_m']:.2f} warn "
              f"{n['warned']}; altitude_change {n['altitude_change_m']:+.2f} ref {n.get('altitude_change_ref_m')}")
        for v, d in (("old", o), ("new", n)):
            if kind == "flat":
                flat[v] += int(d["floors_up"] + d["floors_down"] > 0)
            elif kind == "stairs":
                ref = (d["floors_up_ref"], d["floors_down_ref"])
                exact[(v, key[1])] += int((d["floors_up"], d["floors_down"]) == ref)
        n_stairs += kind == "stairs"
    print(f"flat tracks with a floor: old {flat['old']}, new {flat['new']}")
    for name in TRACKS:
        print(f"stairs exact {name}: old {exact[('old', name)]}, new {exact[('new', name)]} "
              f"of {n_stairs // len(TRACKS)}")


if __name__ == "__main__":
    main()
