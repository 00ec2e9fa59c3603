"""Decision W402 (docs/decisions/waist.md): the waist distance error on start-stop routes, for W157's warning text:
fresh simulated users 9556-9559, T2's stop-and-go `sg1` route (normal steps) and W157's queue (0.2 m steps of 0.7 s),
waist-pendulum and waist-pll, uncalibrated; whether W157's line fired."""

from __future__ import annotations

import logging
import subprocess
import sys
import tempfile
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

SG1 = ("stand:3, straight:0.7, stand:2, straight:1.4, stand:2, straight:0.7, stand:2, straight:2.1, stand:2, "
       "backward:1, stand:2, straight:0.7, stand:2, backward:1, stand:2, straight:1.4, stand:3")
QUEUE = ", ".join(["stand:4, straight:0.5"] * 12)
ROUTES = {"sg1": (SG1, []), "queue": (QUEUE, ["--step-length", "0.2", "--step-time", "0.7"])}


def main() -> None:
    logging.disable(logging.WARNING)
    errors = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, (route, extra) in ROUTES.items():
            for user in range(9556, 9560):
                out = Path(tmp) / f"{name}{user}"
                subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed",
                                str(user), "--out", str(out), *extra], check=True, capture_output=True)
                s = read_session(out)
                for pipeline in ("waist-pendulum", "waist-pll"):
                    res = get_pipeline(pipeline)(s)
                    err = track_summary(res, s)["distance_error_pct"]
                    fired = any("decision W157" in w for w in res.info["warnings"])
                    if fired:
                        errors.append(err)
                    print(f"{name} u{user} {pipeline}: distance error {err:+.1f} %, W157 line "
                          f"{'fired' if fired else 'silent'}", flush=True)
    print(f"where the line fired: {min(errors):+.1f} to {max(errors):+.1f} %", flush=True)


if __name__ == "__main__":
    sys.exit(main())
