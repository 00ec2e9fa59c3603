"""Session 44 review R1's findings F1-F6 (helper FL): `pdrlearn steps --detector accel-force` on a bike ride (L625,
L639, L641), at_times.csv's floor before / after a ride outside the strides (L638, L630, L631), the restart state's
live foot rest reading (E280, L621), ``--at-times`` with ``--window`` (L638), a non-finite count in a restart state
(E281) and L641's stride match on a long session clock."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError

ROOT = Path(__file__).resolve().parents[1]


# F1: the simulator's own bike ride, insoles on: `steps` leaves out the crank strides `track` removes
@pytest.mark.parametrize(("user", "why"), [(12312, "cycling? decision L611"), (12313, "a ride? decision L639")])
def test_steps_accel_force_leaves_out_a_bike_ride_like_track_r1_f1(tmp_path, capsys, caplog, user, why):
    d = tmp_path / "s"
    assert main(["simulate", "--route", "stand:3, straight:10, cycle:30, straight:10, stand:3", "--user-seed",
                 str(user), "--rate", "20", "--out", str(d)]) == 0
    capsys.readouterr()
    with caplog.at_level(logging.WARNING):
        assert main(["steps", str(d), "--detector", "accel-force", "--json", "--out", str(tmp_path / "c.csv")]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["false_positives"] == 0 and got["count"] == got["reference_count"]  # was one crank stroke counted
    table = pd.read_csv(tmp_path / "c.csv")
    assert not ((table["start_s"] > 17) & (table["end_s"] < 48)).any()  # no row inside the 30 s ride
    lines = [r.getMessage() for r in caplog.records if why in r.getMessage()]
    assert len(lines) == 1 and "left out of the count" in lines[0]


# F2 / F4: the L638 merge test's set-up (user 12700, 20 Hz, --storey-height 3.4)
def _lift(tmp_path, route, times, *extra):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route(route), UserProfile.from_seed(12700), rate_hz=20, seed=12700)
    write_session(s, tmp_path / "lift")
    (tmp_path / "at.csv").write_text("t\n" + "\n".join(map(str, times)) + "\n")
    return main(["track", "--no-plot", str(tmp_path / "lift"), "--storey-height", "3.4", "--at-times",
                 str(tmp_path / "at.csv"), "--out", str(tmp_path / "tr"), *extra])


@pytest.mark.parametrize(("route", "times", "floors"), [
    # a lift after the last stride (rides.csv 23.28-25.78 s): 25 s is in it, before its end; 37 s after it
    ("stand:5, straight:10, stand:3, lift:3.4, stand:5", [3, 12, 25, 37], [0, 0, 0, 1]),
    # a lift before the first stride (rides.csv 10.5-13 s): 12 s is in it, before its end (L630: from its end)
    ("stand:3, lift:3.4, stand:3, straight:10, stand:3", [1, 2, 6, 12, 20, 25], [0, 0, 0, 0, 1, 1]),
])
def test_at_times_floor_at_the_times_around_a_ride_outside_the_strides_r1_f2(tmp_path, route, times, floors):
    assert _lift(tmp_path, route, times) == 0
    at = pd.read_csv(tmp_path / "tr" / "at_times.csv")
    assert list(at["floor"]) == floors
    assert np.allclose(at["z_rides"] - at["z"], 3.4 * np.array(floors), atol=0.1)  # the ride in z_rides from its end
    summary = json.loads((tmp_path / "tr" / "summary.json").read_text())
    assert summary["storeys_changed"] == at["floor"].iloc[-1] == 1  # the printed "end floor +1"


def test_at_times_outside_the_window_is_one_error_line_r1_f4(tmp_path, capsys):
    rc = _lift(tmp_path, "stand:5, straight:10, stand:3, lift:3.4, stand:5", [3, 12], "--window", "8,20")
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and err[-1].startswith("error: --at-times") and "row 2 (3.000 s)" in err[-1]
    assert "--window" in err[-1] and not (tmp_path / "tr" / "at_times.csv").exists()


# F3: E280's ride on a foot accelerometer reading 1.2 g at rest (L621's mis-scaled unit), restarted at 12 s
def test_a_restart_keeps_the_live_foot_rest_reading_r1_f3():
    from tests.sim_helpers import quiet_walk
    from tests.test_pedal_s43_l611 import _pedal
    from tests.test_runtime_parity_s44_e280 import _live

    s = quiet_walk("stand:3, straight:8, stand:2, sit:40, stand:2, straight:8, stand:3", 12020, 12020, rate_hz=20.0)
    tr = s.extras["transfers"]
    _pedal(s, float(tr["seated_s"].iloc[0]) + 5, float(tr["rise_s"].iloc[0]) - 5, 40.0)
    acc = s.streams["fAccelerometer"]
    acc.values[:] = acc.values * 1.2
    old, ref, _ = _live(s)
    assert old._foot_rest.g_rest > 11.0  # the case: the unit rests at 1.2 g
    new, got, held = _live(s, 12.0)
    assert held >= 1 and [(x.start_s, x.end_s) for x in got] == [(x.start_s, x.end_s) for x in ref]  # lost 2 before
    assert new._foot_rest.n_still == old._foot_rest.n_still


# F5: a restart state's counts
@pytest.mark.parametrize("bad", [{"stop_bias": {"rps": 0.0, "n_stops": float("inf")}},
                                 {"stop_bias": {"rps": 0.0, "n_stops": -3}},
                                 {"pedal_history": [[0.0, 1.0, float("nan"), True, 0.1, True]]},
                                 {"foot_rest": {"readings": [9.8], "n_still": float("inf")}}])
def test_a_non_finite_or_negative_count_in_a_restart_state_is_one_line_r1_f5(bad):
    from pdrlearn.runtime import Tracker, load_bundle

    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    state = Tracker(bundle, tasks=[]).restart_state()
    assert state["foot_rest"] == {"readings": [], "n_still": 0}
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): .*not finite.*decision L134"):
        Tracker(bundle, tasks=[], resume=json.loads(json.dumps({**state, **bad})))
    old = {k: v for k, v in state.items() if k != "foot_rest"}  # a version-3 state from before F3 still loads
    assert Tracker(bundle, tasks=[], resume=old)._foot_rest.n_still == 0


# F6: L641's stride match is absolute, not relative to the session clock
def test_the_removed_stride_match_does_not_grow_with_the_clock_r1_f6():
    from pdrlearn.track.plasys import same_strides

    s0, s1 = np.array([28800.0, 86400.0, 3000.0]), np.array([28800.9, 86401.0, 3000.5])
    assert not same_strides(s0, s1, s0 + [0.25, 0.8, 0.02], s1 + [0.25, 0.8, 0.02]).any()
    assert same_strides(s0, s1, s0[::-1], s1[::-1]).all()
