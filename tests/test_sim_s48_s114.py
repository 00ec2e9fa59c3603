"""Decision S114: involuntary trunk jerks of the waist unit (``--trunk-jerks``): the kernels, the session's waist
readings and truth table, the foot unit untouched, and the one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.trunk_jerks import check_jerk_options, draw_jerks, jerk_motion

ROUTE = "stand:6"


def _sim(**knobs):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(3), seed=0, rate_hz=100, noise=False,
                         stand_s=1.0, name="tj", **knobs)


@pytest.fixture(scope="module")
def pair():
    return _sim(), _sim(trunk_jerk_rate_hz=1.0, trunk_jerk_m=(0.0, 0.0))


def test_draws_do_not_overlap_and_the_shape_returns_to_rest():
    jerks = draw_jerks(0.0, 60.0, 1.0, (4.0, 12.0), (0.015, 0.04), np.random.default_rng(1))
    assert 20 < len(jerks) < 60
    starts = np.array([j.start_s for j in jerks])
    ends = starts + np.array([j.dur_s for j in jerks])
    assert np.all(starts[1:] >= ends[:-1]) and ends[-1] <= 59.0
    assert all(0.3 <= j.dur_s <= 0.8 and np.radians(4) <= j.peak_rad <= np.radians(12) for j in jerks)
    j = jerks[0]
    t = j.start_s + np.array([0.0, j.dur_s / 2, j.dur_s - 1e-9])
    rv, dp = jerk_motion(t, [j])
    assert np.linalg.norm(rv[1]) == pytest.approx(j.peak_rad) and np.linalg.norm(rv[[0, 2]]) < 1e-6
    assert abs(dp[1, 2]) == pytest.approx(j.bump_m) and not dp[:, :2].any()


def test_a_jerk_tilts_the_waist_unit_and_leaves_the_foot_alone(pair):
    still, jerky = pair
    table = jerky.extras["trunk_jerks"]
    assert "trunk_jerks" not in still.extras and len(table) >= 1
    assert list(table.columns) == ["start_s", "end_s", "peak_deg", "bump_m"]
    for name in ("fAccelerometer", "fGyroscope"):
        np.testing.assert_array_equal(still.streams[name].values, jerky.streams[name].values)
    g = jerky.streams["wGyroscope"]
    a = jerky.streams["wAccelerometer"]
    row = table.iloc[0]
    first_half = (g.t >= row.start_s) & (g.t < (row.start_s + row.end_s) / 2)
    tilt = np.linalg.norm(g.values[first_half].sum(axis=0) / 100.0)  # the rate integrated to the peak (rad)
    assert np.degrees(tilt) == pytest.approx(row.peak_deg, rel=0.1)
    before = a.values[np.searchsorted(a.t, row.start_s) - 5]
    mid = a.values[np.searchsorted(a.t, (row.start_s + row.end_s) / 2)]
    turn = np.degrees(np.arccos(np.dot(before, mid) / np.linalg.norm(before) / np.linalg.norm(mid)))
    assert 0.5 < turn <= row.peak_deg + 0.5  # gravity turns with the tilt in the unit's frame
    outside = ~np.any([(g.t > a - 0.05) & (g.t < b + 0.05) for a, b in zip(table.start_s, table.end_s, strict=True)],
                      axis=0)
    assert np.abs(g.values[outside]).max() < 1e-3  # standing still: no rate outside the jerks


@pytest.mark.parametrize("knobs", [{"trunk_jerk_rate_hz": -1}, {"trunk_jerk_rate_hz": 5},
                                   {"trunk_jerk_deg": (12, 4)}, {"trunk_jerk_m": (0.0, 1.0)}])
def test_bad_jerk_options_are_one_line(knobs):
    opts = {"trunk_jerk_rate_hz": 1.0, "trunk_jerk_deg": (4, 12), "trunk_jerk_m": (0.015, 0.04), **knobs}
    with pytest.raises(DataError, match="trunk_jerk"):
        check_jerk_options(opts["trunk_jerk_rate_hz"], opts["trunk_jerk_deg"], opts["trunk_jerk_m"])


def test_the_cli_size_option_parses_and_refuses_in_one_line():
    from pdrlearn.cli.simulate import parse_jerk_size

    assert parse_jerk_size("2:6:1:2") == {"trunk_jerk_deg": (2.0, 6.0), "trunk_jerk_m": (0.01, 0.02)}
    assert parse_jerk_size(None) == {}
    for bad in ("4:12", "12:4:1:2", "4:12:1:50", "a:b:c:d"):
        with pytest.raises(DataError, match="--trunk-jerk-size"):
            parse_jerk_size(bad)


def test_the_cli_refuses_a_bad_rate_in_one_line(tmp_path, capsys):
    from pdrlearn.cli import main

    assert main(["simulate", "--route", "stand:2", "--trunk-jerks", "5", "--user-seed", "1",
                 "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "--trunk-jerks 5: give the trunk jerks per second" in err and "Traceback" not in err
