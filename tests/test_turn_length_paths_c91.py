"""Decision C91: C88's measured length class for turning strides on every path (offline, streamed, run)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels import turn_length
from pdrlearn.kernels.turn_length import measured_class_one, turn_length_class_one
from pdrlearn.track.evaluate import match_by_overlap
from tests.runtime_helpers import svm_user_walk

BOUNDS = {"short": (0.0, 1.0), "normal": (1.0, 1.6), "long": (1.6, 10.0)}


def test_one_stride_kernel_replaces_only_a_classified_turning_stride():
    p = {"short": 0.1, "normal": 0.1, "long": 0.8}
    assert turn_length.TURN_LENGTH_RULE is True  # C88 adopted once every path applies it (C91)
    assert measured_class_one(-1.2, BOUNDS) == "normal" and measured_class_one(11.0, BOUNDS) is None
    assert turn_length_class_one("long", p, 1.3, math.radians(45), BOUNDS) == (
        "normal", {"short": 0.0, "normal": 1.0, "long": 0.0})
    # straight (L79): kept; decision C191: 1.55 m lies within 5 % of long's 1.6 m, no contradiction by the margin
    assert turn_length_class_one("long", p, 1.55, math.radians(-14.9), BOUNDS) == ("long", p)
    assert turn_length_class_one(None, None, 1.3, math.radians(90), BOUNDS) == (None, None)  # no class: none
    assert turn_length_class_one("long", p, 11.0, math.radians(90), BOUNDS) == ("long", p)  # outside every bound
    assert turn_length_class_one("long", None, 1.55, math.nan, BOUNDS) == ("long", None)  # no turn: straight (C191)


@pytest.fixture(scope="module")
def user_8653(tmp_path_factory):
    """User 8653's SVM on the fused units (L38's parity model), its bundle, and walk D (seed 3)."""
    return svm_user_walk(tmp_path_factory.mktemp("c91"), 8653)


def _run(bundle, s) -> pd.DataFrame:
    from experiments.turn_length_paths_c91 import run_steps

    return run_steps(bundle, s)


def test_streamed_and_run_give_turning_strides_the_same_measured_class(user_8653, monkeypatch):
    """`track --streaming` and the runtime Tracker (`pdrlearn run`) apply C88 with the one kernel: the same length
    class on every matched stride, and the run changes the classifier's class of turning strides only."""
    from pdrlearn.track.plasys import track_plasys

    model, bundle, s = user_8653
    st = track_plasys(s, method="M3", model=model, streaming=True).steps
    on = _run(bundle, s)
    monkeypatch.setattr(turn_length, "TURN_LENGTH_RULE", False)
    off = _run(bundle, s)
    assert len(on) == len(off)
    pairs = match_by_overlap(st, on, min_iou=0.5)
    assert len(pairs) >= 0.95 * len(on)
    a, b = st["length_class"].to_numpy(object), on["length_class"].to_numpy(object)
    assert all(a[i] == b[j] for i, j in pairs)
    changed = on["length_class"].to_numpy(object) != off["length_class"].to_numpy(object)
    assert changed.sum() >= 3  # the classifier called some corners wrong; the measured length put them right
    turn = np.abs(on["turn_angle_rad"].to_numpy(float)) + np.abs(on["pivot_rad"].to_numpy(float))
    assert (turn[changed] >= math.radians(10)).all()  # only strides that turn (the heading unit's turn, ~ the foot's)


def test_offline_and_streamed_agree_on_the_turning_strides_classes(user_8653):
    """L38's parity (>= 95 % of the strides the same class) on D's turning strides, with C88 on both paths."""
    from pdrlearn.track.plasys import track_plasys

    model, _, s = user_8653
    off = track_plasys(s, method="M3", model=model).steps
    st = track_plasys(s, method="M3", model=model, streaming=True).steps
    turn = np.abs(np.nan_to_num(off["turn_angle_rad"].to_numpy(float))) >= turn_length.STRAIGHT_MAX_RAD
    pairs = [(i, j) for i, j in match_by_overlap(off, st, min_iou=0.5) if turn[i]]
    assert len(pairs) >= 15
    a, b = off["length_class"].to_numpy(object), st["length_class"].to_numpy(object)
    assert np.mean([a[i] == b[j] for i, j in pairs]) >= 0.95
