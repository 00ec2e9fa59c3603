"""Decision 29 of docs/decisions/steps.md: W23 (no weight shift, no step) suspended while the pelvis turns
(`InitialContactDetector(turn_shift_rps=0.45)`), measured against its adoption rule (written before this ran).

Scored as decision 28 (`experiments/waist_ic_turn_gate.py`, whose `measure` this runs): Test11 and Test5 of
the mobgap subjects with `score_steps` (as `pdrlearn steps --detector waist-ic`), the simulator (A-D x
slow/normal/fast x users 1-3, 100 Hz, model and realistic pelvis) with `score_events`; the fresh TUG walks of W72
(users 160-179, 20 and 100 Hz; rule (e)).

Run: PYTHONPATH=$PWD python experiments/waist_ic_turn_shift.py [--external datasets/external] [--sim-users 3]
"""

from __future__ import annotations

from waist_ic_turn_gate import measure

TURN_SHIFT_RPS = 0.45  # decision 29 = decision 28: DEFAULT_TURN_GMM turning mean (W7)


def main() -> None:
    # rule (e): fresh TUG walks (W72's route, users not used before)
    measure(__doc__, {"turn_shift_rps": TURN_SHIFT_RPS}, range(160, 180), tug_rule=True)


if __name__ == "__main__":
    main()
