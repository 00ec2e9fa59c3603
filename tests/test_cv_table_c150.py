"""Decision C150: one function builds a model's CV table (``cv_report.display_table``); train's console table,
``train --report``'s report.md and ``pdrlearn report MODEL_DIR`` render it, so the three carry the same rows and
numbers, the thesis' figure (C144) included. Users 9660-9662 (C143's model, testing decision D51)."""

from __future__ import annotations

import pytest

from tests.sim_helpers import terrain_cv_model


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """train's console text, train --report's report.md and pdrlearn report's report.md of one model (users
    9660-9662, shared with decision C143's tests: ``tests.sim_helpers.terrain_cv_model``)."""
    root = terrain_cv_model(tmp_path_factory)
    return ((root / "console.txt").read_text(encoding="utf-8"), (root / "rep" / "report.md").read_text(),
            (root / "R" / "report.md").read_text())


def _rows(lines, sep):
    """{(method, unit): {header: cell}} of the first table whose header starts with ``method``."""
    cells = [[c.strip() for c in line.strip().strip(sep).split(sep)] for line in lines]
    head = cells[0]
    return {(r[0], r[1]): dict(zip(head, r, strict=True)) for r in cells[1:]}


def _console_table(text):
    lines = text.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("┃ method"))
    body = [line for line in lines[i + 2:] if line.startswith("│")]
    return _rows([lines[i].replace("┃", "│"), *body[:5]], "│")


def _md_table(text):
    lines = text.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("| method"))
    body = []
    for line in lines[i + 2:]:
        if not line.startswith("|"):
            break
        body.append(line)
    return _rows([lines[i], *body], "|")


def _numbers(rows):
    def num(v):
        return None if v in ("", "-", "nan") else float(v)

    return {k: {h: num(v) for h, v in r.items() if h.endswith("%")} for k, r in rows.items()}


def test_console_report_md_and_pdrlearn_report_carry_the_same_cv_numbers(outputs):
    console, train_md, report_md = outputs
    con, md, rep = _console_table(console), _md_table(train_md), _md_table(report_md)
    assert set(con) == set(md) == set(rep) and len(con) == 5
    assert "thesis %" in next(iter(con.values()))  # the console had no thesis' figure (C144 elsewhere only)
    assert _numbers(con) == _numbers(md) == _numbers(rep)
    assert _numbers(con)[("svm", "foot")]["thesis %"] == 97.9  # thesis Table 27, as C144's test
    for k in con:  # the folds' spread and interval, and which model is chosen, the same text
        assert con[k]["folds"] == md[k]["folds"] == rep[k]["folds"]
        assert con[k]["95 % CI"] == md[k]["95 % CI"] == rep[k]["95 % CI"]
        assert (con[k]["chosen"] == "yes") == (md[k]["chosen"] == "yes") == (rep[k]["chosen"] == "yes")


def test_the_console_keeps_trains_ranking_and_a_piped_width_under_120(outputs):
    console = outputs[0]
    rows = [line for line in console.splitlines() if line.startswith("│")]
    balanced = [float(r.split("│")[8]) for r in rows]  # decision C36: ranked by balanced accuracy
    assert balanced == sorted(balanced, reverse=True)
    assert max(len(line) for line in console.splitlines() if line[:1] in "┏┃│└") < 120


def test_the_column_dictionary_takes_cv_csvs_names_from_the_writer():
    """Decision C150: columns.py's TRAIN_CV / TRAIN_LOUO are named by cv_report's lists, not a copy of them; a
    column the writer adds without a meaning (or a meaning of no column) fails at import."""
    from pdrlearn.classify.cv_report import CLASS_COLUMN, CV_COLUMNS, LOUO_COLUMNS
    from pdrlearn.columns import TRAIN_CV, TRAIN_LOUO, _named

    assert [c[0] for c in TRAIN_CV] == [*CV_COLUMNS, CLASS_COLUMN]
    assert [c[0] for c in TRAIN_LOUO] == list(LOUO_COLUMNS)
    meanings = {"task": ("-", "text", "t")}
    assert _named(("task",), meanings) == (("task", "-", "text", "t"),)
    with pytest.raises(KeyError, match="new_pct"):
        _named(("task", "new_pct"), meanings)


def test_the_table_rounds_once():
    """Decision C150: 29 of 31 steps is 93.548 %; cv_rows rounded it to 93.55 and the table to 93.6 (rounded
    twice). The table now says 93.5 as train's console did; cv.csv keeps two decimals (93.55)."""
    from pdrlearn.classify.cv_report import cv_frame, display_table, rounded

    acc = 29 / 31
    rec = {"per_class": {"flat": acc, "up": 1.0}, "accuracy": acc, "balanced_accuracy": acc, "n_steps": 31,
           "n_folds": 3, "folds": {"mean": acc, "sd": 0.0, "ci95": [0.7858, 0.9925]}}
    manifest = {"user": "x", "tasks": {"terrain": {"classes": ["flat", "up"], "n_steps": 31,
                                                   "chosen": {"method": "svm", "unit": "foot"},
                                                   "cv": {"svm": {"foot": rec}}}}}
    cv = cv_frame(manifest)
    row = display_table(cv, ["flat", "up"]).iloc[0]
    assert (row["all %"], row["balanced %"], row["flat %"]) == (93.5, 93.5, 93.5)
    assert row["folds"] == "93.5±0.0" and row["95 % CI"] == "78.6-99.2"
    assert rounded(cv, 2)["accuracy_pct"].iloc[0] == 93.55
