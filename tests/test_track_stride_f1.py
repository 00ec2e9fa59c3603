"""Decision L36: foot tracks report ``step_f1`` of their strides against ground-truth strides."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.io import read_session
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def level_right(real_dir):
    return read_session(real_dir / "gaitmap_level_right")


def _result(rows) -> TrackResult:
    steps = pd.DataFrame(rows, columns=["start_s", "end_s"]).assign(length_m=1.0, heading_rad=0.0, unit="foot")
    traj = pd.DataFrame({"t": [0.0], "x": [0.0], "y": [0.0], "z": [0.0]})
    return TrackResult(steps=steps, trajectory=traj, info={})


def test_reference_strides_score_one_and_errors_lower_it(level_right):
    ref = level_right.steps[["start_s", "end_s"]].to_numpy()
    assert evaluate_track(_result(ref), level_right)["step_f1"] == 1.0
    missed = evaluate_track(_result(ref[1:]), level_right)
    assert missed["step_recall"] == pytest.approx(1 - 1 / len(ref)) and missed["step_precision"] == 1.0
    a, b = ref[5]
    extra = [*ref[:5], (a, (a + b) / 2 - 0.3), *ref[5:]]  # a short spurious stride overlapping one labelled
    m = evaluate_track(_result(extra), level_right)
    assert m["step_recall"] == 1.0 and m["step_precision"] == pytest.approx(len(ref) / (len(ref) + 1))
    c, d = a + (b - a) / 3, a + 2 * (b - a) / 3
    split = [*ref[:5], (a, c), (c, d), (d, b), *ref[6:]]  # a turn split at two rests: one stride
    assert evaluate_track(_result(split), level_right)["step_f1"] == 1.0


def test_unlabelled_part_of_a_walk_is_not_scored(level_right):
    ref = level_right.steps[["start_s", "end_s"]].to_numpy()
    before = (ref[0, 0] - 20.0, ref[0, 0] - 19.0)  # far outside the mocap volume's labelled chain
    assert evaluate_track(_result([before, *ref]), level_right)["step_f1"] == 1.0


def test_tracks_of_real_walks_and_no_f1_on_a_detected_segmentation(level_right, real_dir):
    for kw in ({}, {"streaming": True}):
        m = evaluate_track(track_plasys(level_right, method="auto", **kw), level_right)
        assert m["step_f1"] >= 0.98
    stairs = read_session(real_dir / "gaitmap_stairs_up_left")  # steps.csv source=detected: not ground truth
    assert "step_f1" not in evaluate_track(track_plasys(stairs, method="auto"), stairs)
