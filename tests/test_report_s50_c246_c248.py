"""Session 50 (FE), trial s50t3 findings F1 and F7 (docs/decisions/cohort.md): C246 (where W476 withheld a lower
back's step count no report prints the contacts as steps), C247 (nor a stride or a contact CV from them; the speed
and distance flagged) and C248 (a pause is standing: sitting and lying between steps are left out)."""

from __future__ import annotations

import copy

import numpy as np
import pandas as pd
import pytest

from pdrlearn.report.build import STEPS_COLUMN, step_count_columns
from pdrlearn.report.clinical import _normalised, gait_speed_line
from pdrlearn.report.daily_living import daily_living_lines
from pdrlearn.report.spatiotemporal import spatiotemporal_line
from pdrlearn.report.stairs_asymmetry import asymmetry_line
from pdrlearn.report.walking import walking_line
from pdrlearn.waist.plausibility import withhold_step_count

#: trial s50t3's p17401 summary (res/wc/p17401/summary.json), the keys the clinical lines read: W476 withheld it
REASON = ("the 617 waist contacts are over 1.5 x the pelvic-gyro detector's 344 steps (decision W442): no step count, "
          "so median_cadence_spm, median_step_time_s and median_stride_time_s are withheld (decision W476)")
T3 = {"n_steps": 618, "n_steps_counts": "steps of both feet", "n_steps_both_feet": 618, "pipeline": "waist-pendulum",
      "median_stride_length_m": 0.253, "gait_speed_mps": 0.306, "median_cadence_spm": None, "distance_m": 72.47,
      "walking_time_s": 236.9, "time_span_s": 5256.8, "per_s": 3600.0, "leg_length_m": 0.8056,
      "leg_length_source": "meta.json leg_length_m", "step_time_asymmetry_pct": 23.2, "step_time_s_left": 0.305,
      "step_time_s_right": 0.319,
      "stride_time_cv_withheld": {"cause": "lower_back", "reason": "not given on the lower back",
                                  "jitter_free_cv_pct": 42.87, "n_jitter_free_strides": 569},
      "step_count_withheld": REASON, "info": {"n_pelvic_gyro_steps": 344, "params_source": "calibrated",
                                             "step_count_withheld": REASON}}


@pytest.fixture()
def folder(tmp_path):
    pd.DataFrame({"duration_s": [76.0, 23.0], "distance_m": [24.0, 7.1]}).to_csv(tmp_path / "bouts.csv", index=False)
    pd.DataFrame({"n_steps": [422, 196], "n_steps_both_feet": [422, 196]}).to_csv(tmp_path / "periods.csv",
                                                                                  index=False)
    return tmp_path


def _lines(summary, folder) -> str:
    unit = "lower-back unit"
    return "\n".join(x for x in [gait_speed_line(summary, unit), walking_line(summary, folder, unit),
                                 spatiotemporal_line(summary, unit), _normalised(summary, unit, True, True),
                                 asymmetry_line(summary, unit), *daily_living_lines(summary, folder)] if x)


def test_clinical_lines_print_no_contacts_as_steps_c246_c247(folder):
    text = _lines(T3, folder)  # a summary written before C246 (its n_steps_both_feet still 618) reads the same
    assert "618 steps" not in text and "422, 196" not in text and "per hour" not in text
    assert "- Walking: steps not given, 618 contacts (no step count, decision W476; the pelvic gyro counts 344 " \
           "steps)" in text
    assert "- Daily living over 1.5 h recorded: steps not given" in text
    assert "- Steps per 1 h (periods.csv): not given: the lower back's contacts are no step count" in text
    assert "0.25 m" not in text and "42.9" not in text and "stride length / leg" not in text  # C247
    assert "stride-time CV not given: the lower back's contacts are no step count (W476, C247)" in text
    assert "Step-time asymmetry: not given" in text
    assert text.count("from contacts that are no step count (W476): may read high") == 2  # speed and distance
    # the same summary without W476's withholding: its lines as before (the change is W476's alone)
    given = {k: v for k, v in copy.deepcopy(T3).items() if k != "step_count_withheld"}
    text = _lines(given, folder)
    assert "- Walking: 618 steps" in text and "618 steps (423 per hour)" in text and ": 422, 196" in text
    assert "stride length 0.25 m" in text and "42.9" in text and "may read high" not in text


