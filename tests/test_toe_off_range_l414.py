"""Decision L414 (session 34, trial T3 finding 9): a --toe-off track whose median stance (contact) time is below the
shortest contacts L73 checked against a reference gets one warning line naming the bound and its source."""

from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.track.evaluate import summary_warnings
from pdrlearn.track.toeoff import TOE_OFF_MIN_CHECKED_STANCE_S, stance_range_warning


def test_short_contacts_warn_checked_ones_do_not():
    line = stance_range_warning({"median_stance_time_s": 0.36})
    assert line is not None and "0.360 s is below 0.69 s" in line and "L73" in line and "L414" in line
    assert stance_range_warning({"median_stance_time_s": TOE_OFF_MIN_CHECKED_STANCE_S}) is None
    assert stance_range_warning({"median_stance_time_s": None}) is None  # no --toe-off
    assert line in summary_warnings({"median_stance_time_s": 0.36})


def test_a_fast_simulated_walk_with_toe_off_is_warned(tmp_path):
    """User 7955 walking fast (``--speed fast``): its --toe-off median stance is under 0.69 s, so the summary's
    warnings hold L414's line; without --toe-off there is no stance time and no line."""
    ses = tmp_path / "fast"
    assert main(["simulate", "--route", "straight:15", "--speed", "fast", "--user-seed", "7955",
                 "--out", str(ses)]) == 0
    for extra, expected in ((["--toe-off"], True), ([], False)):
        out = tmp_path / f"t{len(extra)}"
        assert main(["track", "--no-plot", str(ses), *extra, "--out", str(out)]) == 0
        summary = json.loads((out / "summary.json").read_text())
        lines = [w for w in summary["info"].get("warnings", []) if "decision L414" in w]
        assert bool(lines) is expected
        if expected:
            assert summary["median_stance_time_s"] < TOE_OFF_MIN_CHECKED_STANCE_S
