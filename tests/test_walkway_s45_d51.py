"""Decisions D51, D52, L672 (session 45, trial T3 findings F3, F4): a walkway's per-footfall table at import keeps its
toe-off and stride length, a --toe-off track writes the reference stance / swing beside its own, and cycle_start_s
names the contact a row's stance belongs to."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.ic_reference import ic_strides
from pdrlearn.io.importer import import_steps
from pdrlearn.track.evaluate import TIMING_REFERENCE_COLUMNS, reference_timings
from pdrlearn.track.gait import add_gait_columns

ROOT = Path(__file__).resolve().parents[1] / "datasets" / "real"


def test_footfall_values_go_on_the_strides_they_belong_to_d51():
    ic = [1.0, 2.1, 3.2, 4.3]
    tc = [1.7, 2.8, 4.0, 5.0]  # each footfall's own toe-off (the last one closes no stride)
    length = [np.nan, 1.40, 1.45, 1.50]  # each footfall's stride length: heel of the previous one to this one
    st = ic_strides(ic, tc_s=tc, length_m=length)
    assert st["pre_ic_s"].tolist() == [1.0, 2.1, 3.2] and st["ic_s"].tolist() == [2.1, 3.2, 4.3]
    assert st["tc_s"].tolist() == [1.7, 2.8, 4.0]  # the opening contact's toe-off
    assert st["length_m"].tolist() == [1.40, 1.45, 1.50]  # the closing contact's length
    late = ic_strides(ic, tc_s=[1.7, 3.5, 4.0, 5.0])  # 3.5 after its stride's closing IC 3.2: not this stride's
    assert np.isnan(late["tc_s"][1]) and late["tc_s"][2] == 4.0


def _session():
    from pdrlearn import sim

    return sim.simulate("walk", 4501, length_m=12)


def test_import_walkway_table_keeps_tc_and_length_and_names_the_rest_d51(tmp_path, caplog):
    session = _session()
    ic = np.sort(session.steps["ic_s"].to_numpy(float))
    rows = []
    for k, t in enumerate(ic):  # both feet: the tracked (right) foot's footfalls and the other foot's between
        rows.append({"Side": "R", "ic_ms": 1e3 * t, "tc_ms": 1e3 * (t + 0.65), "length_m": 1.3 + 0.01 * k,
                     "pass_no": 1})
        rows.append({"Side": "L", "ic_ms": 1e3 * (t + 0.5), "tc_ms": "", "length_m": "", "pass_no": 1})
    path = tmp_path / "walkway.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    with caplog.at_level(logging.WARNING):
        out = import_steps(path, session, 0.0, foot="right")
    st = out.steps
    assert len(st) == len(ic) - 1 and {"tc_s", "length_m"} <= set(st.columns)
    assert np.allclose(st["tc_s"], ic[:-1] + 0.65)  # stance of the opening contact: tc - pre_ic = 0.65 s
    assert np.allclose(st["length_m"], 1.3 + 0.01 * np.arange(1, len(ic)))
    assert st.attrs["footfall_columns"] == {"tc_s": len(ic) - 1, "length_m": len(ic) - 1}
    assert "pass_no" in caplog.text and "not read" in caplog.text  # named, not dropped without a word
    bad = tmp_path / "bad.csv"
    pd.DataFrame({"side": ["X", "R"], "ic_ms": [1000.0, 2000.0]}).to_csv(bad, index=False)
    with pytest.raises(DataError, match="left / right"):
        import_steps(bad, session, 0.0, foot="right")


def test_cycle_start_is_the_previous_contact_l672():
    table = pd.DataFrame({"start_s": [0.0, 1.0, 2.0], "end_s": [1.0, 2.0, 3.0], "event_s": [0.8, 1.9, 2.8],
                          "length_m": [1.2, 1.3, 1.3]})
    add_gait_columns(table, tc_s=np.array([0.4, 1.5, 2.4]))
    assert np.isnan(table["cycle_start_s"][0]) and table["cycle_start_s"][1:].tolist() == pytest.approx([0.8, 1.9])
    assert (table["tc_s"] - table["cycle_start_s"])[1:].tolist() == pytest.approx(table["stance_time_s"][1:].tolist())


def test_reference_timings_d52():
    st = pd.DataFrame({"start_s": [1.0, 2.1], "end_s": [2.1, 3.2], "ic_s": [2.1, 3.2], "pre_ic_s": [1.0, 2.1],
                       "tc_s": [1.7, 3.3]})
    tc, stance, swing, pct = reference_timings(st)
    assert tc[0] == 1.7 and stance[0] == pytest.approx(0.7) and swing[0] == pytest.approx(0.4)
    assert pct[0] == pytest.approx(70 / 1.1)
    assert np.isnan(tc[1]) and np.isnan(stance[1])  # a toe-off after its stride's IC is no reference


def test_track_toe_off_writes_reference_stance_on_gaitmap_d52(tmp_path):
    path = ROOT / "gaitmap_level_left"
    if not (path / "steps.csv").exists():
        pytest.skip("datasets/real/gaitmap_level_left absent")
    from pdrlearn.cli import main

    assert main(["track", "--no-plot", str(path), "--toe-off", "--out", str(tmp_path / "t")]) == 0
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert set(TIMING_REFERENCE_COLUMNS) <= set(steps.columns)
    lab = pd.read_csv(path / "steps.csv")
    paired = steps.dropna(subset=["ref_stance_time_s", "stance_time_s"])
    assert len(paired) >= 20
    j = paired["ref_match"].astype(int).to_numpy()
    # L672: the row's cycle opens at the labelled stride's opening contact (pre_ic), not at its own event_s
    assert np.abs(paired["cycle_start_s"].to_numpy() - lab["pre_ic_ms"].to_numpy()[j] / 1e3).max() < 0.06
    assert np.allclose(paired["ref_stance_time_s"], (lab["tc_ms"] - lab["pre_ic_ms"]).to_numpy()[j] / 1e3)
    bias = float((paired["stance_time_s"] - paired["ref_stance_time_s"]).mean())
    assert -0.06 < bias < -0.02  # docs: ~37 ms short on the left foot's straight strides (L672)
