"""Fixes every 60 s on streamed and offline foot tracks of a multi-floor route: the measurement of decision D24
(docs/decisions/aided.md, adoption rule there).

    PYTHONPATH=<checkout> .venv/bin/python experiments/aided_streamed.py --cache DIR --out OUT.csv [--users 4000-4019]
    .venv/bin/python experiments/aided_streamed.py --compare BASE.csv CAND.csv

The sessions (the simulator on the route R1 twice) and the unaided tracks (``pdrlearn track [--streaming]``, no
model) are written once into DIR and reused; the fixes are fused by ``aid_track`` of the checkout on PYTHONPATH, so
run the script once with the baseline and once with the candidate checkout, then ``--compare``. Fixes: the pelvis
truth every 60 s + N(0, 1 m) per axis, ``accuracy_m`` 2, in the track's frame (origin = the truth at the track's first
row; the trial's nav/mkfix.py), rng seed = user.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

#: the trial's multi-floor route (session 28, trial_nav.md): 3.3 min, one loop up and down two storeys
R1 = ("stand:5, straight:20, turn:90, straight:15, up:17, turn:180, up:17, straight:10, turn:-90, straight:25, "
      "backward:4, stand:20, turn:180, straight:25, turn:90, straight:10, down:17, turn:180, down:17, straight:15, "
      "turn:-90, straight:20, turn:180")
KINDS = ("str", "off")


def _cli(*args) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *map(str, args)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, env=dict(os.environ))


def prepare(u: int, cache: Path, loops: int = 2) -> Path:
    """Simulate the route and track it unaided (streamed and offline) once; return the user's folder."""
    d = cache / f"u{u}"
    if not (d / "meta.json").is_file():
        _cli("simulate", "--route", ", ".join([R1] * loops), "--user-seed", u, "--out", d)
    for kind in KINDS:
        out = cache / f"u{u}.{kind}"
        if not (out / "summary.json").is_file():
            _cli("track", d, *(["--streaming"] if kind == "str" else []), "--out", out)
    return d


def truth_at(session: Path, t: np.ndarray, t0: float) -> np.ndarray:
    tr = pd.read_csv(session / "trajectory.csv")
    tt = tr["timestamp"].to_numpy(float) / 1000.0
    x0, y0 = np.interp(t0, tt, tr["x"]), np.interp(t0, tt, tr["y"])
    return np.c_[np.interp(t, tt, tr["x"]) - x0, np.interp(t, tt, tr["y"]) - y0]


def fixes_for(session: Path, track: Path, seed: int, period_s: float = 60.0) -> pd.DataFrame:
    tr = pd.read_csv(session / "trajectory.csv")
    t_end = float(tr["timestamp"].iloc[-1]) / 1000.0
    t0 = float(pd.read_csv(track / "trajectory.csv")["t"].iloc[0])
    rng = np.random.default_rng(seed)
    ts = np.arange(period_s, t_end - 5.0, period_s)
    xy = truth_at(session, ts, t0)
    return pd.DataFrame({"t": ts, "x": xy[:, 0] + rng.normal(0, 1, len(ts)), "y": xy[:, 1] + rng.normal(0, 1, len(ts)),
                         "accuracy_m": 2.0})


