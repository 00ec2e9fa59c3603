"""Decision W495 (session 43, trial T1 finding F2): `--bout-rule mobgap-indip` is mobgap's bout rule with each
lower-back bout from its second contact to its last-but-one (the detected bouts start and end beyond INDIP's WBs);
an option, not the default."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.bouts import bout_rule, detected_bouts


def _waist(contacts, length=0.6):
    """A lower-back step table: one row per contact, a step to the next one unless it is the sequence's last."""
    c = np.asarray(contacts, float)
    nxt = np.r_[c[1:], c[-1]]
    closing = np.r_[np.diff(c) > 1.5, True]  # the contact before a break (and the last) closes a sequence
    return pd.DataFrame({"start_s": c, "end_s": np.where(closing, c, nxt), "event_s": c, "unit": "waist",
                         "length_m": np.where(closing, 0.0, length), "has_next": ~closing})


def test_mobgap_indip_cuts_each_bout_to_its_second_and_last_but_one_contact():
    """Two walks of 10 contacts 0.5 s apart, 10 s between: mobgap's bouts run 0-4.5 s and 14.5-19 s (9 steps,
    5.4 m); mobgap-indip's 0.5-4.0 s and 15-18.5 s, 7 steps (4.2 m), speed 4.2 / 3.5 m/s, same cadence."""
    st = _waist([*np.arange(10) * 0.5, *(14.5 + np.arange(10) * 0.5)])
    full = detected_bouts(st, bout_rule(preset="mobgap"))
    cut = detected_bouts(st, bout_rule(preset="mobgap-indip"))
    assert list(full["start_s"]) == [0.0, 14.5] and list(full["end_s"]) == [4.5, 19.0]
    assert list(cut["start_s"]) == [0.5, 15.0] and list(cut["end_s"]) == [4.0, 18.5]
    assert list(cut["bout"]) == [1, 2]
    assert cut["distance_m"].tolist() == pytest.approx([4.2, 4.2]) and full["distance_m"].tolist() == pytest.approx(
        [5.4, 5.4])
    assert cut["speed_mps"].tolist() == pytest.approx([4.2 / 3.5] * 2)
    assert cut["stride_length_m"].tolist() == pytest.approx([1.2, 1.2])  # 2 x the 0.6 m step, as before the cut
    assert cut["cadence_spm"].tolist() == pytest.approx(full["cadence_spm"].tolist())
    assert (cut["n_steps"] == full["n_steps"] - 2).all()


def test_the_bouts_kept_are_the_rules_before_the_cut_and_the_definition_says_so():
    """A bout of 6 contacts (4 strides) is kept by mobgap's 4-stride minimum and cut to 4 contacts; one of 5
    contacts is left out by both. summary.json's bout_definition names trim_edges only when it is on."""
    st = _waist([*np.arange(6) * 0.5, *(20 + np.arange(5) * 0.5)])
    assert len(detected_bouts(st, bout_rule(preset="mobgap"))) == 1
    cut = detected_bouts(st, bout_rule(preset="mobgap-indip"))
    assert len(cut) == 1 and (cut["start_s"].iloc[0], cut["end_s"].iloc[0]) == (0.5, 2.0)
    assert bout_rule(preset="mobgap-indip").record() == {"break_s": 3.0, "min_strides": 4, "gap": "contact",
                                                        "trim_edges": True}
    assert bout_rule(preset="mobgap").record() == {"break_s": 3.0, "min_strides": 4, "gap": "contact"}


def test_a_foot_track_is_refused_in_one_line():
    st = _waist(np.arange(10) * 1.0).assign(unit="foot")
    with pytest.raises(DataError, match="mobgap-indip.*foot.*--bout-rule mobgap"):
        detected_bouts(st, bout_rule(preset="mobgap-indip"))


def test_track_with_mobgap_indip_matches_t1s_straight_walk(tmp_path):
    """Trial T1's example, HA001 Test5 T2 (INDIP WB 3.92-8.61 s): under `mobgap` the bout 2.99-9.31 s overlaps 0.742
    of itself, an FN + FP at mobgap's 0.8; under `mobgap-indip` it is a TP (W493's wb_scores.csv)."""
    import json

    from pdrlearn.cli import main
    from tests.conftest import REAL

    rows = {}
    for rule in ("mobgap", "mobgap-indip"):
        out = tmp_path / rule
        assert main(["track", str(REAL / "mobgap_HA001_Test5_Trial2"), "--pipeline", "waist-pendulum", "--bout-rule",
                     rule, "--out", str(out), "--no-plot"]) == 0
        rows[rule] = (pd.read_csv(out / "wb_scores.csv"), json.loads((out / "summary.json").read_text()))
    base, cut = rows["mobgap"][0], rows["mobgap-indip"][0]
    assert sorted(base["match"]) == ["fn", "fp"] and list(cut["match"]) == ["tp"]
    assert base.loc[base["match"] == "fn", "overlap_bout_frac"].iloc[0] < 0.8
    assert rows["mobgap-indip"][1]["bout_definition"]["trim_edges"] is True
    assert "trim_edges" not in rows["mobgap"][1]["bout_definition"]
