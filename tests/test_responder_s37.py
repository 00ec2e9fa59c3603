"""Session 37, fixer FG (trial T5): first-responder indoor tracking - long standstills, end floor, speed."""
import numpy as np
import pytest

from pdrlearn.track import plasys as P


def _two_legs(rest_s: float):
    """A 15-stride leg along 0 rad, a rest of ``rest_s``, a 15-stride leg back along pi: the foot's relative heading
    is right, the compass is off by a heading-dependent +0.15 / -0.15 rad (a hard-iron offset, as trial T5's)."""
    n = 15
    s1 = np.arange(n) * 1.1
    s2 = s1[-1] + 1.1 + rest_s + np.arange(n) * 1.1
    start = np.concatenate([s1, s2])
    end = start + 1.0
    rel = np.concatenate([np.zeros(n), np.full(n, np.pi)])
    absolute = rel + np.concatenate([np.full(n, 0.15), np.full(n, -0.15)])
    return rel, absolute, start, end


def test_fused_heading_window_runs_on_walking_time_l471():
    """L471: a 1500 s rest between two legs no longer splits L17's +-60 s compass window, so each leg keeps the
    offset it had with a 2 s rest (the compass's opposite errors cancel) instead of taking its own leg's error."""
    short = P.fuse_by_segment(*_two_legs(2.0), {}, tau_s=60.0, walking=True)
    long_ = P.fuse_by_segment(*_two_legs(1500.0), {}, tau_s=60.0, walking=True)
    np.testing.assert_allclose(long_, short, atol=1e-12)
    rel = _two_legs(1500.0)[0]
    assert np.max(np.abs(long_ - rel)) < 1e-9  # the opposite compass errors cancel: no leg is turned
    assert P.FUSED_WALKING_CLOCK is True  # the default offline track uses it (decision L471, adopted)
    old = P.fuse_by_segment(*_two_legs(1500.0), {}, tau_s=60.0)  # L17's clock time: each leg turned 0.15 rad
    assert np.max(np.abs(old - rel)) > 0.1


def test_walking_clock_caps_stops_at_three_seconds_l471():
    start = np.array([0.0, 1.1, 2.2, 1000.0, 1001.1])
    end = start + 1.0
    clock = P.walking_clock(start, end)
    np.testing.assert_allclose(np.diff(clock), [1.1, 1.1, 3.0 + 1.0, 1.1])  # 996.8 s stop -> 3 s
    short = np.array([0.0, 1.1, 4.0])  # a 1.9 s stop is walking time, untouched
    np.testing.assert_allclose(P.walking_clock(short, short + 1.0), short + 1.0)


def _streamed_out_and_back(rest_s: float):
    from types import SimpleNamespace

    import pandas as pd

    n = 13
    start = np.concatenate([10.0 + np.arange(n) * 1.1, 10.0 + n * 1.1 + rest_s + np.arange(n) * 1.1])
    steps = pd.DataFrame({"start_s": start, "end_s": start + 1.1, "length_m": 1.5,
                          "heading_rad": np.repeat([0.0, np.pi], n), "gap_s": 0.0})
    traj = pd.DataFrame({"t": np.concatenate([[10.0], steps["end_s"]]), "x": 0.0, "y": 0.0, "z": 0.0})
    return SimpleNamespace(trajectory=traj, steps=steps, info={})


def test_streamed_radius_does_not_grow_over_a_rest_e205():
    """E205: the streamed heading adds only gap_yaw's last second of a rest, so the streamed regime's bias term does
    not run over a 1500 s rest: the radius stays the 2 s rest's (trial T5: 0.89 -> 15.34 m before)."""
    from pdrlearn.track.position_sigma import add_position_sigma

    short, long_ = _streamed_out_and_back(2.0), _streamed_out_and_back(1500.0)
    for r in (short, long_):
        add_position_sigma(r, None, "plasys-streaming")
    s2, s1500 = (float(r.trajectory["pos_sigma_m"].iloc[-1]) for r in (short, long_))
    assert s1500 < 1.1 * s2, (s2, s1500)
    held = _streamed_out_and_back(1500.0)  # a held foot-gap row next to it: L99 bridges it, the clock runs
    held.steps.loc[13, "gap_s"] = 1500.0
    add_position_sigma(held, None, "plasys-streaming")
    assert float(held.trajectory["pos_sigma_m"].iloc[-1]) > 3 * s2


def test_run_prints_the_final_position_error_as_track_does_e206(tmp_path_factory, capsys):
    """E206: `run` of a session with a reference prints the final position error in its one line, as `track`."""
    import json

    from pdrlearn.cli import main
    from tests.runtime_helpers import trained_dirs_and_walk

    d = trained_dirs_and_walk(tmp_path_factory, "fg_run")
    walk = d["tmp"] / "sim"  # a simulated walk (user 9325): its trajectory.csv is the reference
    assert main(["simulate", "--route", "stand:2, straight:8, stand:2", "--user-seed", "9325", "--out", str(walk)]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(d["root"] / "bundle"), str(walk), "--json"]) == 0
    err = json.loads(capsys.readouterr().out)["final_position_error_m"]
    assert main(["run", "--no-plot", str(d["root"] / "bundle"), str(walk)]) == 0
    assert f"final position error {err:.2f} m horizontal" in capsys.readouterr().out


def test_one_line_summary_says_the_end_floor_l473():
    """L473: the floor part of track's and run's one line ends with the storey the walk ended on."""
    from pdrlearn.track.evaluate import floors_phrase

    line = floors_phrase({"floors_up": 3, "floors_down": 3, "storeys_changed": 0, "barometer_unused": False})
    assert line == ", floors up 3 / down 3, end floor +0"
    assert floors_phrase({"floors_up": 2, "floors_down": 0, "storeys_changed": 2}).endswith("end floor +2")
    assert floors_phrase({"floors_up": 0, "floors_down": 0, "storeys_changed": 0}) == ""  # level, no barometer


def test_strides_faster_than_the_training_strides_are_flagged_l474():
    """L474: a stride whose speed lies over 10 % outside the model's recorded training speeds gets
    speed_out_of_range and the track one warning line; a model without a recorded range flags nothing."""
    from types import SimpleNamespace

    import pandas as pd

    from pdrlearn.track.speed_domain import flag_speeds, model_speed_range, training_speed_range

    rng = training_speed_range(np.linspace(1.2, 1.6, 50))
    assert rng[0] == pytest.approx(1.204, abs=1e-3) and rng[1] == pytest.approx(1.596, abs=1e-3)
    model = SimpleNamespace(data_summary={"distance_calibration": {"speed_range_mps": rng}})
    table = pd.DataFrame({"speed_mps": [1.4, 1.9, 1.0, np.nan, 1.7]})
    warnings: list[str] = []
    info = flag_speeds(table, model_speed_range(model), warnings)
    assert table["speed_out_of_range"].tolist() == [False, True, True, False, False]
    assert info["n_out"] == 2 and info["n_strides"] == 4
    assert len(warnings) == 1 and "speed of use" in warnings[0] and "L474" in warnings[0]
    assert model_speed_range(SimpleNamespace(data_summary={})) is None
    assert flag_speeds(pd.DataFrame({"speed_mps": [3.0]}), None, warnings) is None
