"""Session 38: one timestamp-order check (pdrlearn.kernels.order) shared by the live waist tracker (E203), the
sensor pairing (E204), the runtime's input stage and tracker, the online detectors and ``pdrlearn split`` (B380);
each caller keeps its own one-line message."""

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.order import first_out_of_order


def test_first_out_of_order_strict_and_not():
    assert first_out_of_order([1.0, 2.0, 3.0]) is None
    assert first_out_of_order([1.0, 2.0, 2.0, 1.0]) == 2  # a repeat does not increase
    assert first_out_of_order([1.0, 2.0, 2.0, 1.0], strict=False) == 3  # only the step back
    assert first_out_of_order([1.0, 2.0], last=1.0) == 0 and first_out_of_order([1.0, 2.0], 1.0, strict=False) is None
    assert first_out_of_order([0.5], last=1.0, strict=False) == 0
    assert first_out_of_order([], last=5.0) is None and first_out_of_order(np.zeros((0,)), -math.inf) is None


def test_callers_keep_their_lines():
    from pdrlearn.io.split import _check_sorted
    from pdrlearn.runtime.pairing import SensorPair

    pair = SensorPair()
    pair.push_acc([0.0, 0.01, 0.01], np.zeros((3, 3)))  # a repeat is kept (E204)
    with pytest.raises(DataError, match=r"SensorPair.push_acc: timestamps must not go back \(seconds\): sample 0 of "
                                        r"this push \(t=0.005000 s\) is before the previous push's last "
                                        r"\(t=0.010000 s\); push each stream in time order"):
        pair.push_acc([0.005], np.zeros((1, 3)))
    _check_sorted("f.csv", np.array([1.0, 1.0, 2.0]), 0.0, 2)  # a repeat is no error for split (B380)
    with pytest.raises(DataError, match=r"f.csv: timestamps are not sorted \(line 4 is earlier than the line before"):
        _check_sorted("f.csv", np.array([1.0, 2.0, 1.5]), 0.0, 2)
