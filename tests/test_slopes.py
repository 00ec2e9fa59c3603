"""Slopes and hills on the foot altitude (decisions L144-L146): the sustained-slope option (not adopted), the
cross-check against the session's unused waist barometer and the cumulative ascent / descent."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels import distance
from pdrlearn.kernels.altitude_check import ascent_descent
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import count_floors_by_climb, track_summary
from pdrlearn.track.plasys import track_plasys


def _summary(route: str, user: int, **kw) -> dict:
    s = simulate_path(parse_route(route), UserProfile.from_seed(user), seed=user)
    return track_summary(track_plasys(s, **kw), s)


def test_ascent_descent_hysteresis():
    z = np.r_[0.0, 0.3, 0.1, 0.4, 1.2, 0.2, 0.25]
    assert ascent_descent(z) == pytest.approx((0.3 + 0.3 + 0.8 + 0.05, 0.2 + 1.0))  # every rise and drop
    up, down = ascent_descent(z, 0.5)  # 0 -> 1.2 (counted at 1.2), -> 0.2 (1.0 down), remainder +0.05
    assert (up, down) == pytest.approx((1.25, 1.0))
    rng = np.random.default_rng(0)
    level = rng.normal(0.0, 0.13, 400)  # W89: 0.13 m of altitude noise per barometer sample
    up, down = ascent_descent(level, 0.5)
    assert up - down == pytest.approx(level[-1] - level[0]) and up < 0.6 and down < 0.6
    assert sum(ascent_descent(level)) > 20  # without the band the noise is a climb
    assert ascent_descent([1.0]) == (0.0, 0.0)


def test_ascent_within_a_minute_drops_a_slow_drift():
    """Decision L172: with times and a window the band must be crossed within CLIMB_WINDOW_S; the weather's
    0.04 m per minute is dropped, a climb of 1 m in 10 s is kept; without the window the drift is an ascent."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M, CLIMB_WINDOW_S

    t = np.arange(0.0, 3600.0, 1.0)
    z = 0.04 * t / 60.0 + np.clip((t - 1800.0) / 10.0, 0.0, 1.0)  # 2.4 m of drift, 1 m climbed in 10 s
    up, down = ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S)
    assert up == pytest.approx(1.0, abs=0.1) and down == 0.0
    assert ascent_descent(z, ASCENT_BAND_BARO_M)[0] == pytest.approx(3.4, abs=0.01)  # L146 alone: drift counted
    assert ascent_descent(-z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S) == pytest.approx((0.0, up))


def test_the_barometer_warning_does_not_blame_the_foot_for_a_slow_drift():
    """Decision L172 (trial "longhaul", finding 3): a flat foot track (0 m) against a barometer that drifted
    +4.69 m slowly is no disagreement; a slow drift next to a real one is named, with what fused would do."""
    from pdrlearn.track.evaluate import barometer_warning

    s = {"altitude_change_m": 0.0, "barometer_altitude_change_m": 4.69, "barometer_climb_change_m": 0.0,
         "barometer_disagree_limit_m": 0.6, "barometer_unused": True}
    assert barometer_warning(s) is None
    line = barometer_warning({**s, "barometer_climb_change_m": 2.0})
    assert "+2.00 m (+4.69 m recorded, of which +2.69 m slow drift" in line and "--altitude fused" in line
    fused = {**s, "altitude_change_m": 4.70, "altitude_drift_m": 4.70, "barometer_unused": False}
    assert barometer_warning(fused) is None  # a fused track is compared by its climbs too


def test_the_sustained_slope_candidate_is_an_option_off_by_default():
    dz = np.r_[np.full(3, 0.02), np.full(30, 0.07), np.full(30, -0.065), np.full(5, 0.05)]
    assert distance.SUSTAINED_SLOPE is False  # L144: not adopted
    assert not distance.level_dz(dz).any() and count_floors_by_climb(dz) == (0, 0, 0)
    kept = distance.level_dz(dz, slope=True)
    assert kept.sum() == pytest.approx(30 * 0.07 - 30 * 0.065)  # the 5-stride run and the 0.02s stay level
    assert count_floors_by_climb(np.r_[dz, np.full(20, 0.07)], slope=True) == (1, 1, 0)  # 3.5 m up is a storey


def test_summary_has_ascent_and_descent():
    s = _summary("straight:3, slope:20:15, straight:2, turn:180, slope:20:-15, straight:3", 1061)
    assert s["ascent_m"] > 2.0 and s["descent_m"] > 2.0  # 3 m up and down; the net is near 0
    assert s["ascent_m"] - s["descent_m"] == pytest.approx(s["altitude_change_m"])


