"""Decisions L522, L524: a configurable 10 m walkway (``track --ten-m-walk ACCEL,TIMED,DECEL``) and every timed
trial of a recording (ten_m_walk_trials.csv)."""

import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.walk_test import parse_ten_m_walk, ten_metre_walk, ten_metre_walk_trials


def _bout(t0: float, speed: float, metres: float, stride_s: float = 1.0) -> list[dict]:
    """Strides of ``speed * stride_s`` metres, one after the other from ``t0``, contact at each stride's end."""
    n = int(round(metres / (speed * stride_s)))
    return [{"start_s": t0 + i * stride_s, "end_s": t0 + (i + 1) * stride_s, "event_s": t0 + (i + 1) * stride_s,
             "length_m": speed * stride_s, "heading_rad": 0.0} for i in range(n)]


def test_ten_m_walk_option_times_the_middle_6_m_of_a_10_m_walkway_l522():
    steps = pd.DataFrame(_bout(3.0, 0.5, 10.5))  # a 10 m walkway with a run-out, 0.5 m/s
    default = ten_metre_walk(steps)  # L312: 14 m needed
    assert default["ten_m_walk_time_s"] is None
    assert "--ten-m-walk" in default["ten_m_walk_note"]  # L522: the note names the option, not --window
    got = ten_metre_walk(steps, (2.0, 6.0, 2.0))
    assert got["ten_m_walk_time_s"] == pytest.approx(12.0)
    assert got["ten_m_walk_speed_mps"] == pytest.approx(0.5)
    assert got["ten_m_walk_zones_m"] == [2.0, 6.0, 2.0]
    # the deceleration zone counts: 2 + 6 + 3 m is more than the walk
    assert ten_metre_walk(steps, (2.0, 6.0, 3.0))["ten_m_walk_time_s"] is None


def test_parse_ten_m_walk_refuses_a_bad_walkway_l522():
    assert parse_ten_m_walk(None) is None
    assert parse_ten_m_walk("2,6,2") == (2.0, 6.0, 2.0)
    for bad in ("2,6", "2,0,2", "-1,6,2", "a,6,2"):
        with pytest.raises(DataError, match="--ten-m-walk"):
            parse_ten_m_walk(bad)


def test_track_refuses_a_bad_ten_m_walk_in_one_line_l522(tmp_path, capsys):
    from pdrlearn.cli import main

    assert main(["track", str(tmp_path), "--ten-m-walk", "2,0,2", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--ten-m-walk 2,0,2: give the walkway" in err and "ACCEL,TIMED,DECEL" in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_every_straight_bout_is_a_trial_self_selected_and_fast_l524():
    steps = pd.DataFrame(_bout(3.0, 1.0, 15.0) + _bout(40.0, 1.5, 15.0))  # self-selected, rest, fast
    trials = ten_metre_walk_trials(steps)
    assert list(trials.columns) == ["trial", "start_s", "end_s", "time_s", "speed_mps"]
    assert trials["trial"].tolist() == [1, 2]
    assert trials["speed_mps"].tolist() == pytest.approx([1.0, 1.5])
    assert trials["start_s"].tolist() == pytest.approx([5.0, 40.0 + 2.0 / 1.5])
    got = ten_metre_walk(steps)
    assert got["ten_m_walk_speed_mps"] == pytest.approx(1.0)  # the first trial, as L312
    assert got["n_ten_m_walk_trials"] == 2 and got["ten_m_walk_max_speed_mps"] == pytest.approx(1.5)
    # a short bout is no trial
    assert len(ten_metre_walk_trials(pd.DataFrame(_bout(3.0, 1.0, 10.0)))) == 0


def test_a_bout_just_short_of_the_walkway_is_named_beside_a_timed_trial_l524():
    near = _bout(3.0, 1.0, 14.0)[:-1] + [{**_bout(3.0, 1.0, 14.0)[-1], "length_m": 0.99}]  # 13.99 m: no trial
    got = ten_metre_walk(pd.DataFrame(near + _bout(40.0, 1.5, 15.0)))
    assert got["n_ten_m_walk_trials"] == 1 and got["ten_m_walk_speed_mps"] == pytest.approx(1.5)
    assert "walking bout 1 tracked 13.99 m, short of 14 m" in got["ten_m_walk_note"]
    assert ten_metre_walk(pd.DataFrame(_bout(3.0, 1.0, 15.0)))["ten_m_walk_note"] is None  # no near miss: no note