def user_rows(u: int, cache: Path) -> list[dict]:
    from pdrlearn.aid import aid_track
    from pdrlearn.io import read_session
    from pdrlearn.track.base import TrackResult

    d = prepare(u, cache)
    ses = read_session(d)
    rows = []
    for kind in KINDS:
        trk = cache / f"u{u}.{kind}"
        traj, steps = pd.read_csv(trk / "trajectory.csv"), pd.read_csv(trk / "steps.csv")
        t0 = float(traj["t"].iloc[0])
        fx = fixes_for(d, trk, u)
        path = cache / f"fix{u}.{kind}.csv"
        fx.to_csv(path, index=False)
        res = aid_track(TrackResult(steps, traj[["t", "x", "y", "z"]].copy(), {}), ses, fixes_path=path)
        ft = res.trajectory
        g = truth_at(d, ft["t"].to_numpy(float), t0)
        e = np.hypot(ft["x"] - g[:, 0], ft["y"] - g[:, 1]).to_numpy()
        gu = truth_at(d, traj["t"].to_numpy(float), t0)
        eu = np.hypot(traj["x"] - gu[:, 0], traj["y"] - gu[:, 1]).to_numpy()
        rows.append({"user": u, "kind": kind, "rmse_m": float(np.sqrt(np.mean(e**2))), "final_m": float(e[-1]),
                     "max_m": float(e.max()), "unaided_final_m": float(eu[-1]), "unaided_max_m": float(eu.max()),
                     "unaided_final_sigma_m": float(traj["pos_sigma_m"].iloc[-1]),
                     "fixes_used": res.info["aid"]["fixes"]["fixes_used"],
                     "heading_offset_deg": res.info["aid"]["fixes"]["heading_offset_deg"]})
        print(json.dumps({k: (round(v, 3) if isinstance(v, float) else v) for k, v in rows[-1].items()}), flush=True)
    return rows


def compare(base: Path, cand: Path) -> int:
    b, c = pd.read_csv(base), pd.read_csv(cand)
    m = b.merge(c, on=["user", "kind"], suffixes=("_b", "_c"))
    s = m[m.kind == "str"]
    o = m[m.kind == "off"]
    ra, rb = s.rmse_m_b.mean(), s.rmse_m_c.mean()
    print(f"(a) streamed mean RMSE {ra:.3f} -> {rb:.3f} m ({(rb / ra - 1) * 100:+.1f} %); holds: {rb <= 0.8 * ra}")
    for tag, col in (("baseline", "_b"), ("candidate", "_c")):
        lim = s.unaided_final_m_b + 2 * s.unaided_final_sigma_m_b
        fin_bad = s[s["final_m" + col] > lim]
        max_bad = s[s["max_m" + col] > s.unaided_max_m_b + 2 * s.unaided_final_sigma_m_b]
        print(f"(b) {tag}: users with final > unaided final + 2 sigma: {len(fin_bad)} of {len(s)} "
              f"{fin_bad.user.tolist()}; with max > unaided max + 2 sigma: {len(max_bad)} of {len(s)} "
              f"{max_bad.user.tolist()}")
    print(f"    streamed final error mean {s.final_m_b.mean():.3f} -> {s.final_m_c.mean():.3f} m (unaided "
          f"{s.unaided_final_m_b.mean():.3f} m, 2 sigma {2 * s.unaided_final_sigma_m_b.mean():.3f} m); worst "
          f"{s.final_m_b.max():.3f} -> {s.final_m_c.max():.3f} m")
    oa, ob = o.rmse_m_b.mean(), o.rmse_m_c.mean()
    worst = float((o.rmse_m_c - o.rmse_m_b).max())
    print(f"(c) offline mean RMSE {oa:.3f} -> {ob:.3f} m ({(ob / oa - 1) * 100:+.1f} %), largest per-user increase "
          f"{worst:+.3f} m; holds: {ob <= 1.05 * oa and worst <= 1.0}")
    print(f"    offline final error mean {o.final_m_b.mean():.3f} -> {o.final_m_c.mean():.3f} m (unaided "
          f"{o.unaided_final_m_b.mean():.3f} m)")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4000-4019", help="user range, e.g. 4000-4019")
    ap.add_argument("--cache", type=Path, help="folder for the sessions and the unaided tracks (reused)")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--compare", nargs=2, type=Path, metavar=("BASE", "CAND"))
    a = ap.parse_args(argv)
    if a.compare:
        return compare(*a.compare)
    if a.cache is None or a.out is None:
        ap.error("give --cache and --out (or --compare BASE CAND)")
    lo, hi = (int(v) for v in a.users.split("-"))
    a.cache.mkdir(parents=True, exist_ok=True)
    rows = [r for u in range(lo, hi + 1) for r in user_rows(u, a.cache)]
    pd.DataFrame(rows).to_csv(a.out, index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
