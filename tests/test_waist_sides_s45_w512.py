"""Decision W512: the lower back's per-side step times and step-time index leave out turning steps and steps over
1.5 median steps (trial T3 finding F2: the step out of each turn on the spot lands on the same foot, so symmetric
walkers read the left step longer and 2 of 5 "asymmetric")."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.clinical import leg_summary, rhythm_step_times


def _walkway(step_s: float = 0.57, turn_long_s: float = 1.3, turn_short_s: float = 0.42) -> pd.DataFrame:
    """Three passes of 16 contacts alternating right / left at ``step_s``, one walking sequence; between passes a
    turn on the spot: a short turning step onto the right foot, then a long one out of the turn onto the left (the
    pipeline flags the turn's step, not the one out of it), then back in rhythm."""
    t, side, turning = [0.0], ["right"], [0]
    for p in range(3):
        for _ in range(15):
            t.append(t[-1] + step_s)
            side.append("left" if side[-1] == "right" else "right")
            turning.append(0)
        if p < 2:  # the last contact of a pass is a left one: the turn steps onto the right, then the left
            turning[-1] = 1  # a row is the step from its contact to the next: the short step is turning
            for dt, sd in ((turn_short_s, "right"), (turn_long_s, "left"), (step_s, "right")):
                t.append(t[-1] + dt)
                side.append(sd)
                turning.append(0)
    t = np.array(t)
    return pd.DataFrame({"start_s": t, "end_s": np.append(t[1:], t[-1]), "event_s": t, "unit": "waist",
                         "side": side, "turning": turning, "has_next": [True] * (len(t) - 1) + [False],
                         "length_m": 0.7})


def test_turn_steps_leave_the_per_side_step_times_and_the_index():
    st = _walkway()
    s = leg_summary(st)
    assert s["step_time_s_left"] == pytest.approx(0.57) and s["step_time_s_right"] == pytest.approx(0.57)
    assert s["step_time_asymmetry_raw_pct"] == pytest.approx(0.0, abs=1e-6)
    step, _, _ = rhythm_step_times(st)
    assert np.isnan(step).sum() == 4 + 1  # two turns' short and long steps, and the last contact's (no next)


def test_without_a_turning_flag_only_the_long_steps_leave():
    st = _walkway().drop(columns="turning")
    s = leg_summary(st)
    assert s["step_time_s_left"] == pytest.approx(0.57)  # the 1.3 s steps out of the turns left out
    assert s["step_time_s_right"] < 0.57  # the short turning steps stay without the flag
