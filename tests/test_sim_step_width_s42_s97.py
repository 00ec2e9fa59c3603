"""Decision S97 (session 42, trial T1 finding 10 of session 41): ``pdrlearn simulate --step-width METERS`` walks the
user with that distance between the feet's centre lines (0 = a tandem walk); a value that is not finite or outside
0-0.5 m is one ``error:`` line and no folder."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main

USER = 11801  # this session's simulated users for I6: 11800-11809
ROUTE = ["--route", "straight:4", "--stand", "0.5", "--user-seed", str(USER)]


def _lateral(d):
    """Median lateral position (m) of the instrumented foot and the user's step width in meta.json."""
    return (float(pd.read_csv(d / "foot_trajectory.csv")["y"].median()),
            json.loads((d / "meta.json").read_text())["user"]["step_width_m"])


def test_step_width_moves_the_foot_sideways_by_half_of_it(tmp_path):
    out = {}
    for w in ("0", "0.3"):
        assert main(["simulate", *ROUTE, "--step-width", w, "--out", str(tmp_path / w)]) == 0
        out[w] = _lateral(tmp_path / w)
    assert out["0"][1] == 0.0 and out["0.3"][1] == 0.3
    assert abs(out["0.3"][0] - out["0"][0]) == pytest.approx(0.15, abs=0.01)  # each foot half the width off the line


@pytest.mark.parametrize("bad", ["-0.1", "nan", "inf", "0.6"])
def test_a_bad_step_width_is_one_line_and_no_folder(tmp_path, capsys, bad):
    assert main(["simulate", *ROUTE, f"--step-width={bad}", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"--step-width {bad}: give the distance between the feet's" in err, err
    assert not (tmp_path / "x").exists()
