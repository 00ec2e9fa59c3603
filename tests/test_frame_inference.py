"""Axis frames inferred from the data when meta.json declares none (decision D8, docs/frames.md)."""

from __future__ import annotations

import json
import logging
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.frames import _DIRECTIONS, AxisFrame
from pdrlearn.track.frame_inference import (
    FrameInferenceError,
    frame_from_axes,
    infer_session_frame,
    infer_waist_frame,
    remount,
    right_handed_orientations,
    swing_pitch_extremes,
)
from tests.cli_helpers import json_numbers

ORIENTATIONS = right_handed_orientations()


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("A", user_seed=1)  # foot + waist, 20 Hz, straights, curves, stairs


def _yawed(session, placement: str, deg: float):
    """The unit turned by ``deg`` about its up axis (a mount square to no body axis at 45 deg)."""
    up = session.frames[placement].matrix().T @ np.array(_DIRECTIONS["up"])
    return remount(session, placement, Rotation.from_rotvec(np.radians(deg) * up).as_matrix().T)


def _pitched(session, deg: float):
    """The foot unit pitched ``deg`` toes-down (a rotation about the body's left, right-hand rule)."""
    left = session.frames["foot"].matrix().T @ np.array(_DIRECTIONS["left"])
    return remount(session, "foot", Rotation.from_rotvec(np.radians(deg) * left).as_matrix().T)


def test_orientations_are_the_24_right_handed_signed_permutations():
    assert len(ORIENTATIONS) == 24
    assert len({tuple(P.ravel()) for P in ORIENTATIONS}) == 24
    assert all(np.isclose(np.linalg.det(P), 1.0) and np.allclose(np.abs(P).sum(0), 1) for P in ORIENTATIONS)


def test_frame_from_axes_hand_computed():
    # thesis foot: x toward the toes, y up, z right -> forward = +x, left = -z, up = +y
    assert frame_from_axes((0, 1.0), (2, -1.0), (1, 1.0)) == AxisFrame(x="forward", y="up", z="right")
    assert frame_from_axes((2, 1.0), (1, -1.0), (0, 1.0)) == AxisFrame(x="up", y="right", z="forward")


def _synthetic_waist(fs=100.0, seconds=30.0, lead_deg=60.0):
    """FLU specific force of a walking pelvis: vertical and forward oscillation at the 1.8 Hz step frequency
    (forward leading by ``lead_deg``), lateral sway at the 0.9 Hz stride frequency, plus gravity."""
    t = np.arange(int(seconds * fs)) / fs
    w = 2 * np.pi * 1.8
    rng = np.random.default_rng(0)
    acc = np.column_stack([1.5 * np.cos(w * t + np.radians(lead_deg)), 0.8 * np.cos(0.5 * w * t),
                           9.81 + 2.0 * np.cos(w * t)]) + 0.05 * rng.standard_normal((len(t), 3))
    return acc, fs


@pytest.mark.parametrize("k", range(24))
def test_synthetic_waist_in_every_orientation(k):
    acc_flu, fs = _synthetic_waist()
    P = ORIENTATIONS[k]  # sensor axes: v_sensor = P v_body, so the frame's matrix is P^T
    got = infer_waist_frame(acc_flu @ P.T, np.zeros_like(acc_flu), fs).frame
    assert np.allclose(got.matrix(), P.T), (got, P)


def test_synthetic_waist_walking_backward_flips_forward():
    """W2: a forward acceleration lagging the vertical one (backward walking) points the other way."""
    acc, fs = _synthetic_waist(lead_deg=60.0 + 180.0)
    assert infer_waist_frame(acc, np.zeros_like(acc), fs).frame == AxisFrame(x="backward", y="right", z="up")


def test_synthetic_waist_ambiguous_raises():
    acc, fs = _synthetic_waist()
    acc[:, 0] = acc[:, 2] - 9.81 + 0.05 * np.random.default_rng(1).standard_normal(len(acc))  # ML sway lost,
    acc[:, 1] = acc[:, 0]  # both horizontal axes carry the same step-frequency motion
    with pytest.raises(FrameInferenceError):
        infer_waist_frame(acc, np.zeros_like(acc), fs)
    still = np.tile([0.0, 0.0, 9.81], (3000, 1))
    with pytest.raises(FrameInferenceError, match="walking"):
        infer_waist_frame(still, np.zeros_like(still), 100.0)


