"""Decision E171 (session 35, fixer FH, review R1 item 1): a summary keeps the codes its lines had when a command
adds warning lines after them (``track --per`` S69's, ``--corridor``'s, ``--splits``'s), and those lines are coded
where they are raised."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.warning_lines import CodedLine, machine_summary

_DROPS = ("/s: fAccelerometer has 3 interval(s) of 1 s or less ... (decisions B64, B183) ... or "
          "--params {\"timestamps\": true} (decision L83)")


def test_a_summary_keeps_its_codes_when_lines_are_added_after_it():
    """E171: the codes set by an earlier machine summary (track_summary's, plain text after JSON) belong to its first
    lines; a line appended later (here plain text) is coded from its text, the earlier ones keep theirs. Before, the
    unequal lengths threw every earlier code away: the drops line became L83 again."""
    summary = {"info": {"warnings": [_DROPS, "no model: ... (decision E153)"], "warning_codes": ["B64", "E153"]}}
    summary["info"]["warnings"].append("--splits: the tracked path is 21.09 m long; no split time at 50 m beyond it "
                                       "(decision L411)")
    machine_summary(summary, ["/s: a logged line (decision W7)"], "/s")
    assert summary["info"]["warning_codes"] == ["B64", "E153", "L411", "W7"]


def test_the_per_corridor_and_splits_lines_are_coded_where_raised():
    """E171: S69's periods line, the corridor test's and the splits' lines carry the code their text names."""
    from pdrlearn.track.corridor import corridor_laps
    from pdrlearn.track.periods import constant_bounce_line
    from pdrlearn.track.splits import split_table

    empty = pd.DataFrame(columns=["start_s", "end_s", "length_m"])
    bounce = constant_bounce_line({"source_project": "pdrlearn.sim", "knobs": {}}, {"methods": {"length": "pendulum"}})
    lines = [bounce, *split_table(empty, [5.0])[2], *corridor_laps(empty, None, 30.0)[2]]
    codes = ["S69", "L411", "corridor-walk-test"]
    assert [getattr(w, "code", None) for w in lines] == codes
    assert all(isinstance(w, CodedLine) for w in lines)


def test_a_drops_session_tracked_with_splits_keeps_b64(tmp_path, capsys):
    """R1's reproduction: a foot session with scattered dropped samples tracked with --splits 50 (a mark beyond its
    20 m path adds a warning line after the summary's codes were set) keeps the drops line's B64; before: L83."""
    ses = tmp_path / "u1"
    assert main(["simulate", "--scenario", "walk", "--length-m", "20", "--user-seed", "8530", "--drop-rate", "0.03",
                 "--rate", "100", "--out", str(ses)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(ses), "--splits", "50", "--json", "--out", str(tmp_path / "t")]) == 0
    printed = json.loads(capsys.readouterr().out)["info"]["warning_codes"]
    written = json.loads((tmp_path / "t" / "summary.json").read_text())["info"]["warning_codes"]
    assert printed == written
    assert "B64" in written and "L411" in written and "L83" not in written