def test_a_ramp_on_the_foot_warns_against_the_barometer(caplog):
    with caplog.at_level(logging.WARNING):
        s = _summary("straight:3, slope:40:5, straight:3", 1062)  # +2 m, most strides under 0.10 m
    assert s["barometer_altitude_change_m"] == pytest.approx(2.0, abs=0.3)
    assert s["barometer_altitude_change_m"] - s["altitude_change_m"] > s["barometer_disagree_limit_m"]
    assert s["info"]["altitude_check"]["level_zeroed_m"] > 1.0  # the height L39 called level
    line = [w for w in s["info"]["warnings"] if "disagrees with the waist barometer's" in w]
    assert len(line) == 1 and "L39 set" in line[0] and "--pipeline waist-pendulum" in line[0]
    assert "disagrees with the waist barometer's" in caplog.text


def test_a_level_walk_with_a_barometer_does_not_warn():
    s = _summary("straight:30", 1063, streaming=True)
    assert s["barometer_unused"] and abs(s["barometer_altitude_change_m"]) < 0.5
    assert not [w for w in s["info"]["warnings"] if "barometer's" in w]


def _strides(n: int, t0: float = 2.0, period: float = 1.1) -> tuple[np.ndarray, np.ndarray]:
    start = t0 + period * np.arange(n)
    return start, start + period


def _baro(t: np.ndarray, h: np.ndarray) -> np.ndarray:
    from pdrlearn.kernels.barometer import pressure_hpa

    return pressure_hpa(75.0 + h, 1013.25)


def test_fused_altitude_kernel_follows_a_slope_not_a_transient_and_keeps_stairs():
    from pdrlearn.kernels.barometer import fuse_altitude

    t = np.arange(0.0, 80.0, 0.04)  # a 25 Hz barometer
    s0, s1 = _strides(60)
    climb = 0.065 * np.clip((t - s0[10]) / 1.1, 0, 40)  # 40 level strides of a 5 % slope: +2.6 m
    fused = fuse_altitude(np.zeros(60), s0, s1, t, _baro(t, climb))
    assert fused.sum() == pytest.approx(2.6, abs=0.15)  # the foot alone (L39): 0
    jump = np.where(t > 30.0, -2.0, 0.0)  # W108's pressure transient on a level floor, held to the end
    assert abs(fuse_altitude(np.zeros(60), s0, s1, t, _baro(t, jump)).sum()) < 0.3
    fast = 0.3 * np.sign(np.sin(2 * np.pi * t / 2.0))  # a wander faster than a stride: not a climb
    assert np.abs(np.cumsum(fuse_altitude(np.zeros(60), s0, s1, t, _baro(t, fast)))).max() < 0.2
    stairs = np.r_[np.zeros(10), np.full(20, 0.34), np.zeros(30)]  # 6.8 m of stairs, the barometer agreeing
    true = np.interp(t, np.r_[s0[0], s1], np.r_[0.0, np.cumsum(stairs)])
    assert fuse_altitude(stairs, s0, s1, t, _baro(t, true)).sum() == pytest.approx(6.8, abs=0.02)
    assert fuse_altitude(np.zeros(0), s0[:0], s1[:0], t, _baro(t, true)).shape == (0,)


def test_fused_altitude_on_a_real_level_barometer():
    from pathlib import Path

    from pdrlearn.io import read_session
    from pdrlearn.kernels.barometer import fuse_altitude, relative_altitude

    d = Path(__file__).resolve().parents[1] / "datasets" / "external" / "mobgap_HA001_Test5_Trial1"
    if not (d / "wBarometer.csv").exists():
        pytest.skip("datasets/external/mobgap_HA001_Test5_Trial1 absent (pdrlearn fetch mobgap)")
    b = read_session(d)["wBarometer"]
    s0, s1 = _strides(4, 5.0, 1.2)  # the reference's level walk, 5.0-9.9 s (W108)
    assert relative_altitude(b.t, b.values[:, 0], [s0[0], s1[-1]])[1] > 0.3  # the barometer's own wander
    assert abs(fuse_altitude(np.zeros(4), s0, s1, b.t, b.values[:, 0]).sum()) < 0.1  # measured (L154 (d)) 0.037


