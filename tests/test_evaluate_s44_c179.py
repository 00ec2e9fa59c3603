"""Decision C179 (trial T2, finding F3): `evaluate`'s headline for a task says how many side / turn strides C160
left out of its figures - main printed "direction: 181 steps - chosen nn/combined 98.3 % ..." with the 150 side /
turn strides named only on a line under the table, so the figure read as the whole walk's."""

from __future__ import annotations

from pdrlearn.classify.evaluation import headline
from pdrlearn.classify.uncovered import uncovered_note


def _result(uncovered):
    return {"accuracy": 1.0, "detected": {"n_steps": 181, "n_labelled": 181, "accuracy": 0.983},
            "uncovered": uncovered}


def test_the_headline_counts_the_strides_left_out():
    unc = {"n_steps": 150, "kinds": ["side", "turn"], "by_kind": {}}
    line = headline(_result(unc))
    assert line.startswith("98.3 % on the strides the runtime detects (181 of 181 labelled steps matched)")
    assert "; 150 side / turn stride(s) the classes do not cover are not in these figures" in line
    assert "decision C179" in line
    assert uncovered_note(_result(unc)) in line


def test_no_note_without_strides_left_out():
    for unc in (None, {"n_steps": 0, "kinds": ["side", "turn"], "by_kind": {}}):
        assert "C179" not in headline(_result(unc)) and uncovered_note(_result(unc)) == ""
    assert "C179" in headline({"accuracy": 0.9, "uncovered": {"n_steps": 3, "kinds": ["side"], "by_kind": {}}})
