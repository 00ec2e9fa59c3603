"""Session 40, trial T2 findings 3, 8, 11: a very slow walk's lower-back steps (decisions W440, W441, W442, W444)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.waist.pelvic_rhythm import SLOW_PERIOD_S, local_step_period, merge_dropped, rhythm_keep
from pdrlearn.waist.plausibility import count_mismatch_message, not_alternating_message


def _slow(user: int, length: float, step_s: float, walk_m: float, bounce: str = "pendulum"):
    """A short simulated walk at the given step (W440's users 10880-10899 range), 20 Hz."""
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(user), step_length_m=length / f_len, step_time_s=step_s / f_time)
    return simulate_path([Stand(5), Straight(walk_m), Stand(5)], u, speed="normal", rate_hz=20, seed=user,
                         bounce=bounce)


def test_local_step_period_is_the_median_pelvic_interval_near_each_time_w440():
    g = np.arange(0.0, 20.0, 1.2)  # a pelvic step every 1.2 s
    p = local_step_period(g, np.array([5.0, 10.0, 40.0]))
    assert p[:2] == pytest.approx([1.2, 1.2])
    assert np.isnan(p[2])  # no pelvic step within 3 s: not judged


def test_rhythm_keep_drops_the_extra_contact_farther_from_a_pelvic_step_w440():
    g = np.arange(0.0, 12.0, 1.0)  # pelvic steps at 0, 1, ..., 11 s
    ev = np.array([2.0, 2.45, 3.02, 4.0, 4.3, 5.0, 6.0])  # 2.45 and 4.3 lie inside steps (< 0.6 s after)
    keep = rhythm_keep(ev, np.ones(ev.size, dtype=bool), g)
    assert keep.tolist() == [True, False, True, True, False, True, True]
    early = np.array([2.0, 2.7, 2.98, 4.0])  # the phantom first: the later contact (nearer 3 s) is kept
    assert rhythm_keep(early, np.ones(4, dtype=bool), g).tolist() == [True, False, True, True]
    # a new walking sequence is not judged against the previous one's last contact
    assert rhythm_keep(ev[:2], np.array([False, False]), g).all()
    # a normal rhythm (contacts at the pelvic steps) loses nothing
    assert rhythm_keep(g, np.ones(g.size, dtype=bool), g).all()


def test_slow_value_judges_only_a_rhythm_under_70_steps_per_min_w440():
    ev = np.array([2.0, 2.45, 3.02, 4.0])
    slow = np.arange(0.0, 12.0, 1.0)  # 60 steps/min: judged
    assert not rhythm_keep(ev, np.ones(4, dtype=bool), slow, min_period_s=SLOW_PERIOD_S).all()
    fast = np.arange(0.0, 12.0, 0.8)  # 75 steps/min: not judged with "slow", judged at every cadence
    assert rhythm_keep(ev, np.ones(4, dtype=bool), fast, min_period_s=SLOW_PERIOD_S).all()
    assert not rhythm_keep(ev, np.ones(4, dtype=bool), fast).all()


def test_merge_dropped_extends_the_step_over_the_dropped_contact_w440():
    steps = pd.DataFrame({"start_s": [1.0, 1.4, 2.0, 3.0], "end_s": [1.4, 2.0, 3.0, 3.0],
                          "event_s": [1.0, 1.4, 2.0, 3.0], "has_next": [True, True, True, False],
                          "confidence": [1.0, 1.0, 1.0, 0.5]})
    out = merge_dropped(steps, np.array([True, False, True, False]), "n_rhythm")
    assert out["start_s"].tolist() == [1.0, 2.0]
    assert out["end_s"].tolist() == [2.0, 2.0]  # the first spans to 2.0; the second closes its sequence
    assert out["has_next"].tolist() == [True, False]
    assert out["confidence"].tolist() == [1.0, 0.5]
    assert out.attrs["n_rhythm"] == 2


