"""Decision L510's adoption rule (docs/decisions/localization.md): a foot-only (and D25-fallback) track's heading 0 as
the walker's facing at the first walk (``plasys.foot_walk_reference`` with the strides' sides; W413: no module
switch) against L494's travel reference, by ``pdrlearn track --json``'s final position and
``final_position_error_m``, on simulated users 10000-10005 and the real gaitmap foot recordings of
datasets/external (a check, not tuned on)."""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SIDE_FIRST = "stand:2, side:3, straight:4, stand:2"
CASES = [(10000, SIDE_FIRST), (10001, SIDE_FIRST), (10002, "stand:2, side:-3, straight:4, stand:2"),
         (10003, "stand:2, backward:4, straight:4, stand:2"),
         (10004, "stand:2, straight:6, turn:90, straight:4, side:2, stand:2"),
         (10005, "stand:2, straight:6, turn:90, straight:4, side:2, stand:2")]
#: runs ``pdrlearn`` with L510 (argv[1] == '1') or L494's travel reference (the strides' sides not passed)
RUNNER = ("import runpy, sys; import pdrlearn.track.plasys as p; f = p.foot_walk_reference; "
          "p.foot_walk_reference = f if sys.argv.pop(1) == '1' else (lambda h, d, lateral=None, turn=None: f(h, d)); "
          "sys.argv[0] = 'pdrlearn'; runpy.run_module('pdrlearn', run_name='__main__')")


def track(folder: Path, out: Path, facing: bool, units: str) -> dict:
    r = subprocess.run([sys.executable, "-c", RUNNER, "1" if facing else "0", "track", str(folder), "--out", str(out),
                        "--units", units, "--json", "--force"], capture_output=True, text=True, check=True)
    s = json.loads(r.stdout)
    p = s["final_position"]
    return {"xy": (p["x"], p["y"]), "err": s.get("final_position_error_m")}


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folders = []
        for user, route in CASES:
            f = Path(tmp) / f"u{user}"
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(user),
                            "--out", str(f)], check=True, capture_output=True)
            folders.append((f"u{user} {route}", f, ("foot", "foot,waist") if user >= 10004 else ("foot",)))
        ext = ROOT / "datasets/external"
        folders += [(p.name, p, ("foot",)) for p in sorted(ext.glob("gaitmap*")) if p.is_dir()]
        for name, f, units in folders:
            for u in units:
                old, new = (track(f, Path(tmp) / "out", facing, u) for facing in (False, True))
                err = "" if new["err"] is None else f" final error {old['err']:.3f} -> {new['err']:.3f} m"
                moved = ((old["xy"][0] - new["xy"][0]) ** 2 + (old["xy"][1] - new["xy"][1]) ** 2) ** 0.5
                print(f"{name} --units {u}: final ({old['xy'][0]:.3f}, {old['xy'][1]:.3f}) -> ({new['xy'][0]:.3f}, "
                      f"{new['xy'][1]:.3f}){err}; moved {moved:.2e} m", flush=True)


if __name__ == "__main__":
    sys.exit(main())
