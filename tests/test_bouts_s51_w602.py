"""Decisions W602 / W603 / C254 (session 51, FI, trial s51t3 findings F2, F3, F10): a lower-back bout's cadence over
its inner steps (the edge contacts are read inward); ``n_steps_with_turns`` (W331's turning steps on the spot beside
n_steps) in summary.json, periods.csv, the console and clinical.md; the daily-living block from 30 min."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.common import count_phrase
from pdrlearn.report.daily_living import daily_living_lines
from pdrlearn.track.bouts import detected_bouts, step_terms
from pdrlearn.waist.turn_steps import stepless_steps, stepless_summary, steps_with_turns
from tests.test_clinical_s45_c180 import lower_back_steps  # C180's hand-made lower-back step table

#: two bouts as the lower back reads them: 0.5 s steps, the first contact 0.1 s late and the closing one 0.2 s early
#: (a 6-contact bout, true cadence 120), and a 3-contact bout
BOUT = [0.1, 0.5, 1.0, 1.5, 2.0, 2.3]
SHORT = [10.1, 10.5, 10.8]


def test_a_lower_back_bout_cadence_leaves_its_edge_steps_out_w602():
    st = lower_back_steps([*BOUT, *SHORT], length=0.6)
    before, after = detected_bouts(st, edge_steps="all"), detected_bouts(st)
    # L164 over all steps: 5 intervals in 2.2 s = 136.4 spm; W602: 3 inner intervals in 1.5 s = 120
    assert before["cadence_spm"].iloc[0] == pytest.approx(60 * 5 / 2.2)
    b = after.iloc[0]
    assert (b["n_step_intervals"], b["contact_span_s"], b["cadence_spm"]) == (3, pytest.approx(1.5), pytest.approx(120))
    assert (b["start_s"], b["end_s"], b["n_steps"]) == (before["start_s"].iloc[0], 2.3, 6)  # the bout's edges stay
    s = after.iloc[1]  # 3 contacts: no inner step, no cadence
    assert (s["n_step_intervals"], s["contact_span_s"]) == (0, 0.0) and np.isnan(s["cadence_spm"])
    assert before["cadence_spm"].notna().all()
    with pytest.raises(ValueError, match="W602"):
        detected_bouts(st, edge_steps="middle")


def test_step_terms_leave_out_the_steps_beside_a_turn_gap_w602():
    ic = np.array([0.0, 0.5, 1.0, 1.5, 5.0, 5.5, 6.0, 6.5])
    filled = np.array([False, False, False, True, False, False, False])
    assert step_terms(ic, filled, inner=False) == (pytest.approx(3.0), 6)
    assert step_terms(ic, filled, inner=True) == (pytest.approx(1.0), 2)  # 0.5-1.0 and 5.5-6.0 only
    assert step_terms(ic[:3], filled[:2], inner=True) == (0.0, 0)


def test_a_foot_bout_keeps_all_its_strides_w602():
    t = np.arange(0.0, 6.0, 1.0)
    foot = pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t, "length_m": 1.2, "unit": "foot"})
    a, b = detected_bouts(foot, edge_steps="all"), detected_bouts(foot)
    pd.testing.assert_frame_equal(a, b)


#: a stand with a slow turn on the spot that holds no contact (W331)
def _turn(a, b):
    return {"start_s": a, "end_s": b, "start_5_s": a, "end_95_s": b, "angle_deg": 180.0, "peak_dps": 60.0}


def test_steps_with_turns_kernel_w603():
    ev = [*np.arange(0.0, 5.0, 0.5), *np.arange(10.0, 15.0, 0.5)]
    turns = [_turn(6.0, 8.0)]
    assert stepless_steps(ev, turns) == [(7.0, 4)]
    assert stepless_summary(ev, turns) == {"stepless_turns": 1, "turn_steps_missed": 4}
    assert steps_with_turns(20, 4) == 24 and steps_with_turns(20, 0) == 20
    assert steps_with_turns(20, None) is None and steps_with_turns(20, 4, withheld=True) is None
    assert stepless_steps(ev, None) is None and stepless_steps(ev[:3], turns) is None  # a foot track; too few steps


@pytest.fixture(scope="module")
def tracked():
    """A 20 Hz lower-back walk with a 6 s stand, tracked once (waist-pendulum), a stepless turn put in the stand."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.base import get_pipeline

    s = simulate_path(parse_route("stand:2, straight:8, stand:6, straight:8, stand:2"), UserProfile.from_seed(18549),
                      rate_hz=20, seed=0)
    result = get_pipeline("waist-pendulum")(s)
    ev = np.sort(result.steps["event_s"].to_numpy(float))
    k = int(np.argmax(np.diff(ev)))
    mid = 0.5 * (ev[k] + ev[k + 1])
    result.info["yaw_turns"] = [_turn(mid - 1.5, mid + 1.5)]
    return s, result, mid


def test_summary_and_periods_give_the_steps_with_turns_w603(tracked):
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.periods import period_table

    s, result, mid = tracked
    summary = track_summary(result, s, pipeline="waist-pendulum")
    missed = summary["turn_steps_missed"]
    assert missed >= 2 and summary["n_steps_with_turns"] == summary["n_steps"] + missed
    per = period_table(result, s, 5.0, unit="waist", bouts=None, turns=None)
    added = per["n_steps_with_turns"] - per["n_steps"]
    assert added.sum() == missed and added[(per["start_s"] <= mid) & (per["end_s"] > mid)].sum() == missed
    assert f"{summary['n_steps']} steps (~{summary['n_steps_with_turns']} with the turning steps" in count_phrase(
        summary)
    result.info["step_count_unusable"] = True  # W476: no step count, so none with the turns either
    try:
        assert period_table(result, s, 5.0, unit="waist", bouts=None, turns=None)["n_steps_with_turns"].isna().all()
    finally:
        result.info.pop("step_count_unusable")


def test_daily_living_from_30_min_with_the_turning_steps_c254_w603(tmp_path):
    pd.DataFrame({"n_steps": [1500, 1400], "n_steps_both_feet": [1500, 1400],
                  "n_steps_with_turns": [1560, 1430]}).to_csv(tmp_path / "periods.csv", index=False)
    s = {"pipeline": "waist-pendulum", "time_span_s": 3545.0, "n_steps": 2900, "n_steps_counts": "steps of both feet",
         "n_steps_both_feet": 2900, "n_steps_with_turns": 2990, "median_cadence_spm": 105.0, "per_s": 1800.0}
    lines = daily_living_lines(s, tmp_path)  # a 59-min shift: W448's 1 h bound gave none (C254)
    assert lines[0].startswith("- Daily living over 59 min recorded: 2900 steps (2945 per hour); ~2990 steps (3036 "
                               "per hour) with the turning steps on the spot"), lines[0]
    assert lines[-1].endswith(": 1500, 1400; with the turning steps on the spot (W603): 1560, 1430"), lines[-1]
    assert daily_living_lines({**s, "time_span_s": 1799.0}, tmp_path) == []
    no_turns = {**s, "n_steps_with_turns": 2900}
    assert "turning" not in daily_living_lines(no_turns, tmp_path)[0]
