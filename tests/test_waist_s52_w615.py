"""Decision W615 (session 52, FB, review s52r1 F4): D10's frame line ends "(or run track with --mount-frame inferred,
decision W607)" only when `track` or `track-all` (the commands that take the option) read the session; `steps`,
`calibrate`, `gait` ..., the live WaistTracker and a notebook's read_session say the line without it."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main as cli_main
from pdrlearn.cli.track import settings_of
from pdrlearn.io.frames import AxisFrame
from pdrlearn.track.frame_inference import declared_frame_warning
from tests.frame_helpers import yawed_lower_back


class _Found:
    frame = AxisFrame(x="backward", y="up", z="left")

    def describe(self):
        return "measured"


@pytest.mark.parametrize("command, clause", [
    (None, None), ("track", "(or run track with --mount-frame inferred, decision W607)"),
    ("track-all", "(or run track-all with --mount-frame inferred, decision W607)")])
def test_the_line_names_the_option_of_the_command_only_w615(command, clause):
    line = declared_frame_warning("waist", AxisFrame(x="left", y="up", z="forward"), _Found(), 'declared in "frames"',
                                  off={"forward": 92.0}, command=command)
    assert "is still used (decision D8)" in line
    assert (clause in line) if clause else "--mount-frame" not in line


@pytest.fixture(scope="module")
def yawed(tmp_path_factory):
    return yawed_lower_back(tmp_path_factory.mktemp("w615") / "w")


def test_info_does_not_name_an_option_it_lacks_track_does_w615(yawed, tmp_path, capsys):
    """`info` (as `steps`, `calibrate`, `gait` ...: review s52r1 F4) has no --mount-frame; `track` has."""
    said = {}
    for command, extra in (("info", []), ("track", ["--no-plot", "--out", str(tmp_path / "trk")])):
        assert cli_main([command, str(yawed), *extra]) == 0
        said[command] = [ln for ln in capsys.readouterr().err.splitlines() if "is still used (decision D8)" in ln]
    assert len(said["info"]) == 1 and "--mount-frame" not in said["info"][0]
    assert len(said["track"]) == 1 and "(or run track with --mount-frame inferred, decision W607)" in said["track"][0]
    assert settings_of({}, "track-all")["command"] == "track-all" and settings_of({})["command"] == "track"
