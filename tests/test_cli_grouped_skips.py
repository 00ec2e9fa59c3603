"""`train` lists the models it skipped once per reason: on a foot-only recording it printed one line per
method x unit (nine lines for two reasons)."""

from __future__ import annotations

from pathlib import Path

from pdrlearn.cli import main
from pdrlearn.cli.common import grouped_skips

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def test_grouped_skips_one_line_per_reason_in_order():
    assert grouped_skips(["heuristic/waist: no waist", "fusion/fused: needs both units", "svm/waist: no waist",
                          "a sentence: without a model name", "svm/fused: needs both units"]) == [
        "heuristic/waist, svm/waist: no waist", "fusion/fused, svm/fused: needs both units",
        "a sentence: without a model name"]
    assert grouped_skips([]) == []


def test_train_on_foot_only_data_prints_each_reason_once(tmp_path, capsys):
    sessions = [str(REAL / s) for s in ("gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")]
    assert main(["train", *sessions, "--out", str(tmp_path / "m"), "--tasks", "terrain", "--methods",
                 "heuristic,svm", "--cv", "3"]) == 0
    skipped = [ln.strip() for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("skipped ")]
    # default units: svm's two-unit model is the combined one (its soft vote is not trained, decision C23)
    assert skipped == ["skipped heuristic/waist, svm/waist: no session has the waist unit",
                       "skipped svm/combined: needs both units"], skipped
