"""Session 35, trials T3 finding 1 / 9 and T1 finding 2: a slow stair climb tracked by the foot, and force-free
simulated feet. Decisions S77 (diagnosis), steps 61 (not adopted: the option), L430, L431, S78. Fresh users
8450-8469 only."""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import summary_warnings

UP = "stand:3, straight:2, up:12:0.17:0.29, straight:2, stand:3"


def _slow_up(uid: int, step_s: float = 1.2):
    """Trial T3's route at ``--speed slow --step-time 1.2 --rate 100`` (S30's walked step time)."""
    user = dataclasses.replace(UserProfile.from_seed(uid), step_time_s=step_s / SPEED_FACTORS["slow"][1])
    return simulate_path(parse_route(UP), user, speed="slow", rate_hz=100.0)


def _warnings(session, **kw) -> list[str]:
    res = get_pipeline("plasys")(session, **kw)
    summary = res.summary(session)
    return [*summary["info"]["warnings"], *summary_warnings(summary)]


@pytest.fixture(scope="module")
def slow_up_8450():
    return _slow_up(8450)


def test_offline_floor_window_default_and_option_61(slow_up_8450):
    """Steps decision 61 (not adopted): the offline rest keeps L27's 1.0 s window; 2.0 s is the option, and on T3's
    route it removes the rest the default finds in the first stair swing (S77: floor 0.85 rad/s, threshold 1.70)."""
    from pdrlearn.displace.foot import OFFLINE_FLOOR_WINDOW_S, inertial_stance
    from pdrlearn.orient import unit_data

    assert OFFLINE_FLOOR_WINDOW_S == 1.0
    s = slow_up_8450
    foot = unit_data(s, "foot", purpose="test")
    lab = s.steps[s.steps["kind"] == "stairs_up"].iloc[0]
    tc, ic = float(lab["tc_s"]), float(lab["ic_s"])
    swing = (foot.t > tc + 0.05) & (foot.t < ic - 0.05)
    assert inertial_stance(foot.acc, foot.gyr, foot.fs, rhythm_frac=0)[swing].any()
    assert not inertial_stance(foot.acc, foot.gyr, foot.fs, floor_window_s=2.0, rhythm_frac=0)[swing].any()
    # decision L597 (session 42): the foot's slow rhythm (stride period 2.32 s here) drops that swing's rest by default
    assert not inertial_stance(foot.acc, foot.gyr, foot.fs)[swing].any()


def test_steep_stride_check_counts_strides_steeper_than_a_stair_l430():
    from pdrlearn.kernels.altitude_check import STEEPEST_STAIR_DEG, steep_stride_check

    assert STEEPEST_STAIR_DEG == 60.0
    # the T3 track's strides: 0.11-0.20 m long for 0.26-0.35 m of height (4 steeper than 60 deg), a real stair
    # stride 0.58 m for 0.34 m, a level one
    length = np.array([0.11, 0.15, 0.20, 0.19, 0.15, 0.13, 0.58, 1.30])
    dz = np.array([-0.35, -0.34, -0.26, -0.27, -0.30, -0.31, 0.34, 0.02])
    line, info = steep_stride_check(length, dz)
    assert info["steep_strides"] == 4 and info["strides_with_height"] == 7
    assert line is not None and "4 of the 7 strides" in line and "L430" in line
    # one steep stride is no warning; stairs as the real gaitmap ones (0.6 m for 0.3 m) neither
    assert steep_stride_check(np.array([0.1, 0.6]), np.array([0.3, 0.3]))[0] is None
    assert steep_stride_check(np.full(16, 0.62), np.full(16, 0.31))[0] is None


def test_slow_stair_track_is_a_climb_since_steps_70_and_no_steep_stride_line_l430(slow_up_8450):
    """Decision L430: trial T3's slow ascent was read as a descent (its slow swings' lulls split the strides) and got
    the steep-stride line. Since steps 70 / 71 (session 37) a lull the insoles leave unloaded between two loaded
    rests is no rest: the same session tracks its 10 strides as the climb it is (12 x 0.17 m) and the line, whose
    kernel ``test_steep_stride_check_counts_strides_steeper_than_a_stair_l430`` pins, no longer fires; the same
    stairs at the user's normal step neither."""
    res = get_pipeline("plasys")(slow_up_8450)
    assert len(res.steps) == 10 and res.steps["dz_m"].sum() == pytest.approx(12 * 0.17, abs=0.15)
    assert not [w for w in _warnings(slow_up_8450) if "slope allows" in w]
    normal = simulate_path(parse_route(UP), UserProfile.from_seed(8451), speed="normal", rate_hz=100.0)
    assert not [w for w in _warnings(normal) if "slope allows" in w]