@pytest.mark.parametrize("fs,seconds", [(20.0, 60.0), (100.0, 60.0), (100.0, 10.0)])
def test_waist_noise_without_a_walking_rhythm_is_refused(fs, seconds):
    """Gravity + white noise moves enough for the motion gate and often shows a dominant horizontal axis by
    chance (review: 40 of 200 got a frame); with no repeating step it is refused. The same noise on top of
    the rhythmic synthetic walk is still inferred (the gate is about the rhythm, not the noise)."""
    rng = np.random.default_rng(3)
    n = int(fs * seconds)
    for _ in range(10):
        noise = rng.normal(0.0, 1.5, (n, 3))
        acc = np.array([0.0, 9.81, 0.0]) + noise
        with pytest.raises(FrameInferenceError, match="no walking rhythm"):
            infer_waist_frame(acc, np.zeros_like(acc), fs)
    walk, fs_w = _synthetic_waist(fs=fs, seconds=seconds)
    walk = walk + 0.5 * rng.normal(0.0, 1.0, walk.shape)
    assert infer_waist_frame(walk, np.zeros_like(walk), fs_w).frame == AxisFrame(x="forward", y="left", z="up")


@pytest.mark.parametrize("placement", ["foot", "waist"])
def test_simulated_session_in_every_orientation(walk, placement):
    wrong = []
    for P in ORIENTATIONS:
        s = remount(walk, placement, P)
        got = infer_session_frame(s, placement).frame
        if got != s.frames[placement]:
            wrong.append((s.frames[placement].to_dict(), got.to_dict()))
    assert not wrong, wrong


@pytest.mark.parametrize("deg", [-20.0, 15.0, 50.0])
def test_pitched_foot_mount_maps_to_the_nominal_frame(walk, deg):
    """An instep mount pitched toes-down (gaitmap: 45-53 deg) keeps x forward: the mounting window."""
    s = _pitched(walk, deg)
    assert "foot" not in s.frames  # a pitch is not a signed permutation: nothing declared
    assert infer_session_frame(s, "foot").frame == walk.frames["foot"]


def test_foot_pitch_beyond_the_window_takes_the_other_axis_and_its_edge_is_refused(walk):
    # 70 deg toes-down: the thesis 'up' axis (y) is now 20 deg above forward, x points mostly down
    assert infer_session_frame(_pitched(walk, 70.0), "foot").frame == AxisFrame(x="down", y="forward", z="right")
    with pytest.raises(FrameInferenceError, match="edge"):
        infer_session_frame(_pitched(walk, 58.0), "foot")


@pytest.mark.parametrize("placement", ["foot", "waist"])
def test_yawed_45_degrees_is_ambiguous(walk, placement):
    with pytest.raises(FrameInferenceError, match="deg from"):
        infer_session_frame(_yawed(walk, placement, 45.0), placement)
    assert infer_session_frame(_yawed(walk, placement, 15.0), placement).frame == walk.frames[placement]


@pytest.mark.parametrize("rate", [20.0, 100.0])
def test_foot_mostly_walking_backward_is_refused_not_reversed(rate):
    """Review: 3 forward + 13 backward strides gave a reversed frame (x backward) and a mirrored track. The
    strides' mean direction is backward, but the foot does not push off toes-down relative to it: refused."""
    from pdrlearn.sim import Backward, Stand, Straight, UserProfile, simulate_path

    s = simulate_path([Straight(3.0), Stand(1.0), Backward(12), Stand(1.0), Backward(12)], UserProfile.from_seed(1),
                      rate_hz=rate)
    with pytest.raises(FrameInferenceError, match="no forward push-off"):
        infer_session_frame(s, "foot")
    # mostly forward with a backward stretch in the middle: still inferred, and right
    s = simulate_path([Straight(12.0), Stand(1.0), Backward(8), Stand(1.0), Straight(12.0)], UserProfile.from_seed(1),
                      rate_hz=rate)
    found = infer_session_frame(s, "foot")
    assert found.frame == s.frames["foot"] and "asymmetry" in found.describe()


def test_swing_pitch_extremes_hand_computed():
    fs = 10.0
    left = np.array([0.0, 0.0, -1.0])  # thesis foot: z right
    w = np.zeros((20, 3))
    w[2:5, 2] = -1.0  # 0.3 rad toes-down (about left = -z)
    w[5:7, 2] = 2.0  # then 0.4 rad back: 0.1 rad toes-up
    down, up = swing_pitch_extremes(w, fs, np.array([0, 10]), np.array([10, 20]), left)
    assert np.allclose(down, [0.3, 0.0]) and np.allclose(up, [0.1, 0.0])


def test_foot_walking_back_and_forth_is_refused():
    from pdrlearn.sim import simulate

    s = simulate("direction", user_seed=5)  # the calibration exercise: half of the steps backward
    with pytest.raises(FrameInferenceError, match="no common direction"):
        infer_session_frame(s, "foot")


