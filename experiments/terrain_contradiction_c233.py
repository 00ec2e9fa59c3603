"""Decision C233 (docs/decisions/classifiers.md): strides whose measured height clearly contradicts their terrain class.

For each fresh simulated user (default 16760-16789): the terrain calibration exercise (seed 0) trains a per-user
terrain model (``train_user(tasks=["terrain"], seed=0)``); four routes (level, short steps, stairs, ramps; seed 1) are
tracked (``track_plasys(model=...)``). Per session: the strides C233 counts (the kernel's masks on the classes and
integrated heights ``terrain_dz_check`` receives), how many of them hold a class other than the simulator's label,
the classes' agreement with the labels, and whether C233's line fired. Writes
experiments/results/terrain_contradiction_c233.csv (one row per user and route).

    PYTHONPATH=. .venv/bin/python experiments/terrain_contradiction_c233.py [--users 16760 ... 16789]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.kernels import altitude_check as AC
from pdrlearn.sim import simulate
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track import plasys
from pdrlearn.track.evaluate import with_reference_columns

OUT = Path(__file__).parent / "results"
ROUTES = {"level": "straight:20, turn:180, straight:20",
          "short": "straight:10:short, turn:180, straight:10:short",
          "stairs": "straight:3, up:10, turn:180, down:10, straight:3",
          "ramps": "straight:3, slope:20:6, turn:180, slope:20:-6, straight:3"}


def masks_of(terrain, raw):
    terr = np.array([t if isinstance(t, str) else "" for t in terrain], dtype=object)
    level, stair = AC.clear_contradictions(terr, np.asarray(raw, float), AC.next_to_stairs(terr))
    return terr, level | stair


def rows_of(u: int, model) -> list[dict]:
    rows, seen = [], {}
    real = plasys.terrain_dz_check

    def spy(terrain, raw_dz, dz):
        seen["args"] = (np.asarray(terrain, dtype=object), np.asarray(raw_dz, float))
        return real(terrain, raw_dz, dz)

    plasys.terrain_dz_check = spy
    try:
        for name, route in ROUTES.items():
            s = simulate_path(parse_route(route), UserProfile.from_seed(u), seed=1)
            seen.clear()
            res = plasys.track_plasys(s, model=model)
            st = with_reference_columns(res, s)
            terr, flag = masks_of(*seen["args"])
            assert len(terr) == len(st), (len(terr), len(st))
            j = st["ref_match"].to_numpy(float) if "ref_match" in st else np.full(len(st), np.nan)
            ok = np.isfinite(j) & (terr != "")
            truth = np.full(len(st), "", dtype=object)
            truth[ok] = s.steps["terrain"].to_numpy(dtype=object)[j[ok].astype(int)]
            fired = any("clearly contradict" in w for w in res.info["warnings"])
            rows.append({"user": u, "route": name, "n": int(ok.sum()), "agree": int((ok & (terr == truth)).sum()),
                         "flagged": int(flag.sum()), "flagged_matched": int((flag & ok).sum()),
                         "flagged_wrong": int((flag & ok & (terr != truth)).sum()), "fired": fired})
    finally:
        plasys.terrain_dz_check = real
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, nargs="+", default=list(range(16760, 16790)))
    ap.add_argument("--out", type=Path, default=OUT / "terrain_contradiction_c233.csv")
    ap.add_argument("--real", action="store_true", help="only the real gaitmap recordings' check")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    if a.real:
        return real_check()
    for u in a.users:
        model = train_user([simulate("terrain", user_seed=u, seed=0)], tasks=["terrain"], seed=0)
        df = pd.DataFrame(rows_of(u, model))
        df.to_csv(a.out, mode="a", header=not a.out.exists(), index=False)
        print(df.to_string(index=False), flush=True)


def real_check() -> None:
    """The check on the real gaitmap foot recordings (not tuned to): C28's three-recording terrain model (level_left,
    stairs_up_left, stairs_down_left: three of the four are its training recordings); per recording the classes,
    C233's counts and whether its line fired."""
    from pdrlearn.io import read_session

    root = Path(__file__).resolve().parents[1] / "datasets" / "real"
    names = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
    sessions = {n: read_session(root / n) for n in names}
    train = ("gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")
    models = {"c28": train_user([sessions[n] for n in train], tasks=["terrain"], cv=10, seed=0)}
    for mname, model in models.items():
        for n, s in sessions.items():
            res = plasys.track_plasys(s, model=model)
            tc = res.info.get("terrain_dz_check") or {}
            counts = {str(k): int(v) for k, v in res.steps["terrain"].value_counts().items()}
            fired = any("clearly contradict" in w for w in res.info["warnings"])
            print(f"{mname} {n}: classes {counts}, clear level-as-stairs {tc.get('clear_level_as_stairs')}, "
                  f"flat-as-stairs {tc.get('clear_stairs_as_flat')}, line {fired}", flush=True)


if __name__ == "__main__":
    main()