def test_summary_and_report_table_withhold_the_steps_c246_c247():
    s = withhold_step_count(copy.deepcopy(T3))
    assert s["n_steps_both_feet"] is None and s["median_stride_length_m"] is None and s["n_steps"] == 618
    assert s["stride_time_cv_withheld"]["jitter_free_cv_pct"] is None
    assert s["stride_time_cv_withheld"]["n_jitter_free_strides"] is None
    df = step_count_columns(pd.DataFrame([{**T3, "info": None}, {**T3, "info": None, "step_count_withheld": None}]))
    assert pd.isna(df[STEPS_COLUMN].iloc[0]) and df[STEPS_COLUMN].iloc[1] == 618


@pytest.fixture(scope="module")
def tracked():
    """A 20 Hz lower-back walk with a 6 s stop, tracked once (waist-pendulum)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.base import get_pipeline

    s = simulate_path(parse_route("stand:2, straight:8, stand:6, straight:8, stand:2"), UserProfile.from_seed(17570),
                      rate_hz=20, seed=0)
    return s, get_pipeline("waist-pendulum")(s)


def test_periods_csv_withholds_the_contacts_counts_c246(tracked):
    from pdrlearn.track.periods import PERIOD_WITHHELD_KEYS, period_table

    s, result = tracked
    before = period_table(result, s, 3600.0, unit="waist", bouts=None, turns=None)
    assert before["n_steps_both_feet"].iloc[0] > 0 and before["median_cadence_spm"].notna().all()
    result.info["step_count_unusable"] = True
    try:
        after = period_table(result, s, 3600.0, unit="waist", bouts=None, turns=None)
    finally:
        result.info["step_count_unusable"] = False
    assert after[list(PERIOD_WITHHELD_KEYS)].isna().all().all()
    assert (after["n_steps"] == before["n_steps"]).all()  # W476: n_steps stays steps.csv's rows


def test_pauses_leave_out_sitting_and_lying_c248(tracked):
    from pdrlearn.track.clinical import clinical_summary, pause_spans, standing_pauses

    _, result = tracked
    steps = result.steps
    span = pause_spans(steps)
    assert len(span) == 1 and span[0, 1] - span[0, 0] > 4.0
    a, b = span[0]
    plain = clinical_summary(steps)
    assert plain["n_pauses"] == 1 and plain["pause_seated_lying_s"] is None
    standing = clinical_summary(steps, postures=[[a - 20.0, b + 20.0, "standing"]])
    assert standing["n_pauses"] == 1 and standing["pause_time_s"] == pytest.approx(plain["pause_time_s"])
    part = clinical_summary(steps, postures=[[a, a + 2.0, "sitting"], [a + 2.0, b, "standing"]])
    assert part["n_pauses"] == 1 and part["pause_time_s"] == pytest.approx(plain["pause_time_s"] - 2.0)
    assert part["longest_pause_s"] == pytest.approx(plain["longest_pause_s"] - 2.0)
    assert part["pause_seated_lying_s"] == pytest.approx(2.0)
    seated = clinical_summary(steps, postures=[[a - 1.0, b - 0.5, "lying"]])
    assert seated["n_pauses"] == 0 and seated["pause_time_s"] == 0.0
    assert seated["n_walking_bouts"] == plain["n_walking_bouts"]  # a sit still separates two bouts
    left, cut = standing_pauses(np.array([[0.0, 10.0], [20.0, 22.0]]), [[1.0, 9.5, "sitting"], [0.0, 30.0, "x"]])
    assert left.tolist() == [1.5, 2.0] and cut == pytest.approx(8.5)


def test_track_walk_line_names_the_seated_seconds_c248():
    from pdrlearn.cli.common import walk_line

    s = {"n_walking_bouts": 2, "n_bouts": 2, "n_pauses": 1, "pause_time_s": 12.0, "pause_seated_lying_s": 600.0,
         "turn_count": 0}
    assert "1 pause(s) of >= 1 s standing (12.0 s in all; 600.0 s sitting or lying between steps left out, C248)" \
        in walk_line(s)
    assert "1 pause(s) of >= 1 s (12.0 s in all)" in walk_line({**s, "pause_seated_lying_s": None})
    cv = {"stride_time_cv_withheld": {"cause": "lower_back", "jitter_free_cv_pct": None}, "step_count_withheld": "x"}
    assert ", no stride-time CV (the lower back's contacts are no step count; docs/decisions/waist.md W476; " \
           "docs/decisions/cohort.md C247)" in walk_line({**s, **cv})  # C247: track's line, as clinical.md's
