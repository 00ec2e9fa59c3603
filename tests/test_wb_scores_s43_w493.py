"""Decision W493 (session 43, issue 8, trial T1 finding F2): `track` matches the detected bouts to the reference WBs
as mobgap's ``categorize_intervals`` does (overlap >= 0.8 of both durations: TP / FP / FN) and scores cadence, stride
length and speed per matched WB against INDIP's (wb_scores.csv; summary.json's WB keys)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.track.wb_scores import WB_SCORE_COLUMNS, match_intervals, wb_evaluation, wb_score_table
from tests.conftest import REAL


def _bouts(*rows):
    """Detected bouts: (start_s, end_s, cadence_spm, stride_length_m, speed_mps) per row, numbered from 1."""
    return pd.DataFrame([{"bout": i + 1, "start_s": a, "end_s": b, "cadence_spm": c, "stride_length_m": s,
                          "speed_mps": v} for i, (a, b, c, s, v) in enumerate(rows)])


def _ref(*rows):
    """Reference WBs (INDIP's bouts.csv names): (start_s, end_s, cadence_spm, avg_stride_length_m, speed_mps)."""
    return pd.DataFrame([{"wb_id": i, "start_s": a, "end_s": b, "cadence_spm": c, "avg_stride_length_m": s,
                          "speed_mps": v} for i, (a, b, c, s, v) in enumerate(rows)])


def test_a_bout_a_second_longer_at_each_end_of_a_short_wb_misses_mobgaps_080_but_matches_at_051():
    """A 5 s WB inside a 7 s bout: overlap 5 s = 1.0 of the WB but 0.714 of the bout -> FN + FP at 0.8 (both
    durations count, as mobgap's), TP at 0.51; the FN row still names the bout, its overlap and its edges."""
    bouts, ref = _bouts((9.0, 16.0, 100.0, 1.1, 0.9)), _ref((10.0, 15.0, 100.0, 1.0, 1.0))
    t = wb_score_table(bouts, ref)
    assert list(t.columns) == list(WB_SCORE_COLUMNS)
    assert sorted(t["match"]) == ["fn", "fp"]
    fn = t[t["match"] == "fn"].iloc[0]
    assert fn["bout"] == 1 and fn["overlap_s"] == pytest.approx(5.0)
    assert fn["overlap_ref_frac"] == pytest.approx(1.0) and fn["overlap_bout_frac"] == pytest.approx(5 / 7)
    assert fn["start_diff_s"] == pytest.approx(-1.0) and fn["end_diff_s"] == pytest.approx(1.0)
    _, keys = wb_evaluation(bouts, ref)
    assert (keys["n_wb_tp"], keys["n_wb_fp"], keys["n_wb_fn"]) == (0, 1, 1)
    assert keys["wb_f1"] == 0.0 and keys["wb_speed_error_median_pct"] is None  # no matched WB: no median
    t51, keys51 = wb_evaluation(bouts, ref, overlap_threshold=0.51)
    assert list(t51["match"]) == ["tp"] and keys51["wb_f1"] == 1.0
    assert t51["stride_length_error_pct"].iloc[0] == pytest.approx(10.0)
    assert keys51["wb_speed_error_median_signed_pct"] == pytest.approx(-10.0)


def test_one_bout_over_two_wbs_matches_neither():
    """T1's MS001 case: two INDIP WBs with a 4 s break become one bout - 2 FN and 1 FP (never 1 TP + 1 FN)."""
    bouts = _bouts((0.0, 20.0, 100, 1.0, 1.0))
    ref = _ref((1.0, 8.0, 100, 1.0, 1.0), (12.0, 19.0, 100, 1.0, 1.0))
    det, wbs = bouts[["start_s", "end_s"]].to_numpy(), ref[["start_s", "end_s"]].to_numpy()
    assert list(match_intervals(det, wbs)) == [-1, -1]
    t, keys = wb_evaluation(bouts, ref)
    assert list(t["match"]) == ["fp", "fn", "fn"]  # in time order: the bout starts first
    assert list(t["bout"].dropna()) == [1, 1, 1]
    assert (keys["n_wb_reference"], keys["wb_recall"], keys["wb_precision"]) == (2, 0.0, 0.0)


def test_counts_precision_recall_f1_and_medians_over_the_matched_wbs_only():
    """Three WBs, two matched (cadence +10 % and -20 %), one missed, two extra bouts: P 1/2, R 2/3; the medians are over
    the two TPs only (|error| 15 %, signed -5 %), not over the FN row's pairing."""
    bouts = _bouts((0.0, 10.0, 110, 1.0, 1.0), (20.0, 30.0, 80, 1.0, 1.0), (50.0, 60.0, 100, 1.0, 1.0),
                   (41.0, 43.5, 300, 1.0, 1.0))
    ref = _ref((0.5, 10.0, 100, 1.0, 1.0), (20.0, 29.0, 100, 1.0, 1.0), (40.0, 46.0, 100, 1.0, 1.0))
    t, keys = wb_evaluation(bouts, ref)
    assert list(t["match"]) == ["tp", "tp", "fn", "fp", "fp"]
    assert (keys["n_wb_tp"], keys["n_wb_fp"], keys["n_wb_fn"]) == (2, 2, 1)
    assert keys["wb_precision"] == pytest.approx(0.5) and keys["wb_recall"] == pytest.approx(2 / 3)
    assert keys["wb_f1"] == pytest.approx(2 * 0.5 * (2 / 3) / (0.5 + 2 / 3))
    assert keys["wb_cadence_error_median_pct"] == pytest.approx(15.0)
    assert keys["wb_cadence_error_median_signed_pct"] == pytest.approx(-5.0)
    assert t.loc[2, "cadence_error_pct"] == pytest.approx(200.0)  # the FN row's pairing, left out of the medians
    assert keys["wb_overlap_threshold"] == 0.8


@pytest.mark.parametrize("bad", [0.5, 0.3, 1.01, float("nan")])
def test_the_threshold_is_mobgaps_range(bad):
    with pytest.raises(ValueError, match="overlap_threshold"):
        match_intervals(np.array([[0.0, 1.0]]), np.array([[0.0, 1.0]]), bad)


def test_no_detected_bout_is_all_fn_and_no_reference_is_nothing():
    t, keys = wb_evaluation(_bouts(), _ref((1.0, 5.0, 100, 1.0, 1.0)))
    assert list(t["match"]) == ["fn"] and keys["wb_precision"] is None and keys["wb_recall"] == 0.0
    assert wb_evaluation(_bouts((0.0, 5.0, 100, 1.0, 1.0)), None) == (None, {})


def test_track_writes_wb_scores_csv_and_the_summary_keys_on_a_real_mobgap_session(tmp_path, capsys):
    """HA001 Test11 (6 INDIP WBs), waist-pendulum, --bout-rule mobgap: wb_scores.csv has a row per WB plus the
    unmatched bouts, every TP overlaps both by >= 0.8, the columns are in the dictionary and the summary's counts
    are the table's."""
    out = tmp_path / "t"
    assert main(["track", str(REAL / "mobgap_HA001_Test11_Trial1"), "--pipeline", "waist-pendulum", "--bout-rule",
                 "mobgap", "--out", str(out), "--no-plot"]) == 0
    assert "wb_scores.csv" in capsys.readouterr().out
    t = pd.read_csv(out / "wb_scores.csv")
    s = json.loads((out / "summary.json").read_text())
    assert undocumented("wb_scores.csv", t.columns) == []
    assert s["n_wb_reference"] == 6 == int(t["match"].isin(["tp", "fn"]).sum())
    assert s["n_wb_tp"] == int((t["match"] == "tp").sum()) >= 1
    assert s["n_wb_fp"] == int((t["match"] == "fp").sum())
    tp = t[t["match"] == "tp"]
    assert (tp[["overlap_ref_frac", "overlap_bout_frac"]] >= 0.8).all().all()
    bouts = pd.read_csv(out / "bouts.csv")
    assert set(t["bout"].dropna().astype(int)) <= set(bouts["bout"])
    assert s["wb_speed_error_median_pct"] == pytest.approx(float(tp["speed_error_pct"].abs().median()))
    assert "wb_scores" not in s["info"]  # the rows are the table's (E141), not the summary's
