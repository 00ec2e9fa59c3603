"""Decision L325: ``track --rules thesis`` warns when the length-class clamp sets strides to more than twice their
measured length and they add more than 5 % to the distance (trial 31 finding 4: 0.70 m slow strides classed long
were set to 1.62 m, +96 % distance, with only L95's generic line)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.displace.rules import DOUBLED_SHARE, doubled_lengths_line
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.plasys import track_plasys


def test_doubled_lengths_line_counts_the_strides_and_the_added_distance():
    raw = np.array([0.7] * 10 + [1.2] * 10)
    ruled = np.r_[np.full(10, 1.6), np.full(10, 1.2)]
    line = doubled_lengths_line(raw, ruled, ["long"] * 10 + ["normal"] * 10)
    assert line.startswith("the thesis length-class rule (--rules thesis) set 10 of 20 strides to more than 2x")
    assert "(10 long; measured median 0.70 m, set to median 1.60 m), adding 9.0 m (+47 % of the measured 19.0 m)" \
        in line and line.endswith("(decision L325)")
    assert doubled_lengths_line(raw, raw * 1.9, ["long"] * 20) is None  # under 2x: no line
    one = np.r_[0.1, np.full(19, 1.2)]  # one turn stride clamped up: +1.1 m of 22.9 m, under the share
    assert 1.1 / one.sum() < DOUBLED_SHARE and doubled_lengths_line(one, np.r_[1.2, one[1:]], ["normal"] * 20) is None


@pytest.fixture(scope="module")
def walk_and_model():
    cal = simulate("length", user_seed=6142, seed=0)
    return simulate("length", user_seed=6142, seed=5), train_user([cal], tasks=["length"], methods=["svm"],
                                                                 units=["foot"], cv=3)


def test_track_rules_thesis_warns_when_the_classes_double_the_strides(walk_and_model):
    s, model = walk_and_model
    lines = lambda res: [w for w in res.info["warnings"] if "decision L325" in w]  # noqa: E731
    assert not lines(track_plasys(s, model=model, rules="thesis"))  # the user's own gait: the classes agree
    far = {"short": (2.5, 3.0), "normal": (3.0, 3.5), "long": (3.5, 10.0)}  # every class > 2x a stride
    assert len(lines(track_plasys(s, model=model, rules="thesis", bounds=far))) == 1
    assert not lines(track_plasys(s, model=model, rules="bayes", bounds=far))  # bayes weighs the measurement
