"""Decision L127's measurement: floors counted per climb (``count_floors_by_climb``) against L64's count from the
absolute altitude (``count_floors``), on fresh simulated users (a calibration, a 3-loop multi-floor session and
a level session each, tracked with ``track`` and ``run``) and the real gaitmap stair and level recordings.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/floor_climbs.py --users 560-579 --work /tmp/floors
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import pandas as pd

from pdrlearn.track.evaluate import count_floors, count_floors_by_climb

#: the trial's loop (session 21, trial "responder"): 2 storeys of 17 x 0.17 m up, level and backward, stops, 2 down
LOOP = ("straight:10, up:17, turn:180, up:17, straight:6, backward:12, stand:60, straight:6, turn:180, down:17, "
        "turn:180, down:17, straight:10, turn:180, backward:20, straight:10, turn:180, stand:30")
MULTI = "stand:10, " + ", ".join([LOOP] * 3)  # truth 6 up / 6 down
LEVEL = "stand:10, straight:20, turn:180, stand:300, straight:20, backward:10, turn:180, straight:10, stand:10"
REAL = {"gaitmap_stairs_up_left": (1, 0), "gaitmap_stairs_up_right": (1, 0), "gaitmap_stairs_down_left": (0, 1),
        "gaitmap_stairs_down_right": (0, 1), "gaitmap_level_left": (0, 0), "gaitmap_level_right": (0, 0)}


def cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True)


def counts(out: Path) -> tuple[tuple[int, int], tuple[int, int]]:
    """(L64's (up, down) from trajectory.csv's z, L127's (up, down) from steps.csv's dz_m), storeys of 3.0 m."""
    up, down, _ = count_floors_by_climb(pd.read_csv(out / "steps.csv")["dz_m"].to_numpy(float))
    return count_floors(pd.read_csv(out / "trajectory.csv")["z"].to_numpy(float))[:2], (up, down)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="560-579")
    ap.add_argument("--work", type=Path, required=True)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    rows = []
    for u in range(lo, hi + 1):
        w = a.work / f"u{u}"
        for sc in ("terrain", "direction", "length"):
            cli("simulate", "--scenario", sc, "--user-seed", str(u), "--out", str(w / "calib" / sc))
        cli("train", str(w / "calib"), "--out", str(w / "model"))
        cli("export", str(w / "model"), "--out", str(w / "bundle"))
        for kind, route, truth in (("multi", MULTI, (6, 6)), ("level", LEVEL, (0, 0))):
            cli("simulate", "--route", route, "--user-seed", str(u), "--seed", str(u), "--out", str(w / kind))
            cli("track", str(w / kind), "--model", str(w / "model"), "--out", str(w / f"track_{kind}"))
            cli("run", str(w / "bundle"), str(w / kind), "--out", str(w / f"run_{kind}"))
            for mode in ("track", "run"):
                band, climb = counts(w / f"{mode}_{kind}")
                rows.append(dict(source=f"u{u}", kind=kind, mode=mode, truth=truth, band=band, climb=climb))
                print(rows[-1], flush=True)
    for name, truth in REAL.items():
        d = next((p / name for p in (Path("datasets/real"), Path("datasets/external")) if (p / name).is_dir()), None)
        if d is None:
            continue
        cli("track", str(d), "--out", str(a.work / f"real_{name}"))
        band, climb = counts(a.work / f"real_{name}")
        rows.append(dict(source=name, kind="real", mode="track", truth=truth, band=band, climb=climb))
        print(rows[-1], flush=True)
    t = pd.DataFrame(rows)
    for m in ("band", "climb"):
        t[f"{m}_ok"] = [x == y for x, y in zip(t[m], t["truth"], strict=True)]
        t[f"{m}_level"] = [x == (0, 0) for x in t[m]]
    multi = t[t.kind == "multi"]
    print(f"multi-floor exact: band {multi.band_ok.sum()}/{len(multi)}, climb {multi.climb_ok.sum()}/{len(multi)}")
    lev = t[[k == "level" or (k == "real" and x == (0, 0)) for k, x in zip(t.kind, t.truth, strict=True)]]
    print(f"level tracks with a floor: band {(~lev.band_level).sum()}/{len(lev)}, climb {(~lev.climb_level).sum()}"
          f"/{len(lev)}; new by climb {int((lev.band_level & ~lev.climb_level).sum())}")
    st = t[[k == "real" and x != (0, 0) for k, x in zip(t.kind, t.truth, strict=True)]]
    print(f"real stairs exact: band {st.band_ok.sum()}/{len(st)}, climb {st.climb_ok.sum()}/{len(st)}; "
          f"band-exact lost by climb {int((st.band_ok & ~st.climb_ok).sum())}")
    t.to_csv(a.work / "floor_climbs.csv", index=False)


if __name__ == "__main__":
    main()
