"""Decision C144: the thesis' accuracies (Tables 27/28/33) live in pdrlearn.classify.thesis, used by the experiment,
evaluate's table, evaluation_frame and the train report's ``thesis_pct``."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_the_package_values_are_the_experiments_and_its_committed_csv():
    from experiments.characterization import THESIS
    from pdrlearn.classify.thesis import THESIS_ACCURACY, THESIS_TABLE

    assert THESIS is THESIS_ACCURACY  # one copy: the experiment reads the package's
    csv = pd.read_csv(ROOT / "experiments/results/characterization.csv")
    csv = csv[csv["thesis_pct"].notna()]
    assert len(csv) == sum(len(per) for rows in THESIS_ACCURACY.values() for per in rows.values()) == 88
    for r in csv.itertuples():
        assert THESIS_ACCURACY[r.task][(r.method, r.unit)][r._6] == r.thesis_pct
        assert THESIS_TABLE[r.task] == r.table


def _result(method="svm", unit="foot"):
    rec = {"per_class": {"flat": 0.9, "up": 1.0, "down": 0.8}, "accuracy": 0.9, "balanced_accuracy": 0.9,
           "latency_ms": 0.1, "n_steps": 30, "confusion": [[9, 1, 0], [0, 10, 0], [2, 0, 8]], "n_folds": 3}
    units = {"foot": rec, "fused": rec} if method == "svm" else {"fused": rec}
    methods = {method: {"units": {unit: rec}}} | {"svm": {"units": units}}
    return {"classes": ["flat", "up", "down"], "n_steps": 30, "accuracy": 0.9,
            "chosen": {"method": method, "unit": unit}, "methods": methods}


def test_evaluate_table_and_frame_show_the_thesis_figure_next_to_ours():
    from pdrlearn.classify.evaluation import markdown_tables, results_head, results_table
    from pdrlearn.tables import evaluation_frame

    r = _result()
    assert results_head(r, "terrain")[-1] == "thesis %"
    rows = {(row[0], row[1]): row[-1] for row in results_table(r, "terrain")}
    assert rows == {("svm", "foot"): "97.9", ("svm", "fused"): "-"}  # (99.4 + 99.4 + 94.9) / 3; no soft-vote row
    df = evaluation_frame({"boundaries": "given", "tasks": {"terrain": r}})
    th = dict(zip(df["unit"], df["thesis_pct"], strict=True))
    assert th["foot"] == pytest.approx(97.9) and (th["fused"] is None or math.isnan(th["fused"]))
    md = markdown_tables({"tasks": {"length": _result("nn", "combined") | {
        "classes": ["short", "normal", "long"],
        "methods": {"nn": {"units": {"combined": {**r["methods"]["svm"]["units"]["foot"],
                                                  "per_class": {"short": 1.0, "normal": 0.9, "long": 0.8}}}}}}}})
    assert "| thesis % |" in md and "| 95.4 |" in md  # thesis Table 33 NN fusion: (100 + 90.0 + 96.2) / 3


def test_train_report_cv_table_has_thesis_pct():
    from pdrlearn.classify.cv_report import cv_frame, display_table

    r = _result("dtw", "waist")
    manifest = {"tasks": {"terrain": {"classes": r["classes"], "n_steps": 30, "chosen": r["chosen"],
                                      "cv": {m: d["units"] for m, d in r["methods"].items()}}}}
    df = cv_frame(manifest)
    th = {(m, u): v for m, u, v in zip(df["method"], df["unit"], df["thesis_pct"], strict=True)}
    assert th[("dtw", "waist")] == pytest.approx(75.3)  # thesis Table 27: (59 + 98 + 69) / 3
    assert th[("svm", "fused")] is None or math.isnan(th[("svm", "fused")])
    assert list(display_table(df, r["classes"]).columns[3:7]) == ["flat %", "up %", "down %", "all %"]
    assert "thesis %" in display_table(df, r["classes"]).columns


def test_pdrlearn_report_of_an_evaluation_shows_the_thesis_column(tmp_path):
    import json

    from pdrlearn.report.build import collect

    (tmp_path / "evaluation.json").write_text(json.dumps({"boundaries": "given", "tasks": {"terrain": _result()}}))
    tables = [df for sec in collect(tmp_path) for _, df in sec.tables]
    th = dict(zip(tables[0]["unit"], tables[0]["thesis %"], strict=True))
    assert th["foot"] == pytest.approx(97.9) and (th["fused"] is None or math.isnan(th["fused"]))
