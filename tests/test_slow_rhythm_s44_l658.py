"""Decision L658 (session 44, trial T2 F8): L599's slow-rhythm line is given only when the foot's strides fill half of
that rhythm (L605's gate); a short forward-backward-forward session's stop-and-go cycle (5.4 s) is not its strides'."""

from __future__ import annotations

import contextlib
import io
import json

import pytest

from pdrlearn.kernels.contact import RHYTHM_CAP_MIN_FILL
from pdrlearn.track.foot_rest import slow_rhythm_line


def _cli(args: list) -> int:
    from pdrlearn.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main([str(a) for a in args])


def test_the_line_needs_strides_that_fill_the_rhythm():
    assert slow_rhythm_line(5.4, 3.0, 1.3) is None  # T2's fbf: 1.3 s windows in a 5.4 s cycle
    assert slow_rhythm_line(4.0, 6.0, RHYTHM_CAP_MIN_FILL * 4.0) is not None  # a slow walker's own strides
    assert slow_rhythm_line(4.0, 3.0) is not None  # no window given: judged by the period alone, as L599
    assert slow_rhythm_line(2.5, 3.0, 2.4) is None  # under L80's 3 s


@pytest.mark.parametrize("route", ["straight:2, backward:3, straight:2, turn:180, straight:2, backward:3, straight:2"])
def test_a_forward_backward_forward_session_is_not_called_a_slow_walker_l658(route, tmp_path):
    """T2's ``fbf`` (user 21, 100 Hz): "the foot's strides take 5.4 s (about 22 steps/min)" while its summary gives
    70.8 steps/min before L658."""
    walk = tmp_path / "fbf"
    assert _cli(["simulate", "--route", route, "--user-seed", "21", "--rate", "100", "--out", walk]) == 0
    assert _cli(["track", walk, "--no-plot", "--out", tmp_path / "t"]) == 0
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["median_cadence_spm"] > 60
    assert not [w for w in summary["info"]["warnings"] if "strides take" in w], summary["info"]["warnings"]
