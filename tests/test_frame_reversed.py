"""A declared frame whose forward the data find reversed is refused (decision D23), also when the frame inference
gives up on which axis is forward but measured the strides' direction (decision D22); ``info`` says "not checked"
when the data could not judge a frame; ``import --frames`` refuses a left-handed frame (decision B130).

Session 21's "placement" trial: a foot unit turned 180 deg about y with a -25 deg turn about its z (a heel clip
facing backward) and meta.json's frame left as it was: the inference gave up (pitch at the window edge), D10 was
skipped, every stride tracked backward (final position 41.5 m off, exit 0) and ``info`` said "not contradicted"."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.io.frames import AxisFrame
from pdrlearn.track.frame_inference import FrameInferenceError, infer_session_frame, remount

ROOT = Path(__file__).resolve().parents[1]
HEEL = "y:180,z:-25"  # the trial's heel clip; with user 501's walk the inference gives up at the pitch edge
RIGHT_HEEL = AxisFrame(x="backward", y="up", z="left")  # the nearest-axis frame of that mount


def _turn(spec: str) -> np.ndarray:
    """``v_new = M v_old`` for the unit turned by each ``axis:deg`` of ``spec`` in turn about its own axes (the
    trial's ``bin/xform.py``)."""
    M = np.eye(3)
    for item in spec.split(","):
        k, v = item.split(":")
        M = Rotation.from_euler(k, float(v), degrees=True).as_matrix().T @ M
    return M


def _remounted(walk, spec: str, frame: AxisFrame | None = None):
    """The walk with its foot unit turned by ``spec`` and meta.json's foot frame ``frame`` (default: the
    original one, stale)."""
    s = remount(walk, "foot", _turn(spec))
    s.frames["foot"] = frame or walk.frames["foot"]
    return s


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("walk", user_seed=501, length_m=30.0, rate_hz=100.0)


@pytest.mark.parametrize("spec", [HEEL, "y:180,z:-24", "y:180,z:64"])
def test_a_stale_frame_reversed_against_the_strides_is_refused_when_the_inference_gives_up(walk, spec):
    s = _remounted(walk, spec)
    with pytest.raises(FrameInferenceError) as gave_up:  # the case D10 skipped: the axis is in doubt
        infer_session_frame(s, "foot")
    assert gave_up.value.forward is not None and "edge of the" in str(gave_up.value)
    with pytest.raises(DataError) as exc:
        s.require_frame("foot")
    m = str(exc.value)
    assert "is reversed against its data (forward" in m and "decision D23" in m and '"force_frame": true' in m
    assert '{"x": "forward", "y": "up", "z": "right"}' in m  # the stale frame named
    with pytest.raises(DataError):  # every caller, every time: the refusal is kept with the check
        s.require_frame("foot")


def test_the_heel_stale_is_refused_and_declared_right_tracks_as_the_original_mount(walk):
    from pdrlearn.track.plasys import track_plasys

    with pytest.raises(DataError, match="reversed against its data"):
        track_plasys(_remounted(walk, HEEL), method="M3", model="oracle")
    s = _remounted(walk, HEEL, RIGHT_HEEL)
    assert s.require_frame("foot") == RIGHT_HEEL
    a, b = (track_plasys(x, method="M3", model="oracle") for x in (walk, s))  # the waist heading, as `track`
    assert len(a.steps) == len(b.steps) > 10 and (b.steps["length_m"] > 0).all()
    # not bit-identical: the tilted mount moves the stance detector's samples slightly (seen: 0.0004 m per stride)
    np.testing.assert_allclose(b.steps["length_m"], a.steps["length_m"], atol=2e-3)
    np.testing.assert_allclose(b.trajectory[["x", "y"]].to_numpy(), a.trajectory[["x", "y"]].to_numpy(), atol=0.05)


def test_force_frame_keeps_a_reversed_declaration_with_the_warning(walk, caplog):
    s = _remounted(walk, HEEL)
    s.meta["force_frame"] = True
    with caplog.at_level(logging.WARNING):
        assert s.require_frame("foot") == walk.frames["foot"]
    (m,) = [r.getMessage() for r in caplog.records if "reversed against its data" in r.getMessage()]
    assert '("force_frame", decision D23) is still used' in m


def test_a_confident_reversal_is_refused_too_but_a_reversed_up_alone_is_a_warning(walk, caplog):
    """Forward reversed with a confident inference (``z:180``): refused. Upside down, forward kept (``x:180``): the
    filters level with gravity, the trial's track was right (0.35 m): D10's warning, no refusal."""
    with pytest.raises(DataError, match="contradicts its data, which give .*decision D23"):
        _remounted(walk, "z:180").require_frame("foot")
    s = _remounted(walk, "x:180")
    with caplog.at_level(logging.WARNING):
        assert s.require_frame("foot") == walk.frames["foot"]
    assert any("up 1" in r.getMessage() and "still used" in r.getMessage() for r in caplog.records)


def test_info_says_refused_and_not_checked(walk, tmp_path, capsys):
    bad, good = tmp_path / "bad", tmp_path / "good"
    for d, frame in ((bad, None), (good, RIGHT_HEEL)):
        s = _remounted(walk, HEEL, frame)
        write_session(s, d)
        meta = json.loads((d / "meta.json").read_text())
        meta["frames"] = {"foot": s.frames["foot"].to_dict(), "waist": walk.frames["waist"].to_dict()}
        (d / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(bad)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "refused by the commands that need it" in out and str(bad / "meta.json") in out
    assert main(["info", str(good), "--json"]) == 0
    chk = json.loads(capsys.readouterr().out)["frame_checks"]["foot"]
    assert chk["status"] == "unchecked" and chk["check"].startswith("its up and forward not reversed by the data; "
                                                                     "which axis is which not checked (the mount")
    assert main(["info", str(good)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    foot = out[out.index("foot axes:"):out.index("waist axes:")]
    assert "not contradicted" not in foot and "not checked (the mount is pitched" in foot
    assert main(["track", str(bad), "--out", str(tmp_path / "o")]) == 2  # exit 2 with the one line
    # `run` took a declared frame unchecked (the trial's gaitmap heel case: every stride backward, no warning)
    bundle = ROOT / "models" / "plasys-sim-default"
    assert main(["run", str(bundle), str(bad), "--out", str(tmp_path / "r")]) == 2
    assert "reversed against its data" in capsys.readouterr().err and not (tmp_path / "r").exists()


def test_info_says_not_checked_when_nothing_could_be_measured():
    from pdrlearn.io.session import Session, Stream

    t = np.arange(200) / 20.0
    s = Session("still", streams={"wAccelerometer": Stream("wAccelerometer", t, np.tile([0.0, 0.0, 9.81], (200, 1))),
                                  "wGyroscope": Stream("wGyroscope", t, np.zeros((200, 3)))},
                frames={"waist": AxisFrame(x="forward", y="left", z="up")})
    chk = s.frame_checks()["waist"]
    assert chk["status"] == "unchecked" and chk["check"].startswith("not checked (")


def _export(path, walk):
    """The walk's foot unit as a lab CSV (ms, m/s^2, rad/s)."""
    a, w = walk["fAccelerometer"], walk["fGyroscope"]
    df = pd.DataFrame({"t_ms": np.round((a.t - a.t[0]) * 1000.0, 3),
                       **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": np.interp(a.t, w.t, w.values[:, i]) for i, c in enumerate("xyz")}})
    df.to_csv(path, index=False, float_format="%.9g")
    return path


def test_import_refuses_a_left_handed_frame_the_data_cannot_judge(walk, tmp_path, capsys):
    csv = _export(tmp_path / "heel.csv", remount(walk, "foot", _turn(HEEL)))
    args = ["import", str(csv), "--unit", "foot", "--acc", "acc_x,acc_y,acc_z", "--gyro", "gyr_x,gyr_y,gyr_z",
            "--acc-unit", "m/s^2", "--gyro-unit", "rad/s", "--time-unit", "ms", "--frames", "x=up,y=forward,z=right"]
    assert main([*args, "--out", str(tmp_path / "lh")]) == 2
    err = capsys.readouterr().err
    assert "--frames x=up,y=forward,z=right is left-handed" in err and "--force-frame" in err
    assert str(csv) in err and not (tmp_path / "lh").exists()
    assert main([*args, "--out", str(tmp_path / "lh2"), "--force-frame"]) == 0
    rec = json.loads((tmp_path / "lh2" / "meta.json").read_text())["imported"]
    assert rec["frame_forced"]["declared"] == {"x": "up", "y": "forward", "z": "right"}


@pytest.mark.parametrize("bad", ["true", ["feet"], 1])
def test_a_misspelt_force_frame_is_one_line_not_the_same_refusal_again(walk, bad):
    """Decision B136: ``"force_frame": "true"`` (or an unknown unit) was ignored and the refusal repeated its advice
    to add ``"force_frame": true``; now one line names the value and what to give."""
    s = _remounted(walk, HEEL)
    s.meta["force_frame"] = bad
    with pytest.raises(DataError, match=r'"force_frame" is .*: give true \(every unit\) or a list of units'):
        s.require_frame("foot")


def test_a_waist_frame_read_reversed_is_a_warning_not_a_refusal(walk, caplog):
    """D23 as amended: only the foot's reversal (its strides' integrated direction) is refused; the waist's forward
    comes from W2's gait-phase cue, which a correct frame can fail, so a stale waist frame keeps D10's warning."""
    from pdrlearn.track.frame_inference import _turned

    s = remount(walk, "waist", np.eye(3))  # a copy of the session
    backward = _turned(walk.frames["waist"], {"forward", "left"})  # declared turned 180 deg about up
    s.frames["waist"] = backward
    with caplog.at_level(logging.WARNING):
        assert s.require_frame("waist") == backward
    said = [r.getMessage() for r in caplog.records]
    assert any("waist unit" in m and "contradicts its data" in m and "still used" in m for m in said)
