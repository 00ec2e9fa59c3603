"""Decision B449 (session 44, trial T2 F9): L390's insole clock offset pairs forward strides only, at least
``force_clock.MIN_OFFSET_STRIDES`` (5) of them; a turn-on-the-spot session (one clock for every sensor) read +269 ms
from 4 strides, mostly pivots, and was told to shift its insole file."""

from __future__ import annotations

import contextlib
import io
import json


def _cli(args: list) -> int:
    from pdrlearn.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main([str(a) for a in args])


def test_a_turn_on_the_spot_session_gets_no_insole_clock_line_b449(tmp_path):
    """T2's ``spin`` (user 21, 100 Hz): 15 strides, 4 of them forward; before B449 "+269 ms (median of 4 strides)"."""
    walk = tmp_path / "spin"
    route = "straight:3, turn:360, straight:0.5, turn:-360, turn:90, turn:-90, backward:2"
    assert _cli(["simulate", "--route", route, "--user-seed", "21", "--rate", "100", "--out", walk]) == 0
    assert _cli(["track", walk, "--no-plot", "--out", tmp_path / "t"]) == 0
    info = json.loads((tmp_path / "t" / "summary.json").read_text())["info"]
    assert not [w for w in info["warnings"] if "against the foot IMU's own events" in w], info["warnings"]
    assert info.get("force_offset_s") is None

