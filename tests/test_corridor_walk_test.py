"""Decisions L383, L384, B293 (session 33, trial T4 finding 7): a corridor walk test (6MWT / 2MWT) from a track's
cone turns: laps.csv, the corridor's distance and the distance per minute."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.track.corridor import KEYS, corridor_laps
from tests.cli_helpers import tracked_slow_walk


def _walk(rows: int = 135, step_m: float = 0.8, rest_after: int | None = None, rest_s: float = 0.0):
    """A foot table of ``rows`` 1 s strides of ``step_m`` tracked metres (a true 1 m: the track reads 20 % short),
    laps of 30 strides (30 m true, 24 m tracked); ``rest_s`` seconds standing after row ``rest_after``."""
    t = np.arange(rows, dtype=float)
    if rest_after is not None:
        t[rest_after:] += rest_s
    heading = np.where((np.arange(rows) // 30) % 2 == 0, 0.0, np.pi)
    return pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t + 1.0, "length_m": step_m,
                         "heading_rad": heading, "unit": "foot"})


def _turns(mids) -> pd.DataFrame:
    mids = np.asarray(mids, float)
    return pd.DataFrame({"start_s": mids - 0.5, "end_s": mids + 0.5, "angle_deg": 180.0})


def test_laps_and_distance_of_a_hand_made_corridor_walk():
    laps, s, warnings = corridor_laps(_walk(), _turns([30, 60, 90, 120]), 30.0)
    # L518: a foot track's laps 20 % short of --corridor is more than its scale error: one line, the count unchanged
    assert len(warnings) == 1 and "L518" in warnings[0]
    assert corridor_laps(_walk().assign(unit="waist"), _turns([30, 60, 90, 120]), 30.0)[2] == []  # lower back: C213
    assert s["n_laps"] == 4 and len(laps) == 5
    # L383: 4 laps x 30 m + the final 12 tracked metres x (30 / 24, the last lap's scale) = 15 m
    assert s["walk_test_distance_m"] == pytest.approx(135.0)
    assert list(laps["distance_source"]) == ["corridor"] * 4 + ["tracked x scale"]
    assert laps["tracked_m"].iloc[0] == pytest.approx(24.0) and laps["speed_mps"].iloc[0] == pytest.approx(1.0)
    assert list(laps["n_steps"]) == [60, 60, 60, 60, 30]  # both feet, as bouts.csv's
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([60.0, 60.0])
    assert s["fatigue_index"] == pytest.approx(1.0)
    # a turn of 100 deg (a corner) ends no lap
    corner = _turns([30, 60, 90, 120]).assign(angle_deg=[180.0, 100.0, 180.0, -179.0])
    _, s2, w2 = corridor_laps(_walk(), corner, 30.0)
    assert s2["n_laps"] == 4 and any("missed turn" in w for w in w2)


def test_window_is_the_test_span():
    """L383: with --window the test runs over the window: its minutes count from the window's start to its end."""
    _, s, _ = corridor_laps(_walk(), _turns([30, 60, 90, 120]), 30.0, span=(0.0, 180.0))
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([60.0, 60.0, 15.0])
    _, late, _ = corridor_laps(_walk(), _turns([30, 60, 90, 120]), 30.0, span=(-0.5, 179.5))
    assert len(late["walk_test_distance_per_minute_m"]) == 3 and late["walk_test_distance_m"] == pytest.approx(135.0)


def test_missed_turn_counts_two_laps_and_warns():
    laps, s, warnings = corridor_laps(_walk(), _turns([30, 90, 120]), 30.0)
    warnings = [w for w in warnings if "L518" not in w]  # the fixture's foot reads 20 % short (L518's line)
    assert s["n_laps"] == 4 and s["walk_test_distance_m"] == pytest.approx(135.0)
    assert list(laps["corridor_laps"]) == [1, 2, 1, 0]
    assert len(warnings) == 1 and "lap 2 tracked 48.0 m" in warnings[0] and "L384" in warnings[0]


def test_extra_turn_joins_the_next_lap():
    laps, s, warnings = corridor_laps(_walk(), _turns([30, 40, 60, 90, 120]), 30.0)
    warnings = [w for w in warnings if "L518" not in w]  # the fixture's foot reads 20 % short (L518's line)
    assert s["n_laps"] == 4 and len(laps) == 5 and s["walk_test_distance_m"] == pytest.approx(135.0)
    assert laps["start_s"].iloc[1] == pytest.approx(30.0) and laps["end_s"].iloc[1] == pytest.approx(60.0)
    assert len(warnings) == 1 and "extra turn" in warnings[0]


def test_rest_at_a_cone_stays_in_its_lap():
    bouts = pd.DataFrame({"start_s": [0.0, 90.0], "end_s": [60.0, 165.0]})
    laps, s, _ = corridor_laps(_walk(rest_after=60, rest_s=30.0), _turns([30, 90, 120, 150]), 30.0, bouts)
    # decision L647: the cone turn's half second in the gap (89.5-90 s) is turning, not rest
    assert laps["duration_s"].iloc[1] == pytest.approx(60.0) and laps["rest_s"].iloc[1] == pytest.approx(29.5)
    assert laps["speed_mps"].iloc[1] == pytest.approx(0.5) and laps["rest_s"].iloc[0] == 0.0
    # minute 2 (60-120 s) holds the rest and lap 3: 30 m
    assert s["walk_test_distance_per_minute_m"][:2] == pytest.approx([60.0, 30.0])


