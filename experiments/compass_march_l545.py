"""Decision L545's adoption measurement (run once; the rule is in docs/decisions/localization.md): L544 narrowed to
L264's windows against "today" (before L544) and clean-compass tracking, on fresh simulated users 10852-10859, with
L544's runner (``compass_march_l544.run_part``). Offline, no model. Prints; changes nothing on disk but a temporary
folder.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_march_l545.py``
"""

from __future__ import annotations

import logging
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the navigation trial's R1 (L226)
from compass_march_l544 import run_part  # noqa: E402  L544 runner (today, candidate, clean-compass)
from compass_window_shift import LOOP, SHORT  # noqa: E402  L264 routes
from pdrlearn.track.evaluate import STOREY_HEIGHT_M  # noqa: E402

LONG_MARCH = ("straight:2000:fast, slope:800:6, curve:90:50, straight:1500, slope:800:-6, "
              "straight:1000:slow")


def main() -> None:
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l545_"))
    r1x2 = ", ".join([R1] * 2)
    run_part(tmp, "(a) long march", LONG_MARCH, range(10852, 10855), STOREY_HEIGHT_M, clean=True)
    run_part(tmp, "(b) R1x2 30uT", r1x2, range(10855, 10860), 2.89, ("--mag-disturbance", "30"))
    run_part(tmp, "(b) loop 30uT", LOOP, range(10855, 10860), STOREY_HEIGHT_M, ("--mag-disturbance", "30"))
    run_part(tmp, "(c) short 0", SHORT[0], range(10855, 10860), STOREY_HEIGHT_M)
    run_part(tmp, "(c) short loop", SHORT[1], range(10855, 10860), STOREY_HEIGHT_M)
    run_part(tmp, "(c) straight1000", "straight:1000", range(10855, 10857), STOREY_HEIGHT_M, clean=True)


if __name__ == "__main__":
    main()
