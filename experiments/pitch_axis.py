"""Decision L71: which axis does a mirrored foot export negate? The foot's pitch axis: the gyroscope's
principal axis (the sensor axis nearest it, :func:`pdrlearn.io.handedness.pitch_axis`) on every foot
recording (datasets/real, datasets/external gaitmap_*) and simulated scenarios A and D (user 1), and the
lateral axis of the declared frame; mirroring negates one axis of both sensors and leaves the principal axis
of the angular rate where it is, so the same axis is found on the mirrored copy.

Usage::

    PYTHONPATH=. .venv/bin/python experiments/pitch_axis.py [EXTRA_SESSION_DIR ...]
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.io.handedness import PITCH_AXIS_MAX_DEG, pitch_axis, unit_imu_arrays
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]


def lateral(session) -> str:
    f = session.frames.get("foot")
    if f is None:
        return "-"
    return next((a for a, d in f.to_dict().items() if d in ("left", "right")), "-")


def main(extra: list[str]) -> None:
    logging.disable(logging.WARNING)
    found = [*ROOT.glob("datasets/real/gaitmap_*"), *ROOT.glob("datasets/external/gaitmap_*")]
    dirs = sorted({p.resolve() for p in found})
    sessions = [(str(p.name), read_session(p)) for p in dirs] + [(e, read_session(e)) for e in extra]
    sessions += [(f"sim {sc} u1", simulate(sc, user_seed=1, speed="normal")) for sc in ("A", "D")]
    print(f"| session | pitch axis | deg from it | declared lateral axis | named (<= {PITCH_AXIS_MAX_DEG:g} deg) |")
    print("|---|---|---|---|---|")
    worst = 0.0
    for name, s in sessions:
        arrays = unit_imu_arrays(s, "foot")
        if arrays is None:
            continue
        k, deg = pitch_axis(arrays[1])
        worst = max(worst, deg)
        print(f"| {name} | {'xyz'[k]} | {deg:.1f} | {lateral(s)} | {'yes' if deg <= PITCH_AXIS_MAX_DEG else 'no'} |")
    print(f"largest angle: {worst:.1f} deg")


if __name__ == "__main__":
    main(sys.argv[1:])
