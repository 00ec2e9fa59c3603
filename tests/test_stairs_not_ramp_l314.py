"""Decision L314 (session 31 prosthesis trial, finding 3): a lower-back track's steps that W108 puts on stairs (its
"N steps are on stairs" warning; steps.csv ``climb``) make no ramp (ramps.csv, ``n_ramps``) and no "ramps" climb
(``floors_*_ramps``), whatever grade their too-long pendulum lengths give; a foot track (no ``climb``) is unchanged.
Decision L330: only under the PARAMS.json option ``climb_veto`` (off by default)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import climb_kind, floors_by_kind
from pdrlearn.track.grade import climb_rows, ramp_runs

#: the trial's step-to-like stair climb: two contacts per 0.17 / 0.28 m stair (rise / run 0.085 / 0.14 m per contact)
STEPTO = "straight:5, up:34:0.085:0.14, straight:3, down:34:0.085:0.14, straight:5"


def test_rows_on_stairs_are_no_ramp_rows():
    length, dz = np.full(20, 0.7), np.full(20, 0.085)  # 12 %: a ramp grade, as the pendulum reads a stair step
    assert len(ramp_runs(length, dz, 3)) == 1
    assert ramp_runs(length, dz, 3, on_stairs=np.ones(20, bool)) == []
    dz0, pause = np.full(20, 0.085), np.zeros(20)
    rows = np.arange(20)
    assert climb_kind(dz0, pause, length, rows) == "ramps"
    assert climb_kind(dz0, pause, length, rows, np.ones(20, bool)) == "stairs"
    assert climb_kind(dz0, pause, length, rows, np.arange(20) < 9) == "ramps"  # 9 of 20: not more than half


VETO = {"options": {"climb_veto": True}}  # decision L330: L314's veto is opt-in


def test_climb_column_is_read_as_written():
    st = pd.DataFrame({"climb": [True, "False", "true", 0]})
    assert climb_rows(st, VETO).tolist() == [True, False, True, False]
    assert climb_rows(st) is None  # decision L330: no veto unless the option is set
    assert climb_rows(pd.DataFrame({"dz_m": [0.1]}), VETO) is None  # a foot track


@pytest.fixture(scope="module")
def stepto(tmp_path_factory):
    d = tmp_path_factory.mktemp("stepto")
    assert main(["simulate", "--route", STEPTO, "--user-seed", "6071", "--out", str(d / "sim")]) == 0
    return d


def test_waist_step_to_stairs_are_stairs_not_ramps(stepto, capsys):
    out = stepto / "waist"
    (stepto / "veto.json").write_text(json.dumps(VETO))
    assert main(["track", "--no-plot", str(stepto / "sim"), "--pipeline", "waist-pendulum", "--params",
                 str(stepto / "veto.json"),
                 "--out", str(out)]) == 0
    assert "steps are on stairs" in capsys.readouterr().err  # W155's line: W108's climbs
    s = json.loads((out / "summary.json").read_text())
    s = s.get("summary", s)
    steps = pd.read_csv(out / "steps.csv")
    assert steps["climb"].sum() >= 30
    kinds = ("floors_up_stairs", "floors_up_ramps", "floors_down_stairs", "floors_down_ramps")
    assert tuple(s[k] for k in kinds) == (1, 0, 1, 0)
    assert s["n_ramps"] == 0 and len(pd.read_csv(out / "ramps.csv")) == 0
    # the same rows without the column (the code before L314) read ramps: the column is what changed it
    assert floors_by_kind(steps.drop(columns="climb"), info=VETO)["floors_up_ramps"] == 1
    assert floors_by_kind(steps)["floors_up_ramps"] == 1  # L330: the column alone vetoes nothing


def test_foot_track_of_the_same_walk_has_no_climb_column(stepto):
    out = stepto / "foot"
    assert main(["track", "--no-plot", str(stepto / "sim"), "--altitude", "fused", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    s = s.get("summary", s)
    assert "climb" not in pd.read_csv(out / "steps.csv")
    assert (s["floors_up_stairs"], s["n_ramps"]) == (1, 0)
