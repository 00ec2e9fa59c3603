"""Decision W273: experiments/waist_bout_error_w273.py reads INDIP's bout ``Length`` as one foot's finite stride sum
and prices that foot's strides without a length (``ref_nan``). Hand-made strides, hand-computed values."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
from waist_bout_error_w273 import length_by_foot  # noqa: E402

IC = np.arange(7) * 0.5  # contacts left, right, left, ... : left at 0, 1, 2, 3 s (3 strides), right 2 strides
FOOT = np.array(["left", "right"] * 4)[:7]


def _session(lengths, untimed=None):
    """Strides contact i -> i + 2 with the given lengths (NaN = INDIP gave none); ``untimed`` = the foot of one more
    contact INDIP could not time (its bordering strides are not in steps.csv, X2)."""
    steps = pd.DataFrame({"start_s": IC[:-2], "end_s": IC[2:], "ic_s": IC[:-2], "foot": FOOT[:-2],
                          "length_m": lengths, "wb_id": 0})
    extras = {"ics": pd.DataFrame({"wb_id": 0, "ic_s": IC, "foot": FOOT})}
    if untimed is not None:
        extras["ics_untimed"] = pd.DataFrame({"wb_id": [0], "after_s": [1.0], "before_s": [1.5], "foot": [untimed]})
    return SimpleNamespace(steps=steps, extras=extras)


def test_length_is_the_left_foot_sum_with_every_stride_measured():
    s = _session([1.0, 0.9, 1.0, 0.9, 1.0])  # left 3.0 m, right 2.7 m
    f = length_by_foot(s, 0, 0.0, 3.0, 3.0)
    assert (f["foot"], f["ref_nan_m"], f["l_finite/strides"], f["r_finite/strides"]) == ("left", 0.0, "3/3", "2/2")
    assert f["closest"] == pytest.approx(0.0)


def test_a_left_stride_without_length_is_priced_at_the_foot_mean():
    s = _session([1.0, 0.9, np.nan, 0.9, 1.2])  # left finite 2.2 m over 2 of 3 strides
    f = length_by_foot(s, 0, 0.0, 3.0, 2.2)
    assert f["foot"] == "left" and f["l_finite/strides"] == "2/3"
    assert f["ref_nan_m"] == pytest.approx(1.1)


def test_an_untimed_contact_adds_a_stride_to_its_foot():
    s = _session([1.0, 0.9, 1.0, 0.9, 1.0], untimed="right")  # right: 3 timed + 1 untimed contacts = 3 strides
    f = length_by_foot(s, 0, 0.0, 3.0, 1.8)
    assert f["foot"] == "right" and f["r_finite/strides"] == "2/3"
    assert f["ref_nan_m"] == pytest.approx(0.9)


def test_a_length_no_foot_sum_gives_is_left_whole():
    f = length_by_foot(_session([1.0, 0.9, 1.0, 0.9, 1.0]), 0, 0.0, 3.0, 2.85)
    assert f["foot"] == "-" and f["ref_nan_m"] == 0.0
    assert f["closest"] == pytest.approx(100 * 0.15 / 2.85)  # the nearer foot: |2.7 / 2.85 - 1|
