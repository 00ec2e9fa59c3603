"""Fragments of a split step carry no length of their own (decision W27): hand-computed windows, the
tracker/calibration bookkeeping on a real daily-activity recording (datasets/external or the download
cache, tests/conftest.py external_session; skipped without either)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.waist.steplength import FRAGMENT_FRAC, fragment_mask, fragment_windows
from tests.conftest import external_session


def _steps(durations: list[float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start, end and has_next of one walking sequence with these step durations plus its closing row."""
    t = np.concatenate([[0.0], np.cumsum(durations)])
    start = t
    end = np.concatenate([t[1:], t[-1:]])
    has_next = np.array([True] * len(durations) + [False])
    return start, end, has_next


def test_fragment_merges_with_the_neighbour_that_restores_the_median_step():
    # median 0.5 s; 0.2 s < 0.25 s is a fragment; with the previous step 0.7 s (0.2 off), with the next
    # 0.5 s (exact) -> the next step (row 3) owns rows 2..3; 0.3 s is no fragment (>= 0.25 s)
    start, end, hn = _steps([0.5, 0.5, 0.2, 0.3, 0.5, 0.5])
    win = fragment_windows(start, end, hn)
    assert win == {3: (2, 3)}
    assert fragment_mask(len(hn), win).tolist() == [False, False, True, False, False, False, False]


def test_two_fragments_each_merge_with_their_best_neighbour():
    # median 0.475 s, limit 0.2375 s: 0.1 s -> 0.55 with the next step (0.6 with the previous);
    # 0.15 s -> 0.5 s with the next (0.65 with the previous); a tie goes to the previous step
    start, end, hn = _steps([0.5, 0.5, 0.1, 0.45, 0.5, 0.15, 0.35, 0.5])
    assert fragment_windows(start, end, hn) == {3: (2, 3), 6: (5, 6)}
    start, end, hn = _steps([0.5, 0.1, 0.5, 0.5])
    assert fragment_windows(start, end, hn) == {0: (0, 1)}


def test_no_fragments_in_short_or_regular_sequences():
    start, end, hn = _steps([0.5, 0.2])  # two steps: no median to judge by
    assert fragment_windows(start, end, hn) == {}
    start, end, hn = _steps([0.5, 0.45, 0.55, 0.6, 0.4])
    assert fragment_windows(start, end, hn) == {}
    d = 0.5 * FRAGMENT_FRAC  # exactly at the limit is still a step
    start, end, hn = _steps([0.5, 0.5, d, 0.5])
    assert fragment_windows(start, end, hn) == {}


def test_sequences_are_judged_separately():
    s1, e1, h1 = _steps([1.0, 1.0, 1.0])
    s2, e2, h2 = _steps([0.4, 0.4, 0.4, 0.4])  # 0.4 s steps are short only against the first sequence
    win = fragment_windows(np.concatenate([s1, s2 + 10]), np.concatenate([e1, e2 + 10]), np.concatenate([h1, h2]))
    assert win == {}


@pytest.mark.parametrize("name", ["MS001_Test11_Trial1"])
def test_real_merged_fragments_carry_no_length_and_calibration_stays_self_consistent(name):
    d = external_session(f"mobgap_{name}")
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.waist import _kernels as K
    from pdrlearn.waist.ahrs import waist_imu
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    s = read_session(d)
    base, _ = resolve_params(s, None)
    base.f_m = 0.05  # a double-stance term, so that a fragment counted by the calibration would show
    base.options = {"pause_steps": False}  # W136: a stand step's capped length sums only within 0.2 % (not W27's)
    p = calibrate([s], "waist-pendulum", distances=[150.0], params=base)
    st = get_pipeline("waist-pendulum")(s, params=p).steps
    off = get_pipeline("waist-pendulum")(s, params=p, merge_fragments=False).steps
    m = st["merged"].to_numpy(bool)
    assert m.any()  # the recording has split steps (W25: MS001)
    assert np.all(st["length_m"].to_numpy()[m] == 0.0)
    assert not off["merged"].any()
    np.testing.assert_array_equal(st["event_s"], off["event_s"])  # contacts untouched, only lengths
    # an owner's h is the excursion over the whole merged step
    win = fragment_windows(st["start_s"].to_numpy(), st["end_s"].to_numpy(), st["has_next"].to_numpy(bool))
    imu = waist_imu(s)
    idx = np.clip(np.round((st["event_s"].to_numpy(float) - imu.t[0]) * imu.fs).astype(int), 0, len(imu.t) - 1)
    k, (a, b) = next(iter(win.items()))
    assert st["h_m"].iloc[k] == pytest.approx(K.vertical_excursion(imu.acc_v, imu.fs, idx[a], idx[b + 1]))
    # W21: calibrated on the whole recording's length, tracking it sums to that length (the calibration
    # gives a merged fragment neither a chord nor the F term, as the tracker does)
    assert st["length_m"].sum() == pytest.approx(150.0, rel=1e-9)
    # the merged step's turn belongs to its owner alone: the column still sums to the walk's turn
    assert np.all(st["dyaw_rad"].to_numpy()[m] == 0.0)
    assert st["dyaw_rad"].sum() == pytest.approx(off["dyaw_rad"].sum(), abs=1e-9)