def test_track_corridor_writes_laps_csv_and_summary_keys(tmp_path):
    route = ", ".join(["straight:10"] + ["curve:180:0.5, straight:10"] * 3 + ["curve:180:0.5, straight:5"])
    ses = tmp_path / "walk"
    assert main(["simulate", "--route", route, "--user-seed", "7305", "--out", str(ses)]) == 0
    for pipe in ("plasys", "waist-pendulum"):
        out = tmp_path / pipe
        assert main(["track", "--no-plot", str(ses), "--pipeline", pipe, "--corridor", "10", "--out", str(out)]) == 0
        s = json.loads((out / "summary.json").read_text())
        assert s["corridor_m"] == 10.0 and s["n_laps"] == 4, pipe
        assert s["walk_test_distance_m"] == pytest.approx(45.0, abs=1.5), pipe
        laps = pd.read_csv(out / "laps.csv")
        assert list(laps["lap"]) == [1, 2, 3, 4, 5] and (laps["distance_m"].iloc[:4] == 10.0).all()
        assert undocumented("laps.csv", laps.columns) == [] and undocumented("sessions.csv", KEYS) == []


def test_without_corridor_nothing_changes(tmp_path):
    ses = tmp_path / "walk"
    assert main(["simulate", "--route", "straight:10, curve:180:0.5, straight:10", "--user-seed", "7306",
                 "--out", str(ses)]) == 0
    assert main(["track", "--no-plot", str(ses), "--out", str(tmp_path / "t")]) == 0
    s = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert not (tmp_path / "t" / "laps.csv").exists() and "walk_test_distance_m" not in s and "n_laps" not in s


@pytest.mark.parametrize("value", ["0", "-30", "nan"])
def test_bad_corridor_is_one_line_and_no_output_b293(tmp_path, capsys, value):
    ses = tmp_path / "walk"
    assert main(["simulate", "--route", "straight:5", "--user-seed", "7307", "--out", str(ses)]) == 0
    capsys.readouterr()
    assert main(["track", str(ses), f"--corridor={value}", "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--corridor" in err[0] and "a positive number" in err[0] and "Traceback" not in err[0]
    assert not (tmp_path / "t").exists()


def test_t25fw_from_standing_on_a_simulated_walk_l387(tmp_path, capsys):
    """L387: a 0.5 m/s walker's 9 m walk from standing (user 7308): the foot track's time to 7.62 m within 5 % of
    the body's (from the first true stride's start, the simulator's steps.csv, to the body's path passing 7.62 m);
    `track` prints it; the lower back and a 6 m walk are not timed."""
    from pdrlearn.track.walk_test import T25FW_LOWER_BACK_NOTE, t25fw

    out, s, t, x, d = tracked_slow_walk(tmp_path, capsys, "stand:3, straight:9, stand:3", 7308, 0.35, 0.7)
    true_s = t[np.argmax(x >= 7.62)] - pd.read_csv(d / "steps.csv")["start_ms"].min() / 1000
    err = 100 * (s["t25fw_time_s"] / true_s - 1)
    print(f"T25FW: tracked {s['t25fw_time_s']:.2f} s, true {true_s:.2f} s, error {err:+.2f} %")
    assert abs(err) < 5.0 and "timed 25-foot walk" in out and s["t25fw_note"] is None
    assert s["ten_m_walk_time_s"] is None  # 9 m: no 10 m walk (L313), but a T25FW
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert t25fw(steps.assign(unit="waist"))["t25fw_note"] == T25FW_LOWER_BACK_NOTE
    short = steps[steps["start_s"] < steps["start_s"].min() + 6.0 / 0.5]  # about 6 m of it
    assert t25fw(short)["t25fw_time_s"] is None and "25 ft" in t25fw(short)["t25fw_note"]


def test_first_and_final_lap_span_the_steps_not_the_window_l399():
    """L399: with a window wider than the walk, lap 1 starts at the first step and the final lap ends at the last
    step; standing after the test is no part of the final lap (its rest_s, its speed). E98: speed_mps."""
    bouts = pd.DataFrame({"start_s": [0.0], "end_s": [135.0]})
    laps, s, _ = corridor_laps(_walk(), _turns([30, 60, 90, 120]), 30.0, bouts, span=(-5.0, 175.0))
    assert laps["start_s"].iloc[0] == pytest.approx(0.0) and laps["end_s"].iloc[-1] == pytest.approx(135.0)
    assert laps["rest_s"].iloc[-1] == pytest.approx(0.0)
    assert laps["speed_mps"].iloc[-1] == pytest.approx(1.0) and "speed_m_s" not in laps.columns
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([55.0, 60.0, 20.0]) and s["n_laps"] == 4


def test_uneven_legs_warn_against_the_corridor_l407():
    """L407 (trial T3 finding 2): a 5-10-5 shuttle given --corridor 10 or 5: the laps' tracked lengths (5 and 10 m)
    disagree with one corridor length, one warning names them; the count stays L384's (round(tracked / median))."""
    shuttle = _walk(rows=20, step_m=1.0)
    for corridor in (10.0, 5.0):
        laps, s, warnings = corridor_laps(shuttle, _turns([5, 15]), corridor)
        assert list(laps["corridor_laps"]) == [1, 1, 0]
        assert len(warnings) == 1 and "lap 1 tracked 5.0 m, lap 2 tracked 10.0 m" in warnings[0], corridor
        assert "against the median lap's 7.5 m" in warnings[0] and "L407" in warnings[0]


def test_a_missed_turn_on_a_short_walk_warns_l407():
    """L407: with two stretches, one a missed turn (30 and 60 m on a 30 m corridor), L384's median lap is 45 m and
    both count one lap: the laps disagree by a third each way, and the line says so."""
    laps, _, warnings = corridor_laps(_walk(rows=105, step_m=1.0), _turns([30, 90]), 30.0)
    assert list(laps["corridor_laps"]) == [1, 1, 0]
    assert len(warnings) == 1 and "lap 1 tracked 30.0 m, lap 2 tracked 60.0 m" in warnings[0]
