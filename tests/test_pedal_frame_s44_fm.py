"""Session 44, fixer FM (mid-session suite): L625's pedalling check skipped, with one line, on a foot whose axis frame
is not known (`steps` counts without a frame, C142), and the NoStridesError on a foot unit that is not on the foot
(a waist's "strides" are all unrested, so L611 + L640 remove every one: the NoStridesError now leads with B134's
line)."""

from __future__ import annotations

import json
import logging

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


def test_no_walking_strides_names_b134_when_the_unit_is_not_on_the_foot(capsys):
    """Waist data in the foot files: L611 (with L640) leaves no stride, and the one error line leads with B134's
    "is this unit on the foot?" before L611's "cycling?"; a crank alone (tests/test_pedal_s43_l611.py) keeps L611's
    line followed by B268's hint."""
    import pytest

    from pdrlearn.errors import NoStridesError
    from pdrlearn.track import get_pipeline

    s = _waist_in_the_foot_files()
    with pytest.raises(NoStridesError, match=r"no walking strides: no foot-flat rests found: .*is this unit on the "
                                             r"foot\? .*decision B134\); or not walking, removed from the track .*"
                                             r"cycling\? decision L611\)$"):
        get_pipeline("plasys")(s)
