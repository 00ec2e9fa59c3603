"""Decisions L615, L616, L617 (session 43, fixer FE, trial T3 findings F2, F6, F10): the foot track reads a ride's
vibration from its foot unit and calls a vibrating ride a ``vehicle`` (L615), writes a vehicle row for a long
vibrating standstill, level or not (L616), and leaves out a freeze-index episode with no walking next to it (L617).
Simulated users 12060-12069 (seed = user)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.pause_ride import VEHICLE_VIBRATION_MPS2, vibrating_span
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

# a bus climbing 4 m while the walker stands, then a level 30 s ride, then a quiet 25 s stand (no vehicle)
ROUTE = "stand:3, straight:10, vehicle:60::4, straight:10, vehicle:30, straight:10, stand:25, straight:5, stand:3"


@pytest.fixture(scope="module")
def bus():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(12061), seed=12061, scenario="route")


def _track(session, **kw):
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.plasys import track_plasys

    r = track_plasys(session, **kw)
    return r, track_summary(r, session, pipeline="plasys")


def test_vibrating_span_finds_the_shaking_part_of_a_standstill():
    """L616's kernel: a 2 Hz shake of 0.28 m/s^2 RMS from 10 to 40 s inside a 0-50 s standstill with the thesis's still
    noise (Table 12: 0.0175 m/s^2) spans about 10-40 s; the still noise alone is no vehicle."""
    rng = np.random.default_rng(12062)
    t = np.arange(0.0, 50.0, 0.01)
    noise = rng.normal(0.0, 0.0175, (len(t), 3))
    on = (t >= 10.0) & (t < 40.0)
    shake = np.column_stack([np.zeros_like(t), np.zeros_like(t), 9.80665 + on * 0.4 * np.sin(2 * np.pi * 2.0 * t)])
    a, b, vib = vibrating_span(t, shake + noise, 0.0, 50.0)
    assert a == pytest.approx(10.0, abs=1.01) and b == pytest.approx(40.0, abs=1.01) and vib > VEHICLE_VIBRATION_MPS2
    base = np.column_stack([np.zeros_like(t), np.zeros_like(t), np.full_like(t, 9.80665)])
    assert vibrating_span(t, base + noise, 0.0, 50.0) is None


def test_the_foot_track_calls_a_vibrating_ride_a_vehicle_l615_l616(bus):
    """L615: the bus climb is a vehicle, no floor (before: a lift or an escalator, 1 floor up); L616: the level ride
    is a second vehicle row covering the simulated ride, the quiet 25 s stand none, and one line says so (before: no
    row). ``ride_vibration=False`` gives L376's rate alone and no level row."""
    truth = bus.extras["rides"]
    r, m = _track(bus)
    rides = r.info["rides"]
    assert [x["kind"] for x in rides] == ["vehicle", "vehicle"], rides
    assert (m["floors_up"], m["floors_up_rides"], m["n_rides"]) == (0, 0, 2)
    t0, t1 = float(truth["start_s"].iloc[1]), float(truth["end_s"].iloc[1])
    level = rides[1]
    assert min(t1, level["end_s"]) - max(t0, level["start_s"]) >= 0.8 * (t1 - t0)
    assert abs(level["dz_m"]) < 1.0 and level["horizontal_est_m"] is None
    assert list(r.steps["ride"][r.steps["ride"] != ""]) == ["vehicle", "vehicle"]
    said = [w for w in r.info["warnings"] if "L616" in w]
    assert len(said) == 1 and said[0].startswith("2 vehicle ride(s)"), said
    r, m = _track(bus, ride_vibration=False)
    assert [x["kind"] for x in r.info["rides"]] in (["lift"], ["escalator"]) and m["floors_up"] == 1
    assert not any("L616" in w for w in r.info["warnings"])