def test_count_line_is_two_sided_w441():
    more = count_mismatch_message((62, 41))
    assert "W441" in more and "adds contacts inside steps" in more and "62" in more and "41" in more
    fewer = count_mismatch_message((30, 49))
    assert "misses steps" in fewer
    assert count_mismatch_message((45, 41)) is None  # within W99's 30 %
    assert count_mismatch_message(None) is None


def test_not_alternating_line_names_uncountable_small_steps_w442():
    line = not_alternating_message(-0.31, 160, (161, 21))
    assert "W442" in line and "too small or too slow" in line and "not running" in line
    assert "W442" not in not_alternating_message(-0.31, 160, (40, 31))  # not 1.5 x: W98's generic line
    assert "W442" not in not_alternating_message(0.39, 62, (63, 0))  # no pelvic steps (a wheelchair): W98's line


def test_l95_names_no_fast_gait_when_the_count_is_unusable_w442():
    from pdrlearn.track.gait import gait_range_warning

    summary = {"median_cadence_spm": 175.0, "median_speed_mps": 0.30}
    assert "running" in gait_range_warning(summary)
    line = gait_range_warning({**summary, "info": {"step_count_unusable": True}})
    assert "W442" in line and "running" not in line and "short fast steps" not in line


def test_slow_walk_counts_near_the_truth_with_the_rhythm_veto_w440():
    """User 10882 of W440's measurement: 43 steps/min, 0.33 m, pendulum bounce; the seed 003 contacts count
    over twice the truth (80 for 30), the veto ("slow") brings them within 25 % (32)."""
    from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist

    assert OPTION_DEFAULTS["pelvic_rhythm_veto"] is False  # W440: its rule (c) was not met (Test11's step F1 fell)
    s = _slow(10882, 0.15 + 0.25 * 14 / 19, 60 / (40 + 30 * 2 / 19), 10.0)  # as experiments/waist_slow_steps_s40.py
    true = int((s.extras["ics"]["kind"] == "walk").sum())
    on = track_waist(s, pipeline="waist-pendulum", pelvic_rhythm_veto="slow")
    off = track_waist(s, pipeline="waist-pendulum", pelvic_rhythm_veto=False)
    assert len(off.steps) > 2 * true, (len(off.steps), true)
    assert abs(len(on.steps) - true) <= 0.25 * true, (len(on.steps), true)
    assert on.info["n_rhythm_contacts"] == len(off.steps) - len(on.steps)
    assert on.info["n_pelvic_gyro_steps"] is not None
    with pytest.raises(DataError, match="pelvic_rhythm_veto 'fast' is not one of"):
        track_waist(s, pipeline="waist-pendulum", pelvic_rhythm_veto="fast")


def test_tiny_slow_steps_are_named_uncountable_w442():
    """T2 finding 8's gait, a fresh user: 0.1 m every 2 s. The contacts neither alternate nor follow the pelvic
    rhythm: W98's line names the steps as too small or slow to count, with both counts."""
    from pdrlearn.track.waist import track_waist

    r = track_waist(_slow(10895, 0.10, 2.0, 3.0), pipeline="waist-pendulum", pelvic_rhythm_veto="slow")
    lines = [w for w in r.info["warnings"] if "decision W442" in w]
    assert len(lines) == 1, r.info["warnings"]
    assert r.info["step_count_unusable"] is True


def test_freeze_hint_names_slow_shuffling_first_w444():
    """User 10894 of W440's measurement (62 steps/min, 0.39 m, pendulum bounce, no freeze): W395's hint fires; it
    names slow or shuffling walking before freezing."""
    from pdrlearn.track.waist import track_waist

    r = track_waist(_slow(10894, 0.39, 60 / 62, 10.0), pipeline="waist-pendulum")
    lines = [w for w in r.info["warnings"] if "decision W395" in w]
    assert len(lines) == 1, r.info["warnings"]
    assert "most often slow or shuffling walking" in lines[0] and "W444" in lines[0]
    assert lines[0].index("slow or shuffling") < lines[0].index("freezing")
