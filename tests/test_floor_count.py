"""Decision L64: the storeys a track climbed and descended (``floors_up`` / ``floors_down``) and the floor it
ends on (``storeys_changed``), counted from its altitude in storeys of ``STOREY_HEIGHT_M`` (3.0 m) with a band
of 0.4 storey around each floor, in ``evaluate_track`` (so ``track`` and ``run`` summaries alike)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import STOREY_HEIGHT_M, count_floors, evaluate_track


def _flight(z0: float, storeys: float, stairs: int = 18) -> np.ndarray:
    return z0 + np.linspace(0.0, storeys * 3.06, stairs + 1)[1:]  # the simulator's 18 x 0.17 m storey


def test_a_storey_up_and_down_counts_one_each():
    z = np.concatenate([[0.0, 0.0], _flight(0.0, 1), [3.06, 3.06], _flight(3.06, -1)])
    assert count_floors(z) == (1, 1, 0)


@pytest.mark.parametrize("height", [2.5, 3.06, 3.8])  # thesis ch.4 Figure 44 storey, the simulator's, scenario D
def test_one_storey_of_the_thesis_heights_is_one_floor(height):
    assert count_floors(np.linspace(0.0, height, 23)) == (1, 0, 1)
    assert count_floors(np.linspace(0.0, -height, 23)) == (0, 1, -1)


def test_two_up_one_down_and_half_storey_landings():
    """Two storeys up with a landing at each half storey, one down: the landings are no floor."""
    up = np.concatenate([_flight(0.0, 0.5, 9), [1.53] * 3, _flight(1.53, 0.5, 9), [3.06] * 3,
                         _flight(3.06, 0.5, 9), [4.59] * 3, _flight(4.59, 0.5, 9)])
    z = np.concatenate([[0.0], up, [6.12] * 4, _flight(6.12, -1)])
    assert count_floors(z) == (2, 1, 1)


def test_sway_and_drift_inside_a_floor_do_not_count():
    rng = np.random.default_rng(0)
    z = 0.3 * np.sin(np.linspace(0, 60, 400)) + rng.normal(scale=0.1, size=400)  # +-0.4 m around the start
    assert count_floors(z) == (0, 0, 0)
    # hovering at the edge of a floor's band enters it once, and leaves it only inside another floor's band
    edge = 0.6 * STOREY_HEIGHT_M
    assert count_floors([0.0, edge - 0.05, edge + 0.05, edge - 0.05, edge + 0.05, edge - 0.05]) == (1, 0, 1)
    assert count_floors([]) == (0, 0, 0)
    assert count_floors([np.nan, 0.0, 3.0, np.nan]) == (1, 0, 1)


def test_a_storey_count_depends_on_the_storey_height():
    assert count_floors(np.linspace(0.0, 6.0, 30)) == (2, 0, 2)
    assert count_floors(np.linspace(0.0, 6.0, 30), storey_height_m=2.0) == (3, 0, 3)


def test_the_summary_counts_the_tracked_and_the_reference_storeys(tmp_path, capsys):
    """A simulated walk up two storeys, along the top, and one storey down, tracked with the oracle's classes;
    ``pdrlearn track`` says the count in its one line."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route("straight:2, up:18, turn:180, up:18, straight:2, turn:180, down:18, straight:2"),
                      UserProfile.from_seed(3), speed="normal", rate_hz=20.0, seed=0, name="floors")
    out = evaluate_track(track_plasys(s, method="M3", model="oracle"), s)
    write_session(s, tmp_path / "floors")
    assert main(["track", "--no-plot", str(tmp_path / "floors"), "--method", "M3", "--model", "oracle",
                 "--out", str(tmp_path / "t")]) == 0
    assert "floors up 2 / down 1" in capsys.readouterr().out
    assert (out["floors_up_ref"], out["floors_down_ref"], out["storeys_changed_ref"]) == (2, 1, 1)
    assert (out["floors_up"], out["floors_down"], out["storeys_changed"]) == (2, 1, 1)
    assert out["storey_height_m"] == STOREY_HEIGHT_M
    # a level track: no floor changes, and the keys are there
    level = TrackResult(steps=pd.DataFrame({"start_s": [0.0], "end_s": [1.0], "length_m": [1.0],
                                            "heading_rad": [0.0], "dz_m": [0.0]}),
                        trajectory=pd.DataFrame({"t": [0.0, 1.0], "x": [0.0, 1.0], "y": 0.0, "z": 0.0}), info={})
    assert (evaluate_track(level)["floors_up"], evaluate_track(level)["floors_down"]) == (0, 0)


