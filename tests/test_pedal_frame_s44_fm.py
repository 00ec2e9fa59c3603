"""Session 44, fixer FM (mid-session suite): L625's pedalling check skipped, with one line, on a foot whose axis frame
is not known (`steps` counts without a frame, C142), and L611 standing down on a foot unit that is not on the foot
(B134's line tells the user; a waist's "strides" are all unrested, so L611 + L640 had removed every one)."""

from __future__ import annotations

import json
import logging

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.io import Stream, write_session
from pdrlearn.track.frame_inference import remount
from pdrlearn.track.pedalling import NO_FRAME
from tests.test_frame_status import _stripped, walk  # noqa: F401 (walk: the module's fixture)


def test_steps_without_a_foot_frame_skips_the_pedalling_check_l625(walk, tmp_path, capsys, caplog):  # noqa: F811
    s = _stripped(remount(walk, "foot", Rotation.from_euler("y", 40, degrees=True).as_matrix().T))
    write_session(s, tmp_path / "yaw40")
    with caplog.at_level(logging.WARNING):
        assert main(["steps", str(tmp_path / "yaw40"), "--detector", "accel", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["count"] == got["reference_count"] and got["pedalling_strides"] == 0
    assert [r.getMessage().count(NO_FRAME) for r in caplog.records if NO_FRAME in r.getMessage()] == [1]


def _waist_in_the_foot_files():
    from pdrlearn.sim import simulate

    s = simulate("A", user_seed=581, rate_hz=100.0)
    for f, w in (("fAccelerometer", "wAccelerometer"), ("fGyroscope", "wGyroscope")):
        s.streams[f] = Stream(f, s.streams[w].t, s.streams[w].values)
    for w in ("wAccelerometer", "wGyroscope"):
        del s.streams[w]
    return s


def test_l611_stands_down_when_the_foot_unit_is_not_on_the_foot_b134():
    from pdrlearn.displace.foot import FootDisplacement
    from pdrlearn.displace.force_check import checked_stance
    from pdrlearn.orient import unit_data
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.foot_rest import foot_rest_gravity
    from pdrlearn.track.pedalling import not_on_the_foot, pedal_loops
    from pdrlearn.track.plasys import METHODS

    s = _waist_in_the_foot_files()
    assert not_on_the_foot(s)
    result = get_pipeline("plasys")(s)
    warnings = track_summary(result, s)["info"]["warnings"]
    assert not [w for w in warnings if "decision L611" in w]
    assert len([w for w in warnings if "decision B134" in w]) == 1
    assert len(result.steps) >= 10  # the walk's strides are tracked (B134: a warning, not a refusal)
    # the kernel itself still calls the waist's strides loops: the stand-down is the session's placement, nothing else
    foot = unit_data(s, "foot")
    fd_kw = {k: METHODS["M3"][k] for k in ("integrator", "zupt_end", "gyro_bias", "attitude")}
    stance = checked_stance(s, foot)[0]
    fd = FootDisplacement(**fd_kw).estimate(foot, result.steps[["start_s", "end_s"]], stance=stance)
    assert pedal_loops(fd, foot, foot_rest_gravity(s)).sum() >= 10
    assert not pedal_loops(fd, foot, foot_rest_gravity(s), s).any()
    assert np.isfinite(result.steps["length_m"]).all()
