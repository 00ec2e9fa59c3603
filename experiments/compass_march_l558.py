"""Decision L558's adoption measurement (run once; the rule is in docs/decisions/localization.md): L545's candidate
(in L264's windows no hard-iron offset where the headings do not spread, a heading offset that drifts linearly) with
a walk of one window fitted as L182's one fit, against "today" (the windows as L264 fits them) and clean-compass
tracking (``compass_fallback=False``), with L544's runner (``compass_march_l544.run_part``: "candidate" is
``windowed_disagreement(drift=True)``). Fresh simulated users 11120-11139 and L544's users 10840-10851. Offline, no
model. Prints; changes nothing on disk but a temporary folder.

If L558 is adopted (L559) the windows always do this and a rerun compares the rule with itself.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_march_l558.py [first_part [end_part]]``
"""

from __future__ import annotations

import logging
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the navigation trial's R1 (L226)
from compass_march_l544 import MARCH, run_part  # noqa: E402  march and runner (L544)
from compass_march_l545 import LONG_MARCH  # noqa: E402  the ~70 min march (L545)
from compass_window_shift import LOOP, ROUTE1, SHORT  # noqa: E402  routes (L264)
from pdrlearn.track.evaluate import STOREY_HEIGHT_M  # noqa: E402

D30 = ("--mag-disturbance", "30")


def parts(tmp: Path) -> list[tuple]:
    """L558's parts in order: (args, kwargs) of ``run_part``; fresh users first, then L544's for the same part."""
    r1x2 = ", ".join([R1] * 2)
    sh = STOREY_HEIGHT_M
    return [
        ((tmp, "(a) long march", LONG_MARCH, range(11120, 11123), sh), {"clean": True}),
        ((tmp, "(a) march L544", MARCH, range(10840, 10844), sh), {"clean": True}),
        ((tmp, "(a) straight1000", "straight:1000", [11123, 11124, 10844, 10845], sh), {"clean": True}),
        ((tmp, "(b) R1x2 30uT", r1x2, [*range(11125, 11131), *range(10846, 10852)], 2.89, D30), {}),
        ((tmp, "(b) loop 30uT", LOOP, [*range(11125, 11131), *range(10846, 10852)], sh, D30), {}),
        ((tmp, "(b) shift route1 30uT", ROUTE1, [11131, 11132, 10850, 10851], sh, D30), {}),
        ((tmp, "(c) short 0", SHORT[0], [*range(11133, 11139), *range(10846, 10852)], sh), {}),
        ((tmp, "(c) short loop", SHORT[1], [*range(11133, 11139), *range(10846, 10852)], sh), {}),
        ((tmp, "(d) R1x2 3uT", r1x2, [*range(11133, 11139), *range(10846, 10852)], 2.89), {}),
        ((tmp, "(d) shift route1", ROUTE1, [11139, 10850, 10851], sh), {"clean": True}),
    ]


def main(start: int = 0, end: int | None = None) -> None:
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l558_"))
    for a, k in parts(tmp)[start:end]:
        run_part(*a, **k)


if __name__ == "__main__":
    main(*(int(x) for x in sys.argv[1:3]))
