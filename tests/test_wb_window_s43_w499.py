"""Decision W499 (session 43, fixer FJ; amends W493, docs/decisions/waist.md): with ``track --window`` a reference WB
the window cuts is dropped (L272) and so are the detected bouts that overlap it - review R1 finding 4: the cut
detected bout of that walk was kept and scored a false positive (HA001 Test11, --window 30,60: n_wb_fp 1, F1 0.667)."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.wb_scores import outside_spans

HA001 = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


def test_outside_spans_kernel_w499():
    bouts = pd.DataFrame({"bout": [1, 2, 3], "start_s": [30.01, 37.79, 55.0], "end_s": [31.28, 51.37, 60.0]})
    assert outside_spans(bouts, None) is bouts and outside_spans(bouts, []) is bouts
    kept = outside_spans(bouts, [{"start_s": 28.64, "end_s": 33.24}, {"start_s": 59.5, "end_s": 64.0}])
    assert kept["bout"].tolist() == [2]  # the bouts numbered as bouts.csv's
    assert outside_spans(None, [{"start_s": 0.0, "end_s": 1.0}]) is None


def test_a_wb_cut_by_the_window_is_no_false_positive_w499(tmp_path):
    out = tmp_path / "w"
    assert main(["track", str(HA001), "--pipeline", "waist-pendulum", "--no-plot", "--out", str(out),
                 "--window", "30,60"]) == 0
    table = pd.read_csv(out / "wb_scores.csv")
    assert table["match"].tolist() == ["tp"] and table["ref_wb"].tolist() == [2]
    s = json.loads((out / "summary.json").read_text())
    assert s["n_wb_fp"] == 0 and s["wb_f1"] == 1.0
    assert "window_cut_wbs" not in s["info"]  # E141: not a summary value