def test_track_and_steps_agree_on_the_slow_cadence_l431(caplog):
    """Decision L431: user 8454 at a 1.2 s step: the track's split strides gave a median cadence inside L95's range
    (71 steps/min) and L431's line said the contacts' 53. Since steps 70 / 71 (session 37) the strides are not split:
    the track's own cadence is the slow one and L95's line says it, with the cadence `pdrlearn steps` counts."""
    from pdrlearn.cli.steps import cadence_range_warning
    from pdrlearn.steps import get_detector
    from pdrlearn.steps.strides import one_per_stride

    s = _slow_up(8454)
    res = get_pipeline("plasys")(s)
    summary = res.summary(s)
    assert summary["median_cadence_spm"] < 68  # the slow walk's own cadence, below L95's range
    lines = [w for w in summary_warnings(summary) if "slower than the walking" in w]
    assert len(lines) == 1 and "L431" not in lines[0]
    table, _ = one_per_stride(get_detector("accel").detect(s), s, force=False)
    steps_line = cadence_range_warning(table, s.meta, "foot")
    assert steps_line is not None and "slower than the walking" in steps_line
    cad = float(lines[0].split("median cadence ")[1].split(" ")[0])
    assert abs(cad - float(steps_line.split("median cadence ")[1].split(" ")[0])) <= 2  # two detectors: 52 / 53


def test_contact_cadence_line_only_when_the_track_line_is_silent_l431():
    from pdrlearn.track.gait import contact_cadence_warning, gait_range_warning

    summ = {"median_cadence_spm": 70.4, "median_speed_mps": None, "n_stair_strides": 9, "n_straight_strides": 2,
            "info": {"contact_cadence_spm": 52.0}}
    assert gait_range_warning(summ) is None
    assert "median cadence 52 steps/min" in contact_cadence_warning(summ)
    assert contact_cadence_warning({**summ, "info": {"contact_cadence_spm": 104.0}}) is None
    assert contact_cadence_warning({**summ, "median_cadence_spm": 52.0}) is None  # L95's own line says it


def _level(rocker: str = "hermite", force: bool = False):
    s = simulate_path(parse_route("stand:3, straight:12, stand:3"), UserProfile.from_seed(8455), speed="normal",
                      rate_hz=100.0, rocker=rocker)
    if force:
        return s
    return dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if not k.startswith("fForce")})


@pytest.mark.parametrize(("rocker", "force", "told"), [("hermite", False, True), ("smooth", False, False),
                                                       ("hermite", True, False)])
def test_force_free_simulated_hermite_feet_are_told_s78(rocker, force, told):
    """Decision S78 (trial T1 finding 2): a force-free foot track of a simulated session with the default Hermite
    rocker says its contacts can read ~+100 ms late; `--rocker smooth` or the insoles: no line."""
    logging.disable(logging.NOTSET)
    lines = [w for w in _warnings(_level(rocker, force)) if "Hermite heel rocker" in w]
    assert len(lines) == int(told)
    if told:
        assert "--rocker smooth" in lines[0] and "S78" in lines[0]


@pytest.mark.parametrize("case", ["real_gaitmap", "meta_not_sim"])
def test_real_force_free_feet_are_not_told_s78(case):
    """Decision S78 amended (session 35, review R3 finding 5): a real force-free foot recording (gaitmap's level walk,
    no fForce files, no knobs) and a session whose meta.json names another source project (the simulator's knobs
    kept) get no Hermite line: fails when the source_project check is removed."""
    from pathlib import Path

    from pdrlearn.io import read_session

    logging.disable(logging.NOTSET)
    if case == "real_gaitmap":
        folder = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_left"
        if not folder.is_dir():
            pytest.skip("datasets/real not here")
        session = read_session(folder)
    else:
        session = _level()
        session.meta = {**session.meta, "source_project": "gaitmap"}
    assert not [w for w in _warnings(session) if "Hermite heel rocker" in w]


def test_ignore_force_on_simulated_insoles_says_so_s78():
    """Decision S78 amended (review R3 finding 5): `--ignore-force` on a simulated session that has its insoles is told
    the foot is tracked without force sensors, not that it has none."""
    logging.disable(logging.NOTSET)
    lines = [w for w in _warnings(_level(force=True), ignore_force=True) if "Hermite heel rocker" in w]
    assert len(lines) == 1 and "has no force sensors" not in lines[0] and "--ignore-force" in lines[0]
