"""Decision L674 (docs/decisions/localization.md): a hole in a stride's foot samples gives it no classes and no
height change.

Trial T2 (session 45, F6): a 120 ms hole (100 Hz) inside a swing gave a confident "down" stride with dz -0.46 m on flat
ground, live and in `pdrlearn run` alike (B11 / E36 take the classes only over 0.25 s). A stride whose foot
accelerometer / gyroscope samples have an interval over 2.5 of their median interval (two samples lost or more) now has
no classes and dz 0 m, its length kept, in the runtime and `track --streaming` (review R3 F1, FM: the height change
of the clean stride before it instead of 0 m).
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.window import SWING_GAP_INTERVALS, stride_hole
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import holed_chunks, synthetic_session

#: the synthetic swing of step k lies in [k + 0.4, k + 1.0) s (stance 0.4 s, swing 0.6 s); samples of 5.65-5.75 s
#: (three at 20 Hz) are lost, the interval 5.60-5.80 s is four of the stream's
HOLE = (5.62, 5.78)


def test_the_kernel_finds_a_hole_of_two_lost_samples_and_not_one():
    t = np.round(np.arange(0.0, 2.0, 0.05), 6)
    assert stride_hole(t, 0.2, 1.8) == 0.0
    one = np.delete(t, 10)  # one sample lost: an interval of 2 sample intervals
    assert stride_hole(one, 0.2, 1.8) == 0.0
    two = np.delete(t, [10, 11])  # two lost: 3 intervals, over SWING_GAP_INTERVALS
    assert 3 * 0.05 > SWING_GAP_INTERVALS * 0.05
    assert stride_hole(two, 0.2, 1.8) == pytest.approx(0.15)
    assert stride_hole(two, 0.8, 1.8) == 0.0  # outside the stride (and its covering samples)


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(12, seed=12831, name="walk")


def _push(bundle, walk, hole=None):
    tr, steps = Tracker(bundle), []
    for chunk in holed_chunks(walk, 0.5, hole, ("fAccelerometer", "fGyroscope")):
        steps += tr.push(chunk)
    return steps + tr.flush(), tr.warnings


def test_a_stride_with_a_hole_in_its_swing_has_no_classes_and_no_height_change(synthetic_bundle, walk):
    clean, _ = _push(synthetic_bundle, walk)
    got, warnings = _push(synthetic_bundle, walk, HOLE)
    assert len(got) == len(clean)
    hit = [i for i, st in enumerate(got) if st.start_s < HOLE[0] and st.end_s > HOLE[1]]
    assert len(hit) == 1
    st, ref = got[hit[0]], clean[hit[0]]
    assert ref.classes and ref.dz_m != 0.0  # the same stride whole: classed, with its integrated height
    # review R3 F1 (FM): the height change of the clean stride before it (L674's 0 m flattened stairs)
    assert st.classes == {} and st.dz_m == got[hit[0] - 1].dz_m and st.gap_s == 0.0 and st.length_m != 0.0
    assert sum("decision L674" in w for w in warnings) == 1
    others = [i for i in range(len(got)) if i != hit[0]]
    assert all(got[i].classes == clean[i].classes for i in others)
