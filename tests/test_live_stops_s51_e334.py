"""Decisions E334 / E335 (session 51, FA, review s51r1 F1): E324's long-stop turn with a waist dropout: the
near-moving margin by time (no crash when the stop holds fewer samples than the margin's window), a gap over 1 s adds
nothing (each side by its own samples; before: the gap's edge sample stood for half the gap), read once per stride."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.rest_heading import sample_weights
from pdrlearn.kernels.stride import long_stop_turn
from tests.test_live_stops_s50_e324 import stop_streams


def _seen(frac: float) -> float:
    """The share of stop_streams' raised-cosine spin turned by ``frac`` of its 4 s."""
    return frac - math.sin(2 * math.pi * frac) / (2 * math.pi)


def test_the_weights_count_a_gap_as_one_median_interval():
    t = np.array([0.0, 0.1, 0.2, 5.2, 5.3, 5.4])
    assert np.allclose(sample_weights(t), np.gradient(t))  # L296's other callers: as before
    assert np.allclose(sample_weights(t, 1.0), 0.1)  # the gap's edge samples no longer stand for half of it


def test_a_dropout_over_the_margin_s_window_does_not_break_the_turn():
    # waist samples only in the stop's first second (50 of them, under the 101 of the 1 s margin's window): the spin
    # at 60 s is unseen; before E334 a ValueError (review s51r1 F1 (a), track --streaming and the live Tracker)
    stream = stop_streams(90.0, 60.0, 90.0, gap=(1.0, 89.5))
    assert abs(math.degrees(long_stop_turn(stream, 0.0, 90.0))) < 2.0


@pytest.mark.parametrize("fs", [20.0, 100.0])
def test_a_gap_through_the_spin_splits_it_and_one_outside_it_changes_nothing(fs):
    through = stop_streams(90.0, 30.0, 90.0, fs=fs, gap=(33.0, 60.0))  # the spin's last second unseen
    got = math.degrees(long_stop_turn(through, 0.0, 90.0))
    assert abs(got - 90.0 * _seen(0.75)) < 3.0, got  # before E334: over 700 deg (review s51r1 F1 (b))
    outside = math.degrees(long_stop_turn(stop_streams(90.0, 30.0, 90.0, fs=fs, gap=(40.0, 70.0)), 0.0, 90.0))
    whole = math.degrees(long_stop_turn(stop_streams(90.0, 30.0, 90.0, fs=fs), 0.0, 90.0))
    assert abs(outside - 90.0) < 1.5 and abs(outside - whole) < 0.5, (outside, whole)
