"""Decisions L696-L698 (session 47): L684's streamed rhythm rule as the default, its period read over walking.

L696: a stand between walking bouts leaves the segmenter's trailing |w| means (the terrain exercise's bouts read as a
2.75-5.15 s period and dropped real stances: training's runtime bout edges moved, c55). L697: the streamed period is
the first autocorrelation peak that reaches 0.8 of the highest (L189's stairs with a landing every fourth stride read
3.8 s). L698: a foot gap ends the rhythm's series (R2's doubled period after ``--gap foot:10:2``)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main as cli
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK
from pdrlearn.sim import simulate

OLD = {"stance_rhythm_frac": 0}  # the segmenter before L684


def _same_strides(session) -> None:
    g = session.streams["fGyroscope"]
    np.testing.assert_array_equal(SK.stance_strides(g.t, g.values), SK.stance_strides(g.t, g.values, OLD))


def test_the_rhythm_rule_is_the_default_and_old_bundles_get_it_l696():
    assert FR.STREAMED_RHYTHM_FRAC == 0.1 and SK.StanceSegmenter().rhythm_frac == 0.1
    assert SK.StanceSegmenter.from_params({"stance_gyro_rad_s": 0.8}).rhythm_frac == 0.1  # a bundle without the key
    assert SK.StanceSegmenter.from_params(OLD).rhythm_frac == 0.0


def test_the_terrain_exercises_stands_move_no_stride_l696():
    """c55's walk (terrain exercise, user 2500, seed 7, 20 Hz): the rule read 2.75-5.15 s from its bouts and stands and
    merged three pairs of strides (91 -> 88, printed); the means over walking keep the 91."""
    _same_strides(simulate("terrain", 2500, seed=7))


def test_a_repeating_group_of_strides_reads_the_stride_l697():
    t = np.arange(0, 24, 0.05)
    w = 1 + np.sin(2 * np.pi * t / 1.0) * (1 + (np.floor(t) % 4 == 0))  # every fourth stride twice
    assert FR.stride_period(w, 20.0) == pytest.approx(4.0, abs=0.06)  # offline's reading: the group (unchanged)
    assert FR.stride_period(w, 20.0, near_top=FR.STREAMED_PEAK_FRAC) == pytest.approx(1.0, abs=0.06)
    assert FR.trailing_period(t, w) == pytest.approx(1.0, abs=0.06)


@pytest.mark.slow
def test_stairs_with_landings_move_no_stride_l697():
    """L189's case (scenario D fast, user 5, device errors): three stairs and a landing read P 3.80 s once (67 -> 66
    strides, printed) before L697."""
    _same_strides(simulate("D", user_seed=5, speed="fast", device_errors=True))


def test_a_foot_gap_ends_the_rhythms_series_l698(tmp_path):
    t = np.arange(0, 12, 0.01)
    w = 1 + np.sin(2 * np.pi * t / 1.4)
    keep = (t < 4) | (t >= 6)
    assert np.isnan(FR.trailing_period(t[keep & (t < 7)], w[keep & (t < 7)]))  # 1 s after the gap: no period yet
    assert FR.trailing_period(t[keep], w[keep]) == pytest.approx(1.4, abs=0.02)  # 6 s after it
    # R2's gap (L695 "Left") on user 14640: P 1.11, 1.09, 2.18, 1.12 ... at the stance starts after it (printed)
    d = tmp_path / "gap"
    assert cli(["simulate", "--route", "stand:3, straight:20, stand:3", "--rate", "100", "--step-time", "0.7",
                "--step-length", "0.4", "--gap", "foot:10:2", "--user-seed", "14640", "--out", str(d)]) == 0
    g = read_session(d).streams["fGyroscope"]
    seg, read = SK.StanceSegmenter(), []
    rest = seg._rhythm_rest

    def logged(min_run: float) -> float:
        tt, m = seg._rhythm.arrays()
        read.append((seg.stance_start, FR.trailing_period(tt, m)))
        return rest(min_run)

    seg._rhythm_rest = logged
    seg.update(g.t, g.values)
    after = np.array([p for s, p in read if 10 <= s <= 24])
    assert len(after) >= 10 and np.nanmax(after) < 1.5 * 1.4 and np.isfinite(after).sum() >= 8
