"""Decision L500's cases (docs/decisions/localization.md): the foot track's walking bouts and pauses with L500's
rhythm (movements, bound only when the intervals are mostly stands), on simulated users 9800-9817 (L482's
stop-and-go routes and slow continuous walks at 0.15-0.4 m/s) and the real recordings of datasets/real (a check, not
tuned on).

L500 was adopted (L501); W413 removed the module switches, so this prints the rule as it is. L501's measurement
against L104's median alone and L482's bound ran with ``clinical.STRIDE_WINDOW_RHYTHM`` / ``RHYTHM_MOVEMENTS``,
which commit d3ffb129 holds (``git show d3ffb129:experiments/slow_walk_pauses_l500.py``)."""

from __future__ import annotations

import logging
import sys

from stopgo_pauses_l482 import ONE_STEP, SG1, real, run_cases  # noqa: E402

logging.disable(logging.WARNING)  # the slow walks' L95 speed lines
SLOW_ROUTE = "stand:3, straight:10, stand:3"
#: (speed label, step length m, step time s): 0.15-0.4 m/s
SPEEDS = [("0.15", "0.24", "1.6"), ("0.18", "0.25", "1.4"), ("0.20", "0.25", "1.25"), ("0.30", "0.3", "1.0"),
          ("0.40", "0.3", "0.75")]
CASES = ([(u, "sg1", SG1, [], (8, 7)) for u in range(9800, 9804)]
         + [(u, "one-step", ONE_STEP, [], (6, 5)) for u in range(9804, 9808)]
         + [(9808 + 2 * i + k, f"{v} m/s", SLOW_ROUTE, ["--step-length", sl, "--step-time", stt], None)
            for i, (v, sl, stt) in enumerate(SPEEDS) for k in range(2)])


def main() -> None:
    right, paused = run_cases(CASES)
    print(f"stop-and-go users right under L500: {right} of 8; slow walks with a pause: {paused} of 10", flush=True)
    real()


if __name__ == "__main__":
    sys.exit(main())