def test_plasys_accepts_the_documented_option_l615(bus, tmp_path):
    """The documented ``{"options": {"ride_vibration": ...}}`` is read by the plasys pipeline (before: "unknown
    parameter(s) options"); a lower-back-only option, a string and ``--streaming`` are one error line each."""
    from pdrlearn.cli import main
    from pdrlearn.cli.track import _track_params
    from pdrlearn.io import write_session

    p = tmp_path / "p.json"
    assert _track_params({"options": {"ride_vibration": False}, "rest_s": 0.05}, p, False) == (
        {"rest_s": 0.05}, {"ride_vibration": False})
    for opts, streaming, words in (({"rhythm_warning": True}, False, "lower-back options"),
                                   ({"ride_vibration": "yes"}, False, "true or false"),
                                   ({"ride_vibration": True}, True, "drop --streaming"), ([1], False, "JSON object")):
        with pytest.raises(DataError, match=words) as err:
            _track_params({"options": opts}, p, streaming)
        assert str(p) in str(err.value) and "\n" not in str(err.value)
    write_session(bus, tmp_path / "s")
    p.write_text(json.dumps({"options": {"ride_vibration": False}}))
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--params", str(p), "--out", str(tmp_path / "t")]) == 0
    kinds = list(pd.read_csv(tmp_path / "t" / "rides.csv")["kind"])
    assert kinds in (["lift"], ["escalator"]), kinds


def test_a_freeze_with_no_walking_next_to_it_is_left_out_l617():
    """L617: an episode 30 s after the last stride (a bus, a bike's coast) is left out with one line; one 3 s after a
    stride, or with a stride inside, is kept and renumbered."""
    from pdrlearn.track.freezes import FREEZE_WALK_GAP_S, walkless_freezes

    steps = pd.DataFrame({"start_s": [5.0, 6.0, 100.0], "end_s": [6.0, 7.0, 101.0]})
    rows = [{"freeze": 1, "start_s": 37.0, "end_s": 40.0, "duration_s": 3.0, "peak_fi": 135.1},
            {"freeze": 2, "start_s": 10.0, "end_s": 12.0, "duration_s": 2.0, "peak_fi": 5.0},
            {"freeze": 3, "start_s": 99.0, "end_s": 103.0, "duration_s": 4.0, "peak_fi": 4.0}]
    kept, lines = walkless_freezes(rows, steps)
    assert FREEZE_WALK_GAP_S == 4.0
    assert [(r["freeze"], r["start_s"]) for r in kept] == [(1, 10.0), (2, 99.0)]
    assert len(lines) == 1 and "37.0-40.0 s" in lines[0] and "L617" in lines[0]
    assert walkless_freezes(None, steps) == (None, [])


def test_the_foot_track_leaves_out_a_tremble_far_from_walking_l617():
    """L617 in :func:`foot_freezes` (the foot track's and a window's path): a 6 Hz tremble of the foot 25 s after the
    last stride reads as a freeze episode, left out; with a stride 2 s before it, kept (before: kept both times)."""
    from types import SimpleNamespace

    from pdrlearn.track.freezes import foot_freezes

    rng = np.random.default_rng(12063)
    t = np.arange(0.0, 60.0, 0.02)
    tremble = ((t >= 30.0) & (t < 37.0)) * 2.0 * np.sin(2 * np.pi * 6.0 * t)
    acc = np.column_stack([np.zeros_like(t), np.zeros_like(t), 9.80665 + tremble]) + rng.normal(0, 0.02, (len(t), 3))
    session = SimpleNamespace(streams={"fAccelerometer": SimpleNamespace(t=t, values=acc)})
    far = pd.DataFrame({"start_s": [2.0, 3.0], "end_s": [3.0, 4.0]})
    rows, lines = foot_freezes(session, "plasys", far)
    assert rows == [] and len(lines) == 1 and "L617" in lines[0]
    near = pd.DataFrame({"start_s": [2.0, 27.0], "end_s": [3.0, 28.0]})
    rows, lines = foot_freezes(session, "plasys", near)
    assert len(rows) == 1 and 27.0 <= rows[0]["start_s"] <= 33.0 and lines == []


def test_a_long_freeze_of_gait_is_no_vehicle_l616_amended():
    """L616 amended: a 20 s freeze of gait (the foot trembling at 3-8 Hz in place) vibrates above 0.15 m/s^2 but its
    freeze-index episodes cover it: no vehicle row (before the guard: "vehicle", as users 12060-12069 read)."""
    s = simulate_path(parse_route("stand:3, straight:10, freeze:20, straight:10, stand:3"),
                      UserProfile.from_seed(12066), seed=12066, scenario="route")
    r, _ = _track(s)
    assert not [x for x in r.info.get("rides") or [] if x["kind"] == "vehicle"]
    assert not any("L616" in w for w in r.info["warnings"])
