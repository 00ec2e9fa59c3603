"""Decision C55 (trial mlres, session 25): the runtime and `track --model` called the first stride of a walking
bout `backward`: the segmenter opens it 0.3 s before the foot's rest ends, ~0.1 s earlier than the label, and the
model had only seen bout starts cut at the labels. Training now cuts a bout's edge strides as the runtime does."""

from __future__ import annotations

import contextlib
import logging

import numpy as np
import pytest

from pdrlearn.classify import detected as D
from pdrlearn.classify.training import session_windows, train_user
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.evaluate import match_by_overlap

USER = 2500  # the trial's user


def _bout_edges(steps):
    start, end = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    opens = np.r_[True, start[1:] > end[:-1] + D.BOUT_GAP_S]
    closes = np.r_[start[1:] > end[:-1] + D.BOUT_GAP_S, True]
    return opens, closes


def test_bout_edges_move_to_the_segmenters_strides_and_nothing_else():
    walk = simulate("terrain", USER, seed=7)
    lab = walk.steps.reset_index(drop=True)
    got = D.runtime_bout_edges(walk, lab)
    opens, closes = _bout_edges(lab)
    assert opens.sum() >= 3  # the walk has several bouts
    seg = D.detected_strides(walk)
    # inner boundaries stay the labels'; every moved bound is a bound of a detected stride
    assert np.array_equal(got["start_s"].to_numpy()[~opens], lab["start_s"].to_numpy()[~opens])
    assert np.array_equal(got["end_s"].to_numpy()[~closes], lab["end_s"].to_numpy()[~closes])
    moved = got["start_s"].to_numpy()[opens]
    assert np.isin(moved, seg["start_s"].to_numpy()).all()
    # the segmenter opens a bout earlier than the labels (trial: 0.10-0.16 s)
    assert (lab["start_s"].to_numpy()[opens] - moved).max() >= 0.08
    # the labels themselves are not changed, nor the other columns
    assert got.drop(columns=["start_s", "end_s"]).equals(lab.drop(columns=["start_s", "end_s"]))
    assert walk.steps["start_s"].to_numpy()[0] == lab["start_s"].iloc[0]


def test_only_training_windows_are_recut():
    walk = simulate("terrain", USER, seed=7)
    train = session_windows([walk], n_samples=40)[0].steps
    ev = session_windows([walk], n_samples=40, purpose="evaluate")[0].steps
    assert np.array_equal(ev["start_s"].to_numpy(), walk.steps["start_s"].to_numpy())
    assert not np.array_equal(train["start_s"].to_numpy(), walk.steps["start_s"].to_numpy())
    rest = session_windows([walk], n_samples=40, boundaries="rest")[0].steps  # rest windows: C13's own cut
    assert np.array_equal(rest["start_s"].to_numpy(), walk.steps["start_s"].to_numpy())


@pytest.mark.parametrize("on", [False, True])
def test_a_bouts_first_stride_is_forward_on_the_runtimes_strides(on):
    from experiments.c55_bout_edges import before_c55

    assert not hasattr(D, "RUNTIME_BOUT_EDGES")  # C55 is the code (decision C162)
    logging.disable(logging.WARNING)
    try:
        with contextlib.nullcontext() if on else before_c55():  # off: the labels' bout edges, as before C55
            calib = [simulate(s, USER, seed=0) for s in ("terrain", "direction")]
            model = train_user(calib, tasks=["direction"], methods=["svm", "nn"], units=["foot"], cv=3,
                               distance_calibration=False)
    finally:
        logging.disable(logging.NOTSET)
    walk = simulate("terrain", USER, seed=7)  # forward only, five bouts
    lab = walk.steps.reset_index(drop=True)
    strides = D.detected_strides(walk)
    pred = model.predict_steps(walk, strides, windows="given", warn_rate=False)["direction"].to_numpy(object)
    opens, _ = _bout_edges(lab)
    firsts = [si for si, li in match_by_overlap(strides, lab, min_iou=D.MIN_IOU) if opens[li]]
    wrong = [si for si in firsts if pred[si] != "forward"]
    if on:
        assert len(firsts) >= 4 and wrong == []
    else:  # what the trial saw: the model trained on the labels' bout starts calls some of them backward
        assert wrong
