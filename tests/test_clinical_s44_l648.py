"""Decision L648 (session 44, trial T1 finding F5): a TUG's slow (2.5-4 s) rise and sit, which W182's bounds drop as
bends, are read again with W450's bounds at the walk's ends (the session's first rise within 5 s before the first
contact, its last sit within 5 s after the last); a TUG with one of them still missed says why in tug_time_note and
clinical.md."""
from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.report.clinical import clinical_markdown
from pdrlearn.waist.transfers import one_sided_tug_note, transfer_summary


@pytest.fixture(scope="module")
def slow_tug(tmp_path_factory):
    d = tmp_path_factory.mktemp("l648")
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3, turn:180", "--sit-start", "5",
                 "--sit-end", "5", "--stand", "0.5", "--transfer-time", "2.5:4", "--step-length", "0.4",
                 "--step-time", "0.7", "--bounce", "pendulum", "--rate", "100", "--user-seed", "12457",
                 "--out", str(d / "s")]) == 0
    assert main(["track", "--no-plot", str(d / "s"), "--units", "waist", "--out", str(d / "t")]) == 0
    return d


def test_a_slow_tug_is_timed(slow_tug):
    truth = pd.read_csv(slow_tug / "s" / "transfers.csv")
    true_s = (truth["seated_ms"].iloc[-1] - truth["rise_ms"].iloc[0]) / 1000.0  # 28.24 s
    s = json.loads((slow_tug / "t" / "summary.json").read_text())
    assert s["tug_time_s"] == pytest.approx(true_s, abs=1.0)  # W182 alone: None
    rows = pd.read_csv(slow_tug / "t" / "transfers.csv")
    assert list(rows["kind"]) == ["sit-to-stand", "stand-to-sit"] and (rows["duration_s"] > 2.3).all()


#: a rise before a 20 s walk and no sit after it (trial T1's user 4414)
RISE_ONLY = pd.DataFrame([{"transfer": 1, "kind": "sit-to-stand", "start_s": 5.28, "end_s": 7.0, "duration_s": 1.72,
                           "peak_s": 6.0, "peak_tilt_deg": 35.0, "height_change_m": 0.4, "flag": ""}])


def test_a_tug_with_one_transfer_missed_says_why(tmp_path):
    steps = pd.DataFrame({"start_s": [9.2 + 0.6 * k for k in range(27)]})
    note = transfer_summary(RISE_ONLY, steps)["tug_time_note"]
    assert note == one_sided_tug_note(RISE_ONLY, steps["start_s"].to_numpy())
    assert note.startswith("no TUG time: a sit-to-stand at 5.3 s before the walk but no stand-to-sit after its last "
                           "step at 24.8 s") and "L648" in note
    long_walk = pd.DataFrame({"start_s": [9.2 + 0.6 * k for k in range(300)]})  # 180 s: no TUG
    assert one_sided_tug_note(RISE_ONLY, long_walk["start_s"].to_numpy()) is None
    (tmp_path / "t").mkdir()
    (tmp_path / "t" / "summary.json").write_text(json.dumps({"session": "s", "pipeline": "waist-pendulum",
                                                             "tug_time_s": None, "tug_time_note": note}))
    assert f"- TUG: not timed ({note}" in clinical_markdown(tmp_path)
