"""Decision W105's rule (docs/decisions/waist.md): the waist gyroscope's rate at rest on simulated users 840-859,
clean and with 0.02 rad/s added on the unit's up axis; the warning must fire on no clean and every biased session.

    PYTHONPATH=. .venv/bin/python experiments/waist_still_bias_w105.py [OUT_DIR]
"""

from __future__ import annotations

import logging
import os
import subprocess
import sys

from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.plausibility import still_yaw_rate, still_yaw_rate_message

ROUTE = "stand:3, straight:10, turn:90, straight:5"
USERS = range(840, 860)
BIAS_RPS = 0.02


def _rate(session):
    imu = waist_imu(session)
    return still_yaw_rate(imu.t, imu.acc_nav, imu.gyr_nav, imu.fs)


def _text(r) -> str:
    return "none" if r is None else f"{r[0]:+.5f} ({r[1]:.2f}-{r[2]:.2f} s)"


def main() -> None:
    logging.disable(logging.WARNING)
    root = sys.argv[1] if len(sys.argv) > 1 else "out/w105"
    warned = [0, 0]
    for u in USERS:
        out = os.path.join(root, f"u{u}")
        if not os.path.exists(out):
            subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", ROUTE, "--user-seed", str(u),
                            "--rate", "100", "--pelvis", "realistic", "--out", out], check=True, capture_output=True)
        s = read_session(out)
        r0 = _rate(s)
        g = s["wGyroscope"]
        s.streams["wGyroscope"] = Stream(g.name, g.t, g.values + BIAS_RPS * s.frames["waist"].matrix()[2])
        r1 = _rate(s)
        w = [still_yaw_rate_message(r) is not None for r in (r0, r1)]
        warned = [a + b for a, b in zip(warned, w, strict=True)]
        print(u, "clean", _text(r0), "warn" if w[0] else "-", f"| +{BIAS_RPS}:", _text(r1), "warn" if w[1] else "-",
              flush=True)
    print(f"clean sessions warned: {warned[0]}/{len(USERS)}; biased sessions warned: {warned[1]}/{len(USERS)}")


if __name__ == "__main__":
    main()
