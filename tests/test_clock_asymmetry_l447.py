"""Decision L447 (session 36, trial T2 finding 2): a foot + lower-back track whose unit clocks are said to be offset
(L161's warning) leaves the step-time asymmetry index empty, with the reason, instead of printing the index of
mislabelled contacts (a symmetric simulated walker read 41.8 %)."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """One symmetric walk of user 8882 (foot + waist, 50 Hz), on synchronised clocks and with the waist 0.3 s late."""
    root = tmp_path_factory.mktemp("l447")
    logging.disable(logging.WARNING)
    try:
        for name, off in (("synced", 0.0), ("offset", 0.3)):
            write_session(simulate("walk", 8882, length_m=60, rate_hz=50.0, clock_offset_s=off), root / name)
    finally:
        logging.disable(logging.NOTSET)
    return root


def test_offset_clocks_leave_the_asymmetry_index_empty_l447(walks, tmp_path):
    summaries = {}
    for name in ("synced", "offset"):
        assert main(["track", "--no-plot", str(walks / name), "--out", str(tmp_path / name)]) == 0
        summaries[name] = json.loads((tmp_path / name / "summary.json").read_text())
    synced, offset = summaries["synced"], summaries["offset"]
    assert synced["step_time_asymmetry_pct"] is not None and synced["step_time_asymmetry_pct"] < 10
    assert any("decision L161" in w for w in offset["info"]["warnings"])
    assert offset["step_time_asymmetry_pct"] is None
    assert "decision L447" in offset["step_time_asymmetry_reason"]
    assert "--clock-offset" in offset["step_time_asymmetry_reason"]


def test_a_clock_warning_empties_an_index_the_labels_would_give_l447(walks):
    """The synchronised walk gives an index; the same track with L161's (or L446's) clock line among its warnings
    gives none, and the reason (the index of swapped labels read 41.8 % on T2's symmetric walker)."""
    from pdrlearn.io import read_session
    from pdrlearn.kernels.align import unit_offset_message
    from pdrlearn.track.labelled_asymmetry import track_asymmetry
    from pdrlearn.track.plasys import track_plasys

    s = read_session(walks / "synced")
    steps = track_plasys(s).steps
    assert track_asymmetry(s, steps)["step_time_asymmetry_pct"] is not None
    for line in (unit_offset_message(0.3, 0.0), "the unit clocks could not be checked: ... decision L446); ..."):
        out = track_asymmetry(s, steps, ["another warning", line])
        assert out["step_time_asymmetry_pct"] is None and out["n_step_time_asymmetry_steps"] == 0
        assert "decision L447" in out["step_time_asymmetry_reason"]


def test_align_units_clock_labels_the_contacts_l447(walks, tmp_path):
    """With --align-units' estimate applied, the index labels the lower back's contacts on the aligned clock (it had
    read them on the waist's own clock: 4 strides labelled, no index), as --clock-offset's moved session does."""
    out = {}
    for name, extra in (("align", ["--align-units"]), ("given", ["--clock-offset", "0.3"])):
        assert main(["track", "--no-plot", str(walks / "offset"), "--out", str(tmp_path / name), *extra]) == 0
        out[name] = json.loads((tmp_path / name / "summary.json").read_text())
    assert out["align"]["info"]["unit_alignment"]["source"] == "estimated"
    assert out["align"]["step_time_asymmetry_pct"] is not None and out["align"]["step_time_asymmetry_pct"] < 10
    assert out["given"]["step_time_asymmetry_pct"] < 10  # the symmetric walker either way (0.19 % / 2.61 % read)
