"""Decisions D28 and D30 (docs/decisions/aided.md): which declared foot frames the frame check
(:func:`pdrlearn.track.frame_inference.check_declared_frame`) refuses, on fresh simulated users (the trial T3 L route
and scenario A) remounted in memory (:func:`pdrlearn.track.frame_inference.remount`) and on the real foot recordings.
Per session: the right frame; the unit yawed +-20/30/40/45 deg about its mount normal with the nearest-axis (unyawed)
frame declared; turned +-90 deg about it with the old frame kept (strapped across the foot, D28); x/y swapped with z
negated back (D11's advice followed) and the old frame kept (D30). Prints "refused" per case.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/frame_misdeclared.py [--users 9640-9647]``
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

from frame_check_evidence import sim  # noqa: E402  (one simulate call, shared)
from pdrlearn.io.plasys import read_session  # noqa: E402
from pdrlearn.track.frame_inference import check_declared_frame, remount  # noqa: E402,I001

#: trial T3's base walk
ROUTE = "stand:3, straight:20, turn:90, straight:10, turn:-90, straight:15, stand:3"
YAWS = (20, 30, 40, 45)


def about(axis: np.ndarray, deg: float) -> np.ndarray:
    """Rotation matrix of ``deg`` about the unit vector ``axis`` (Rodrigues)."""
    k = axis / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    a = np.radians(deg)
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K


def refused(s, frame, R) -> bool:
    out = remount(s, "foot", R)
    out.frames["foot"] = frame  # the declared frame kept (nearest axes, or the old one)
    return check_declared_frame(out, "foot", frame).refuse


def cases(folder: Path) -> str:
    s = read_session(folder)
    frame = s.frames.get("foot")
    if frame is None:
        return "no declared foot frame"
    normal = frame.matrix()[2]  # the sensor direction declared up: the mount normal
    parts = [f"right {refused(s, frame, np.eye(3))}"]
    yaw = [refused(s, frame, about(normal, sg * d)) for d in YAWS for sg in (1, -1)]
    parts.append(f"yaw 20-45 nearest-axis refused {sum(yaw)}/{len(yaw)}")
    across = [refused(s, frame, about(normal, sg * 90)) for sg in (1, -1)]
    parts.append(f"across 90 refused {sum(across)}/2")
    swap = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, -1]])  # x/y swapped, z negated back (D11 followed)
    parts.append(f"swapped+z-fixed refused {refused(s, frame, swap)}")
    return ", ".join(parts)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="9640-9647")
    ap.add_argument("--real-only", action="store_true")
    args = ap.parse_args()
    a, b = (int(x) for x in args.users.split("-"))
    tmp = Path(tempfile.mkdtemp(prefix="d28_"))
    for u in range(a, b + 1) if not args.real_only else ():
        for name, sargs in (("route", ("--route", ROUTE, "--rate", "100")), ("scenario A", ("--scenario", "A"))):
            d = tmp / f"{u}_{name.replace(' ', '_')}"
            sim(d, u, *sargs)
            print(f"u{u} {name}: {cases(d)}", flush=True)
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(p for p in base.iterdir() if p.is_dir() and p.name.startswith("gaitmap")):
            s = read_session(d)
            frame = s.frames.get("foot")
            verdict = ("no declared foot frame" if frame is None
                       else f"refused {check_declared_frame(s, 'foot', frame).refuse}")
            print(f"{base.name}/{d.name}: {verdict}", flush=True)


if __name__ == "__main__":
    main()
