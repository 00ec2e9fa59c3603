"""Session 41, implementer I4: decision L561 (`gait` names the leading foot of a step-to-step stair flight, in
gait_summary.json's ``stairs``, its printed lines and clinical.md), against the simulator's truth (S80 / S92)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.stair_lead import flight_lead

ROUTE = ("stand:3, straight:5, up:5:0.17:0.28:step-to-step:right, straight:3, turn:180, straight:3, "
         "down:5:0.17:0.28:step-to-step:left, straight:3, turn:180, straight:3, up:6:0.17:0.28, straight:3, stand:3")


def _truth(ics: pd.DataFrame) -> list[tuple[str, str]]:
    """The simulator's flights in order: (kind, the first foot on it) - on a step-to-step flight the leading foot
    (S92: the feet are together before it, so the chosen foot steps first and leads every stair)."""
    kind, foot = ics["kind"].to_numpy(), ics["foot"].to_numpy()
    out = []
    for k in range(len(kind)):
        if kind[k] in ("stairs_up", "stairs_down") and (k == 0 or kind[k - 1] != kind[k]):
            out.append((str(kind[k]), str(foot[k])))
    return out


@pytest.fixture(scope="module")
def gait_out(tmp_path_factory):
    root = tmp_path_factory.mktemp("l561")
    for foot in ("left", "right"):
        assert main(["simulate", "--route", ROUTE, "--user-seed", "11150", "--seed", "11150", "--foot", foot,
                     "--out", str(root / foot)]) == 0
    out = root / "gait"
    assert main(["gait", str(root / "left"), str(root / "right"), "--out", str(out)]) == 0
    return root, out


def test_gait_names_the_leading_foot_of_each_step_to_step_flight_l561(gait_out, capsys):
    root, out = gait_out
    truth = _truth(pd.read_csv(root / "left" / "ics.csv"))
    assert truth == [("stairs_up", "right"), ("stairs_down", "left"), ("stairs_up", "left")]  # S92's chosen leads
    summary = json.loads((out / "gait_summary.json").read_text())
    for block in (summary, summary["reference"]):  # the tracked feet and the labels, one rule
        flights = block["stairs"]
        assert [f["kind"] for f in flights] == [k for k, _ in truth]
        assert [f["pattern"] for f in flights] == ["step-to-step", "step-to-step", "step-over-step"]
        assert [f["lead"] for f in flights[:2]] == [lead for _, lead in truth[:2]] and flights[2]["lead"] is None
    assert main(["gait", str(root / "left"), str(root / "right")]) == 0
    printed = capsys.readouterr().out
    assert "stairs (L561): up step-to-step, the right foot leading" in printed
    assert "stairs (L561): down step-to-step, the left foot leading" in printed
    assert "stairs (L561): up step over step, the feet alternating" in printed


def test_clinical_md_says_which_foot_leads_on_the_stairs_l561(gait_out, tmp_path):
    _, out = gait_out
    assert main(["report", str(out), "--out", str(tmp_path / "rep"), "--clinical"]) == 0
    text = (tmp_path / "rep" / "clinical.md").read_text()
    line = next(x for x in text.splitlines() if x.startswith("- Stairs"))
    assert "up step-to-step, the right foot leading" in line and "down step-to-step, the left foot leading" in line


@pytest.mark.parametrize("offset", [0.0, 0.4])
def test_the_pattern_is_judged_from_step_heights_whatever_the_feet_s_height_offset_l561(offset):
    """L561's kernel: step-to-step (the lead rises a stair, the trail ends beside it) against step over step, with
    the two tracks' heights offset from each other (each foot is counted from its own height before the flight)."""
    r = 0.17
    side = np.array(["left", "right"] * 6, dtype=object)
    # a level contact each, then 5 stairs: left leads (z: left j r, right j r after its step)
    z = np.r_[0.0, 0.0, np.repeat(np.arange(1, 6) * r, 2)] + np.where(side == "right", offset, 0.0)
    f = flight_lead(side, z, 2, 12, 1.0)
    assert f["pattern"] == "step-to-step" and f["lead"] == "left" and f["lead_index"] == pytest.approx(1.0)
    over = np.r_[0.0, 0.0, np.arange(1, 11) * r] + np.where(side == "right", offset, 0.0)  # each step one stair
    g = flight_lead(side, over, 2, 12, 1.0)
    assert g["pattern"] == "step-over-step" and g["lead"] is None and g["lead_index"] == pytest.approx(0.0, abs=1e-9)
    right_first = np.array(["right", "left"] * 6, dtype=object)  # down, the right foot leading
    down = flight_lead(right_first, np.r_[0.0, 0.0, -np.repeat(np.arange(1, 6) * r, 2)], 2, 12, -1.0)
    assert down["pattern"] == "step-to-step" and down["lead"] == "right"
