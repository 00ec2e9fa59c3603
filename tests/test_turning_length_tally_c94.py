"""Decision C94: C89's count of the classifier's length classes on turning strides, on the streamed and run paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.turn_length import TurnTally, disagrees_one
from pdrlearn.track.turn_classes import turning_length_disagreement
from tests.runtime_helpers import replay, svm_user_walk

BOUNDS = {"short": (0.0, 1.0), "normal": (1.0, 1.6), "long": (1.6, 1.8)}


def test_the_one_stride_tally_counts_as_the_offline_table_function():
    assert disagrees_one("long", 1.3, math.radians(45), BOUNDS) is True
    assert disagrees_one("normal", -1.3, math.radians(-45), BOUNDS) is False
    assert disagrees_one("long", 1.3, math.radians(14.9), BOUNDS) is None  # straight (L79)
    assert disagrees_one("long", 1.9, math.radians(90), BOUNDS) is None  # no measured class (R4)
    assert disagrees_one(None, 1.3, math.radians(90), BOUNDS) is None
    rng = np.random.default_rng(8742)
    cls = rng.choice(np.array(["short", "normal", "long", None], dtype=object), 200)
    length = rng.uniform(0.0, 2.0, 200)
    turn = rng.uniform(-1.5, 1.5, 200)
    tally = TurnTally()
    for c, x, t in zip(cls, length, turn, strict=True):
        tally.add(c, x, t, BOUNDS)
    assert (tally.off, tally.compared) == turning_length_disagreement(cls, length, turn, BOUNDS)
    assert tally.classified == sum(isinstance(c, str) for c in cls) and tally.compared > 20


@pytest.fixture(scope="module")
def user_8740(tmp_path_factory):
    """User 8740's SVM on the fused units, its bundle, and walk D (seed 3): its classifier calls about half of D's
    corners a length class their measured length contradicts."""
    return svm_user_walk(tmp_path_factory.mktemp("c94"), 8740)


def _c89(warnings) -> list[str]:
    return [w for w in warnings if "decision C89" in w]


def test_streamed_and_run_print_the_same_c89_line(user_8740):
    """`track --streaming` and the runtime Tracker (`pdrlearn run`) count with the one kernel, on the classifier's
    classes before C88 replaces them: the same line, with C88 on by default (C91)."""
    from pdrlearn.runtime import Tracker
    from pdrlearn.track.plasys import track_plasys

    model, bundle, s = user_8740
    streamed = _c89(track_plasys(s, method="M3", model=model, streaming=True).info.get("warnings", []))
    tr = Tracker(bundle)
    replay(tr, s)
    run = _c89(tr.warnings)
    assert len(streamed) == 1 and run == streamed
    assert "(decision C88)" in run[0]  # C88's default: the line says those strides now take the measured class
    offline = _c89(track_plasys(s, method="M3", model=model).info.get("warnings", []))
    assert len(offline) == 1  # the offline count still fires with C88 on (it counts the classifier's classes)
