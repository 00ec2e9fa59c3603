"""Decision L722 (session 48, trial T3 F2): L720's contact read at the heel contact point, a prototype.

The ``accel`` detector run on the heel's specific force a + alpha x r + w x (w x r) (FLU body frame; r = L22's lever
arm from a ``track --reference-point heel`` of the same recording), against the current contacts (the same detector on
the unit's own acceleration). Reads the sessions and tracks ``experiments/mount_s48_l721.py`` wrote::

    PYTHONPATH=. python experiments/mount_s48_l722.py L721_DIR 15822 15840
"""

from __future__ import annotations

import dataclasses
import json
import logging
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.orient.filters import unit_data
from pdrlearn.steps import get_detector

ROOT = Path(__file__).resolve().parents[1]


def lever_arm(summary: Path) -> np.ndarray:
    found = []

    def walk(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if k == "lever_arm_m" and v is not None:
                    found.append(v)
                walk(v)
    walk(json.loads(summary.read_text()))
    return np.asarray(found[0], dtype=float)


def contacts(session, r: np.ndarray | None) -> np.ndarray:
    """The accel detector's contacts (event_s) on the unit's acceleration (r None) or the point at r (FLU, m)."""
    if r is not None:
        u = unit_data(session, "foot")
        alpha = np.gradient(u.gyr, u.t, axis=0)
        a = u.acc + np.cross(alpha, r) + np.cross(u.gyr, np.cross(u.gyr, r))
        acc = session.streams["fAccelerometer"]
        R = session.require_frame("foot").matrix()
        session.streams["fAccelerometer"] = dataclasses.replace(acc, values=a @ R)
    return get_detector("accel").detect(session)["event_s"].to_numpy(float)


def remap(times: np.ndarray, old: np.ndarray, new: np.ndarray) -> np.ndarray:
    """Each of ``times`` (current contacts) as the new contact within 0.1 s of it (NaN if none)."""
    out = np.full(len(times), np.nan)
    for i, t in enumerate(times):
        if np.isfinite(t) and len(new):
            j = np.argmin(np.abs(new - t))
            out[i] = new[j] if abs(new[j] - t) < 0.1 else np.nan
    return out


def stance(steps: pd.DataFrame, ic_map) -> np.ndarray:
    c0, c1 = ic_map(steps["cycle_start_s"].to_numpy(float)), ic_map(steps["event_s"].to_numpy(float))
    return 100 * (steps["tc_s"].to_numpy(float) - c0) / (c1 - c0)


def sim(root: Path, lo: int, hi: int) -> None:
    rows = []
    for user in range(lo, hi):
        for mount in ("A", "B"):
            s = read_session(root / f"P{user}" / mount)
            st = pd.read_csv(root / "track" / f"P{user}" / mount / "steps.csv")
            old = contacts(s, None)
            assert np.allclose(np.sort(old), np.sort(st["event_s"].to_numpy(float))), "not the track's contacts"
            new = contacts(read_session(root / f"P{user}" / mount), lever_arm(
                root / "track" / f"P{user}" / mount / "summary.json"))
            ok = np.isfinite(st["stance_pct"].to_numpy(float)) & np.isfinite(st["ref_stance_pct"].to_numpy(float))
            cur = stance(st, lambda t: t)
            cand = stance(st, lambda t, old=old, new=new: remap(t, old, new))
            ref = st["ref_stance_pct"].to_numpy(float)
            assert np.allclose(cur[ok], st["stance_pct"].to_numpy(float)[ok])
            rows += [dict(user=user, mount=mount, cur=c, cand=k, cur_err=abs(c - f), cand_err=abs(k - f))
                     for c, k, f in zip(cur[ok], cand[ok], ref[ok], strict=True) if np.isfinite(k)]
    d = pd.DataFrame(rows)
    per = d.groupby(["user", "mount"])[["cur", "cand", "cur_err", "cand_err"]].median()
    print(f"users {lo}-{hi - 1}: {len(d)} strides with both stance values")
    print("median over users of per-user medians:")
    print(per.groupby(level="mount").median().round(4).to_string())
    diff = per.xs("B", level="mount") - per.xs("A", level="mount")
    for c in ("cur", "cand"):
        print(f"B - A stance_pct {c}: median {diff[c].median():+.4f} [{diff[c].min():+.4f}, {diff[c].max():+.4f}]")


def real() -> None:
    logging.disable(logging.WARNING)
    for side in ("left", "right"):
        src = ROOT / "datasets" / "real" / f"gaitmap_level_{side}"
        with tempfile.TemporaryDirectory() as tmp:
            assert main(["track", str(src), "--reference-point", "heel", "--out", tmp]) == 0
            r = lever_arm(Path(tmp) / "summary.json")
            tracked = pd.read_csv(Path(tmp) / "steps.csv")["event_s"].to_numpy(float)
        old, new = contacts(read_session(src), None), contacts(read_session(src), r)
        ref = pd.read_csv(src / "steps.csv")["ic_ms"].to_numpy(float) / 1000
        for name, ic in (("current", old), ("heel", new)):
            e = np.array([ic[np.argmin(np.abs(ic - t))] - t for t in ref])
            e = e[np.abs(e) < 0.15]
            print(f"gaitmap level {side} {name}: lever arm {np.round(r, 4).tolist()}, {len(e)} contacts matched, "
                  f"median error {1000 * np.median(e):+.2f} ms, median |error| {1000 * np.median(np.abs(e)):.2f} ms"
                  + (f" (track's own contacts equal: {np.allclose(np.sort(old), np.sort(tracked))})"
                     if name == "current" else ""))


if __name__ == "__main__":
    if sys.argv[1:] == ["real"]:
        real()
    else:
        sim(Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))
