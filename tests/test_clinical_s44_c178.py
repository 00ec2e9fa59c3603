"""Decision C178 (session 44, trial T1 finding F11): with ``--walk-test-duration`` the ``--per`` periods are the
test's minutes - ``--per-align`` defaults to first-step (the test's "go", L516); ``--per-align start`` still gives
the recording's."""
from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main

ROUTE = "stand:5, straight:30, turn:180, straight:30, stand:3"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("c178")
    assert main(["simulate", "--route", ROUTE, "--user-seed", "12440", "--rate", "100", "--out", str(d / "s")]) == 0
    return d


def _summary(out):
    return json.loads((out / "summary.json").read_text())


def test_walk_test_periods_start_at_the_first_step(walk):
    out = walk / "auto"
    assert main(["track", "--no-plot", str(walk / "s"), "--units", "waist", "--corridor", "30",
                 "--walk-test-duration", "60", "--per", "30", "--out", str(out)]) == 0
    s = _summary(out)
    assert s["per_align"] == "first-step"
    assert s["per_start_s"] > 4.0  # the first step after 5 s standing, not the recording's 0 s


def test_an_explicit_per_align_start_is_kept(walk):
    out = walk / "start"
    assert main(["track", "--no-plot", str(walk / "s"), "--units", "waist", "--corridor", "30",
                 "--walk-test-duration", "60", "--per", "30", "--per-align", "start", "--out", str(out)]) == 0
    s = _summary(out)
    assert "per_align" not in s and s["per_start_s"] < 1.0


def test_without_a_walk_test_the_periods_start_at_the_recording(walk):
    out = walk / "plain"
    assert main(["track", "--no-plot", str(walk / "s"), "--units", "waist", "--per", "30", "--out", str(out)]) == 0
    assert _summary(out)["per_start_s"] < 1.0