def test_require_frame_infers_once_warns_and_declared_wins(walk, caplog):
    s = walk.copy()
    declared = dict(s.frames)
    s.frames = {}
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        assert s.require_frame("foot") == declared["foot"]
        assert s.require_frame("foot") == declared["foot"]  # cached: one warning
        assert s.has_frame("waist")
    lines = [r.getMessage() for r in caplog.records]
    assert len(lines) == 2 and all("\n" not in ln for ln in lines), lines
    assert 'inferred from the data: "frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}' in lines[0]
    assert s.frames == {}  # an inferred frame is not written back as declared (write_session)
    assert s.frames_inferred == {"foot": declared["foot"].to_dict(), "waist": declared["waist"].to_dict()}
    odd = AxisFrame(x="left", y="up", z="forward")
    s.frames = {"foot": odd}
    with pytest.raises(DataError, match="turned by 9[01] deg, decision D28"):  # D28: a foot forward turned 90 deg
        s.require_frame("foot")
    s = walk.copy()
    s.frames, s.meta = {"foot": odd}, {**s.meta, "force_frame": True}
    assert s.require_frame("foot") is odd  # forced, a declared frame wins even against the data (D23)
    s = walk.copy()
    s.frames, s.infer_frames = {}, False
    with pytest.raises(DataError, match="declares no axis frame for the foot unit; add"):
        s.require_frame("foot")


def test_not_inferable_keeps_the_one_wording_with_the_reason(walk):
    s = _yawed(walk, "foot", 45.0)
    with pytest.raises(DataError) as exc:
        s.require_frame("foot")
    msg = str(exc.value)
    assert msg.startswith(f"session '{s.name}' (its meta.json) declares no axis frame for the foot unit and its "
                          "data does not fix the axes (the medio-lateral direction is 45 deg"), msg
    assert msg.endswith('"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}') and "\n" not in msg
    assert not s.has_frame("foot")


@pytest.mark.parametrize("name,extra", [("gaitmap_level_left", []),
                                        ("mobgap_HA001_Test5_Trial1", ["--pipeline", "waist-pendulum"])])
def test_cli_track_on_a_stripped_real_session_gives_the_same_numbers(real_dir, tmp_path, capsys, name, extra):
    src = real_dir / name
    if not src.is_dir():
        pytest.skip("real data not bundled")
    stripped = tmp_path / name
    shutil.copytree(src, stripped)
    meta = json.loads((stripped / "meta.json").read_text())
    meta.pop("frames", None)
    meta.pop("source_project")
    (stripped / "meta.json").write_text(json.dumps(meta))
    assert read_session(stripped).frames == {}
    runs = {}
    for key, folder in (("declared", src), ("inferred", stripped)):
        assert main(["track", "--no-plot", str(folder), "--out", str(tmp_path / key), "--json", *extra]) == 0
        cap = capsys.readouterr()
        runs[key] = (json.loads(cap.out), cap.err)
    inferred = [ln for ln in runs["inferred"][1].splitlines() if "inferred from the data" in ln]
    assert len(inferred) == 1 and inferred[0].startswith(f"warning: {stripped / 'meta.json'}"), runs["inferred"][1]
    assert "inferred" not in runs["declared"][1]
    a, b = json_numbers(runs["declared"][0]), json_numbers(runs["inferred"][0])
    assert len(a) >= 5 and a == b
    declared = {p: f.to_dict() for p, f in read_session(src).frames.items()}  # meta.json or source_project
    assert "frames_inferred" not in runs["declared"][0]
    got = runs["inferred"][0]["frames_inferred"]  # what to paste into meta.json: the frames it found
    assert got and all(got[p] == declared[p] for p in got), (got, declared)


def test_foot_pitch_edge_with_a_yaw_is_refused_not_guessed(walk):
    """A yawed mount skews the sagittal axes' projections: at the window's edge none of the four signed axes
    may lie in it. Before: forward fell back to the first sagittal axis with a made-up pitch of 0 deg."""
    left = walk.frames["foot"].matrix().T @ np.array(_DIRECTIONS["left"])
    up = walk.frames["foot"].matrix().T @ np.array(_DIRECTIONS["up"])
    # the unit yawed 15 deg, then pitched 60 deg toes-down (rotations in the old sensor frame)
    R = Rotation.from_rotvec(np.radians(15.0) * up) * Rotation.from_rotvec(np.radians(60.0) * left)
    with pytest.raises(FrameInferenceError, match="edge"):
        infer_session_frame(remount(walk, "foot", R.as_matrix().T), "foot")