def _stairs_dz(storeys: float, stairs: int = 17, rise: float = 0.17) -> np.ndarray:
    """One foot's stride heights up a flight (two stairs per stride, the last stride one stair when odd)."""
    n = int(round(abs(storeys) * stairs))
    return np.sign(storeys) * np.array([2 * rise] * (n // 2) + [rise] * (n % 2))


def test_floors_per_climb_are_immune_to_a_slow_drift():
    """Decision L127 (trial "responder", session 21): ten loops of 2 storeys up and down whose altitude sinks
    0.1 m per loop between the climbs (the streamed drift of L126): L64's absolute bands lose the late loops'
    second floor, the count per climb does not."""
    from pdrlearn.track.evaluate import count_floors_by_climb

    loop = np.concatenate([np.zeros(10), _stairs_dz(1), np.zeros(2), _stairs_dz(1), np.full(20, -0.1 / 20),
                           _stairs_dz(-1), np.zeros(2), _stairs_dz(-1), np.zeros(30)])
    dz = np.tile(loop * np.where(loop > 0, 0.97, 1.0), 10)  # climbs 3 % short, as streamed (L126)
    assert count_floors_by_climb(dz) == (20, 20, 0)
    assert count_floors(np.concatenate([[0.0], np.cumsum(dz)]))[:2] != (20, 20)  # L64's count misses floors
    assert count_floors_by_climb(dz, storey_height_m=2.89) == (20, 20, 0)


def test_a_climb_bridges_a_landing_and_counts_by_the_band():
    from pdrlearn.track.evaluate import count_floors_by_climb

    half = _stairs_dz(0.5)  # 9 stairs: 1.53 m
    landing = np.zeros(4)  # a U-turn on the landing: one climb
    assert count_floors_by_climb(np.concatenate([half, landing, half])) == (1, 0, 1)
    assert count_floors_by_climb(np.concatenate([half, np.zeros(5), half])) == (0, 0, 0)  # two half storeys apart
    assert count_floors_by_climb(half) == (0, 0, 0)  # a half-storey landing is no floor (L64's band)
    assert count_floors_by_climb(np.full(400, 0.09)) == (0, 0, 0)  # level strides (< 0.10 m) never climb
    assert count_floors_by_climb([np.nan, 0.34, np.inf] + [0.34] * 8) == (1, 0, 1)
    assert count_floors_by_climb([]) == (0, 0, 0)


def test_foot_and_waist_tracks_count_per_climb():
    """Decisions L127, L172: foot strides and lower-back steps alike count per climb from their own dz, so the 2 m
    the z drifts between the climbs moves no count; a lower-back step is half a stride, so its climb bridges 8
    steps (L127's 4 strides), a foot climb 4 strides."""
    dz = np.concatenate([_stairs_dz(1), np.zeros(40), _stairs_dz(-1)])  # level strides between the climbs
    z = np.concatenate([[0.0], np.cumsum(dz)]) - np.linspace(0.0, 2.0, len(dz) + 1)  # the z drifts 2 m down
    steps = pd.DataFrame({"start_s": np.arange(len(dz), dtype=float), "end_s": np.arange(1, len(dz) + 1, dtype=float),
                          "length_m": 0.7, "heading_rad": 0.0, "dz_m": dz, "unit": "foot"})
    traj = pd.DataFrame({"t": np.arange(len(z), dtype=float), "x": 0.0, "y": 0.0, "z": z})
    out = evaluate_track(TrackResult(steps=steps, trajectory=traj, info={}), storey_height_m=2.89)
    assert (out["floors_up"], out["floors_down"], out["storey_height_m"]) == (1, 1, 2.89)
    waist = evaluate_track(TrackResult(steps=steps.assign(unit="waist"), trajectory=traj, info={}))
    assert (waist["floors_up"], waist["floors_down"]) == (1, 1)
    assert count_floors(z)[:2] != (1, 1)  # L64's bands on the drifting z miss the way down
    half = _stairs_dz(0.5)  # 1.53 m, a U-turn on a landing of 6 steps, 1.53 m: one storey on the lower back
    dz2 = np.concatenate([half, np.zeros(6), half])
    st2 = pd.DataFrame({"start_s": np.arange(len(dz2), dtype=float), "end_s": np.arange(1, len(dz2) + 1.0),
                        "length_m": 0.7, "heading_rad": 0.0, "dz_m": dz2})
    tr2 = pd.DataFrame({"t": np.arange(len(dz2) + 1, dtype=float), "x": 0.0, "y": 0.0,
                        "z": np.concatenate([[0.0], np.cumsum(dz2)])})
    assert evaluate_track(TrackResult(steps=st2.assign(unit="waist"), trajectory=tr2, info={}))["floors_up"] == 1
    assert evaluate_track(TrackResult(steps=st2.assign(unit="foot"), trajectory=tr2, info={}))["floors_up"] == 0
    with pytest.raises(ValueError, match="storey height"):
        evaluate_track(TrackResult(steps=steps, trajectory=traj, info={}), storey_height_m=0.0)


def test_a_flat_lower_back_walk_with_the_weather_drift_counts_no_floor_and_no_ascent():
    """Decision L172 (trial "longhaul", finding 1): 73 min of level walking whose barometer drifts 4.67 m (the
    simulator's 0.3 hPa/h, the weather's) counted floors_up 1 and ascent 4.67 m on the lower back; now no floor, no
    ascent, the drift is ``altitude_drift_m`` and one warning names it; a storey of 18 stair steps still counts."""
    from pdrlearn.track.evaluate import drift_warning

    t = np.arange(0.0, 73 * 60.0, 0.5)  # a step every 0.5 s
    z = 4.67 * t / t[-1]
    steps = pd.DataFrame({"start_s": t[:-1], "end_s": t[1:], "length_m": 0.7, "heading_rad": 0.0,
                          "dz_m": np.diff(z), "unit": "waist"})
    flat = evaluate_track(TrackResult(steps=steps, trajectory=pd.DataFrame({"t": t, "x": 0.0, "y": 0.0, "z": z}),
                                      info={}))
    assert (flat["floors_up"], flat["floors_down"]) == (0, 0)
    assert flat["ascent_m"] < 0.5 and flat["descent_m"] == 0.0
    assert flat["altitude_drift_m"] == pytest.approx(4.67, abs=0.5)
    assert "drifted +4.67 m slowly" in drift_warning(flat)
    climb = np.clip((t - 1000.0) / 9.0, 0.0, 1.0) * 3.06  # 18 stair steps of 0.17 m in 9 s
    steps2 = steps.assign(dz_m=np.diff(z + climb))
    up = evaluate_track(TrackResult(steps=steps2, trajectory=pd.DataFrame({"t": t, "x": 0.0, "y": 0.0, "z": z + climb}),
                                    info={}))
    assert (up["floors_up"], up["floors_down"]) == (1, 0)
    assert up["ascent_m"] == pytest.approx(3.06, abs=0.5) and up["altitude_drift_m"] == pytest.approx(4.67, abs=0.5)


def test_loops_of_floors_count_exactly_offline_and_streamed_and_say_the_barometer_is_unused(tmp_path, capsys):
    """Decisions L126/L127: a short multi-loop session (3 x 2 storeys up and down, 17 stairs of 0.17 m per
    storey) counts 6 / 6 offline and streamed; the one-line summary says the barometer file was not used and the
    storey height given."""
    import json

    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    loop = "straight:3, up:17, turn:180, up:17, straight:3, turn:180, down:17, turn:180, down:17, straight:3, turn:180"
    s = simulate_path(parse_route(", ".join(["stand:5"] + [loop] * 3)), UserProfile.from_seed(7), speed="normal",
                      rate_hz=20.0, seed=1, name="loops")
    write_session(s, tmp_path / "loops")
    for extra in ([], ["--streaming"]):
        out = tmp_path / f"t{len(extra)}"
        assert main(["track", "--no-plot", str(tmp_path / "loops"), "--method", "M3", "--model", "oracle",
                     "--storey-height",
                     "2.89", "--out", str(out), *extra]) == 0
        summary = json.loads((out / "summary.json").read_text())
        assert (summary["floors_up"], summary["floors_down"], summary["storeys_changed"]) == (6, 6, 0)
        assert summary["barometer_unused"] is True and summary["storey_height_m"] == 2.89
        # L378: the foot track reads the waist barometer for its rides only (none on these stairs); since E293
        # (session 45) `track --streaming` reads the rides as offline does, so it says the same
        used = "wBarometer.csv read for rides only, L378)"
        assert f"floors up 6 / down 6 (foot altitude, storeys of 2.89 m; {used}" in capsys.readouterr().out
