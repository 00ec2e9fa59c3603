"""experiments/step_count.py's real-recordings table (decision steps 42): ``detected`` is every detection,
``scored`` the detections the precision, F1 and count error use, so each row's count error can be checked by hand
as |scored - reference| / reference."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "experiments" / "step_count.py"
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


@pytest.fixture(scope="module")
def step_count():
    spec = importlib.util.spec_from_file_location("pdrlearn_step_count_under_test", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


@pytest.mark.skipif(not WAIST.exists(), reason="datasets/real not present")
def test_real_table_count_error_uses_the_scored_column(step_count):
    from pdrlearn.io import read_session

    s = read_session(WAIST)
    row = step_count.detector_row(s, WAIST.name, "pelvic-gyro")
    # the session has detections outside its labelled bouts: the two counts differ (the trial's 187 vs 63)
    assert row["count"] > row["scored_count"]
    lines = step_count._md_real(pd.DataFrame([row])).splitlines()
    head, cells = _cells(lines[0]), _cells(lines[2])
    got = dict(zip(head, cells, strict=True))
    assert int(got["detected"]) == row["count"] and int(got["scored"]) == row["scored_count"]
    ref, scored = int(got["reference"]), int(got["scored"])
    assert float(got["count error"].rstrip(" %")) == pytest.approx(100 * abs(scored - ref) / ref, abs=0.05)


def test_real_table_detector_error_row_keeps_the_columns(step_count):
    row = {"session": "x", "detector": "accel-force", "note": "DataError: no force"}
    lines = step_count._md_real(pd.DataFrame([row])).splitlines()
    assert len(_cells(lines[0])) == len(_cells(lines[2]))


def test_foot_f1_is_pooled_per_reference_never_across_e161(step_count):
    """Decision E161 (session 34, trial T5 finding 1): the stairs' F1, scored against a rest-based segmentation (no
    timing: not ground truth), is pooled apart from the motion-capture level walks, and the printed table says so."""
    rows = pd.DataFrame([
        {"session": "gaitmap_level_left", "detector": "accel", "reference_count": 29, "scored_count": 30,
         "recall": 1.0, "f1": 0.983, "timing_error_mean_s": 0.015},
        {"session": "gaitmap_level_right", "detector": "accel", "reference_count": 30, "scored_count": 30,
         "recall": 1.0, "f1": 1.0, "timing_error_mean_s": 0.019},
        {"session": "gaitmap_stairs_down_left", "detector": "accel", "reference_count": 19, "scored_count": 19,
         "recall": 1.0, "f1": 1.0, "timing_error_mean_s": float("nan")},
        {"session": "gaitmap_level_left", "detector": "accel-force", "reference_count": None, "scored_count": None,
         "recall": None, "f1": None, "timing_error_mean_s": None}])
    pooled = step_count.foot_pooled(rows).set_index("reference")
    assert pooled.loc["motion capture", "f1"] == pytest.approx(118 / 119)  # 2 x 59 / (60 + 59): not 0.995
    assert pooled.loc["rest-based segmentation (NOT ground truth)", "sessions"] == 1
    text = step_count._md_foot_pooled(rows)
    assert "| shared | motion capture | 2 | 59 | 60 | 0.992 |" in text and "NOT ground truth" in text


def test_demo_table_says_the_stair_f1_is_not_ground_truth_e161():
    spec = importlib.util.spec_from_file_location("pdrlearn_demo_under_test", ROOT / "experiments" / "demo.py")
    demo = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(demo)
    assert "NOT ground truth" in demo.DEMO_F1_ROWS["stairs_steps"]
    assert "motion capture" in demo.DEMO_F1_ROWS["foot_steps"]
    # trial T1 F9 (session 36): the waist row names its detector, the stride-length row its stride point and strides
    assert "PLL detector" in demo.DEMO_F1_ROWS["waist_steps"]
    assert "sensor point" in demo.STRIDE_LENGTH_ROW and "own strides" in demo.STRIDE_LENGTH_ROW
