"""Decisions W155, W157, W158 (trial 26, "building"): a lower-back track on stairs names ``stairs_length`` when it
is off and leaves stair steps out of W100's walk ratio; start-stop micro-bouts (a queue) warn; a lift ride's
barometric height belongs to the standstill (``pause_dz_m``, bouts' ``altitude_change_before_m``), not to the next
step or walking bout."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import _walk_ratio
from pdrlearn.waist.params import WaistParams
from pdrlearn.waist.plausibility import micro_bout_message, micro_bouts


def _sim(tmp_path_factory, name: str, *args: str):
    out = tmp_path_factory.mktemp(name) / name
    assert main(["simulate", *args, "--user-seed", "3", "--out", str(out)]) == 0
    return read_session(out)


@pytest.fixture(scope="module")
def storey(tmp_path_factory):
    return _sim(tmp_path_factory, "storey", "--route", "straight:4, up:18, straight:4, turn:180, down:18, straight:4")


@pytest.fixture(scope="module")
def queue(tmp_path_factory):  # the trial's queue: 12 x (a 4 s stand, 0.5 m) in 0.2 m steps of 0.7 s
    return _sim(tmp_path_factory, "queue", "--route", ", ".join(["stand:4, straight:0.5"] * 12),
                "--step-length", "0.2", "--step-time", "0.7")


def _has(res, decision: str) -> bool:
    return any(f"decision {decision}" in w for w in res.info["warnings"])


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_a_counted_stair_climb_names_stairs_length_unless_it_is_on(storey, pipeline):  # W155
    off = get_pipeline(pipeline)(storey)
    assert _has(off, "W155") and any("stairs_length" in w for w in off.info["warnings"])
    assert evaluate_track(off, storey)["floors_up"] == 1
    assert not _has(get_pipeline(pipeline)(storey, stairs_length=True), "W155")


def test_a_level_walk_with_stops_has_neither_line(tmp_path_factory):  # W155, W157
    s = _sim(tmp_path_factory, "level", "--route", "straight:15, stand:5, straight:10, turn:90, stand:3, straight:10")
    for pipeline in ("waist-pendulum", "waist-pll"):
        res = get_pipeline(pipeline)(s)
        assert not _has(res, "W155") and not _has(res, "W157")


def test_stair_steps_are_left_out_of_the_walk_ratio(storey):  # W155 (trial finding 12)
    res = get_pipeline("waist-pendulum")(storey, stairs_length=True)
    st = res.steps["stairs"].to_numpy(bool)
    assert st.sum() >= 20
    p = WaistParams()
    steps = res.steps.assign(length_m=np.where(st, 0.05, res.steps["length_m"]))  # a stair step read very short
    shuffle = _walk_ratio(steps, p, "waist-pendulum", False, 1.73)  # every step judged: a shuffling gait
    assert shuffle[1] is not None and "short-stepping" in shuffle[1]
    level = _walk_ratio(steps, p, "waist-pendulum", False, 1.73, stairs=lambda t: t["stairs"].to_numpy(bool))
    assert level[1] is None and level[0] > shuffle[0]


def test_micro_bouts_count_the_short_sequences_and_their_share():  # W157
    has_next = np.array([1, 1, 0, 1, 1, 1, 1, 0, 1, 0], dtype=bool)  # sequences of 2, 4 and 1 steps
    length = np.array([0.5, 0.5, 0, 0.6, 0.6, 0.6, 0.6, 0, 0.4, 0])
    assert micro_bouts(length, has_next) == (2, 3, pytest.approx(1.4), pytest.approx(3.8))
    assert micro_bout_message(5, 6, 5.0, 10.0) is not None
    assert micro_bout_message(4, 6, 9.0, 10.0) is None and micro_bout_message(5, 6, 4.9, 10.0) is None


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_a_queue_shuffle_warns_by_default(queue, pipeline):  # W157
    res = get_pipeline(pipeline)(queue)
    assert _has(res, "W157")
    ref = 6.0
    assert res.steps["length_m"].abs().sum() > 1.5 * ref  # the reading the line is about: long


@pytest.fixture(scope="module")
def lift(tmp_path_factory):
    """10 m, a 30 s stand whose barometer rises 9 m (a lift, 10-16 s into it), 10 m (the trial's inject.py)."""
    from pdrlearn.kernels.barometer import altitude_m, pressure_hpa

    out = tmp_path_factory.mktemp("lift") / "lift"
    assert main(["simulate", "--route", "straight:10, stand:30, straight:10", "--user-seed", "3",
                 "--out", str(out)]) == 0
    walk = get_pipeline("waist-pendulum")(read_session(out)).steps
    t_stop = float(walk.loc[~walk["has_next"].to_numpy(bool), "end_s"].iloc[0])
    b = pd.read_csv(out / "wBarometer.csv")
    t = b["timestamp"].to_numpy(float) / 1000.0
    ride = 9.0 * np.clip((t - t_stop - 10.0) / 6.0, 0.0, 1.0)
    p0 = 1013.25
    b["x"] = pressure_hpa(altitude_m(b["x"].to_numpy(float), p0) + ride, p0)
    b.to_csv(out / "wBarometer.csv", index=False, float_format="%.5f")
    return read_session(out)


def test_a_lift_ride_is_the_pause_s_not_the_next_step_s(lift):  # W158
    res = get_pipeline("waist-pendulum")(lift)
    st = res.steps
    after = int(np.flatnonzero(~st["has_next"].to_numpy(bool))[0]) + 1  # the first step after the stand
    assert st["pause_dz_m"].iloc[after] == pytest.approx(9.0, abs=0.3)
    assert abs(st["dz_m"].iloc[after]) < 0.3 and np.abs(st["dz_m"]).max() < 0.3
    z = res.trajectory["z"].to_numpy()
    assert np.allclose(np.cumsum(st["dz_m"] + st["pause_dz_m"]), z[1:] - z[0])
    bouts = detected_bouts(st)
    assert len(bouts) == 2
    assert bouts["altitude_change_before_m"].iloc[1] == pytest.approx(9.0, abs=0.3)
    assert np.abs(bouts["altitude_change_m"]).max() < 0.3
    ev = evaluate_track(res, lift)
    assert (ev["floors_up"], ev["floors_down"]) == (3, 0)  # the ride still changes floors


def test_stairs_length_climbs_bounds_only_the_climb_steps(storey):  # W156 (an option; its rule was not met)
    off = get_pipeline("waist-pendulum")(storey)
    on = get_pipeline("waist-pendulum")(storey, stairs_length="climbs")
    changed = on.steps["length_m"].to_numpy() != off.steps["length_m"].to_numpy()
    assert changed.sum() >= 8 and (on.steps["length_m"].to_numpy()[changed] == 0.30).all()
    assert changed[on.steps["stairs"].to_numpy(bool)].sum() == changed.sum()  # inside W91's stairs, W108's climbs
    assert not _has(on, "W155")
    assert get_pipeline("waist-pendulum")(storey).info["options"]["stairs_length"] is False  # the default


def test_an_unknown_stairs_length_is_refused(storey):  # W156
    from pdrlearn.errors import DataError

    with pytest.raises(DataError, match="stairs_length 'yes'.*climbs"):
        get_pipeline("waist-pendulum")(storey, stairs_length="yes")


def test_the_start_stop_line_states_no_direction_w402():  # W402: T2's stop-and-go read -22.8 % under "reads long"
    line = micro_bout_message(7, 8, 5.0, 6.0)
    assert "reads long" not in line
    assert "too short or too long" in line and "-30 to +220 %" in line and "decision W402" in line