def test_fused_altitude_is_an_option_of_the_foot_pipeline(caplog):
    from pdrlearn.track import altitude

    assert altitude.DEFAULT_ALTITUDE == "foot"  # L154: the adoption rule was not met
    route = "straight:3, slope:40:5, straight:3"  # +2 m, most strides under L39's 0.10 m
    for streaming in (False, True):
        foot = _summary(route, 1062, streaming=streaming)
        with caplog.at_level(logging.WARNING):
            caplog.clear()
            s = _summary(route, 1062, altitude="fused", streaming=streaming)
        assert s["altitude_change_m"] == pytest.approx(2.0, abs=0.25)
        assert s["info"]["altitude_source"] == "fused" and not s["barometer_unused"]
        assert s["info"]["foot_altitude_change_m"] == pytest.approx(foot["altitude_change_m"])
        assert "disagrees with the waist barometer's" not in caplog.text  # L145 agrees with the fused altitude
        assert foot["info"]["altitude_source"] == "foot" and foot["altitude_change_m"] < 1.1  # the default: foot
        assert [w for w in foot["info"]["warnings"] if "`--altitude fused` (L154)" in w]  # and L145 still warns


def test_fused_altitude_without_a_barometer_and_unknown_values():
    from pdrlearn.errors import DataError

    s = simulate_path(parse_route("straight:10"), UserProfile.from_seed(1063), seed=1063)
    with pytest.raises(DataError, match="altitude 'baro' is not one of foot, fused"):
        track_plasys(s, altitude="baro")
    del s.streams["wBarometer"]
    r = track_plasys(s, altitude="fused")
    assert r.info["altitude_source"] == "foot"
    assert [w for w in r.info["warnings"] if "needs the waist barometer (wBarometer.csv)" in w]


def test_track_cli_altitude_option(tmp_path):
    import json

    from typer.testing import CliRunner

    from pdrlearn.cli import app
    from pdrlearn.io import write_session

    write_session(simulate_path(parse_route("straight:3, slope:30:6, straight:3"), UserProfile.from_seed(1064),
                                seed=1064), tmp_path / "ramp")
    r = CliRunner().invoke(app, ["track", "--no-plot", str(tmp_path / "ramp"), "--altitude", "fused", "--out",
                                 str(tmp_path / "f")])
    assert r.exit_code == 0, r.output
    summ = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert summ["altitude_change_m"] == pytest.approx(1.8, abs=0.25) and summ["info"]["altitude_source"] == "fused"
    r = CliRunner().invoke(app, ["track", "--no-plot", str(tmp_path / "ramp"), "--altitude", "baro", "--out",
                                 str(tmp_path / "g")])
    assert r.exit_code != 0 and "altitude 'baro' is not one of foot, fused" in str(r.exception)
    assert "\n" not in str(r.exception) and not (tmp_path / "g").exists()  # one line, before any tracking
    r = CliRunner().invoke(app, ["track", "--no-plot", str(tmp_path / "ramp"), "--pipeline", "waist-pendulum",
                                 "--altitude",
                                 "fused", "--out", str(tmp_path / "h")])
    assert r.exit_code != 0 and "--altitude" in r.output + str(r.exception)
    # review s24: --units foot left the barometer out and the warning said the session lacked it
    r = CliRunner().invoke(app, ["track", "--no-plot", str(tmp_path / "ramp"), "--altitude", "fused", "--units", "foot",
                                 "--out", str(tmp_path / "i")])
    assert r.exit_code != 0 and "--altitude fused reads the waist barometer (wBarometer.csv), which --units foot " \
        "leaves out" in str(r.exception) and not (tmp_path / "i").exists()


def test_fused_climb_bias_keeps_a_level_top_level_after_an_over_read_climb_l478():
    """Decision L478: a foot that over-reads every climbing stride (3.3 %, trial T3's +30.99 m for 30 m) no longer
    leaves the fused filter a payback for the level strides after the climb (a false downhill ramp)."""
    from pdrlearn.kernels.barometer import fuse_altitude

    s0, s1 = _strides(140)
    true = np.r_[np.zeros(10), np.full(100, 0.15), np.zeros(30)]  # 15 m up, then a level top
    t = np.arange(0.0, s1[-1] + 2.0, 0.04)
    baro = _baro(t, np.interp(t, np.r_[s0[0], s1], np.r_[0.0, np.cumsum(true)]))
    old = fuse_altitude(true * 1.033, s0, s1, t, baro, climb_bias=False)
    assert old[110:].sum() < -0.15  # measured -0.26 m: the slope state takes the climb's over-read
    new = fuse_altitude(true * 1.033, s0, s1, t, baro, climb_bias=True)
    assert abs(new[110:].sum()) < 0.05 and np.abs(new[110:]).max() < 0.01  # measured -0.007 m in all
    assert new[:110].sum() == pytest.approx(15.0, abs=0.05)  # the climb reads the barometer's 15 m (old: 15.25)
    assert np.array_equal(fuse_altitude(true * 1.033, s0, s1, t, baro), new)  # decision L479: on by default
