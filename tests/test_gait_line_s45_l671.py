"""Decision L671: the console gait line prints the step-time asymmetry index (with its standard error and "within
noise" on a foot + lower-back track), and the foot + lower-back track fills step_time_s_left / _right (trial T3
finding F7)."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.cli.common import asymmetry_clause
from pdrlearn.track.clinical import LEG_KEYS

ROUTE = "stand:3, straight:12, turn:180, straight:12, turn:180, straight:12, stand:3"


def test_the_clause_names_the_index_its_error_and_noise():
    assert asymmetry_clause({"step_time_asymmetry_pct": None}) == ""
    line = asymmetry_clause({"step_time_asymmetry_pct": 1.87, "step_time_asymmetry_se_points": 1.2})
    assert "step-time asymmetry 1.9 %" in line and "standard error 1.2 points" in line and "within noise" in line
    line = asymmetry_clause({"step_time_asymmetry_pct": 12.0, "step_time_asymmetry_se_points": 1.2})
    assert "12.0 %" in line and "within noise" not in line
    line = asymmetry_clause({"step_time_asymmetry_pct": 25.3, "step_time_asymmetry_se_points": None})
    assert "25.3 %" in line and "lower back alone" in line
    assert "step_time_asymmetry_se_points" in LEG_KEYS  # every summary has the key (W228)


@pytest.fixture(scope="module")
def tracked(tmp_path_factory):
    """Trial T3's walkway session u12780_normal (right shoe, no insoles) tracked with --toe-off."""
    d = tmp_path_factory.mktemp("t3") / "u12780"
    logging.disable(logging.WARNING)
    try:
        assert main(["simulate", "--route", ROUTE, "--speed", "normal", "--rate", "100", "--rocker", "smooth",
                     "--user-seed", "12780", "--out", str(d)]) == 0
    finally:
        logging.disable(logging.NOTSET)
    for f in d.glob("fForce*.csv"):
        f.unlink()
    return d


def test_the_foot_and_lower_back_track_prints_the_index_and_fills_the_sides(tracked, tmp_path, capsys):
    capsys.readouterr()
    assert main(["track", "--no-plot", "--toe-off", str(tracked), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    pct, se = s["step_time_asymmetry_pct"], s["step_time_asymmetry_se_points"]
    assert pct is not None and se is not None and se > 0
    gait = next(line for line in out.splitlines() if line.startswith("gait speed"))
    assert f"step-time asymmetry {pct:.1f} %" in gait and f"standard error {se:.1f} points" in gait
    left, right = s["step_time_s_left"], s["step_time_s_right"]  # meta.json: the right foot is instrumented
    assert left == pytest.approx(0.575, abs=0.03) and right == pytest.approx(0.570, abs=0.03)
    assert s["step_time_s_ratio"] == pytest.approx(left / right)
