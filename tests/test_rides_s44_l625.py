"""Decision L625 (session 44, helper I2): ``pdrlearn steps --detector accel`` leaves out the strides track's L611
calls pedalling, with one line ("cycling?"), as track does; ``--keep-pedalling`` counts them and marks them in
--out's ``pedalling`` column; JSON ``pedalling_strides``. Simulated user 12140 (seed = user), 20 Hz, a 0.17 m crank
at 40 rpm in the seated span (tests/test_pedal_s43_l611.py's model)."""

from __future__ import annotations

import json
import logging

import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.sim_helpers import quiet_walk
from tests.test_pedal_s43_l611 import _pedal


@pytest.fixture(scope="module")
def cycling(tmp_path_factory):
    from pdrlearn.io import write_session

    s = quiet_walk("stand:3, straight:8, stand:2, sit:40, stand:2, straight:8, stand:3", 12140, 12140, rate_hz=20.0)
    tr = s.extras["transfers"]
    a, b = float(tr["seated_s"].iloc[0]) + 5, float(tr["rise_s"].iloc[0]) - 5
    _pedal(s, a, b, 40.0)
    d = tmp_path_factory.mktemp("l625") / "s"
    write_session(s, d)
    return d, a, b, len(s.steps)


def _steps(args, capsys, caplog):
    capsys.readouterr()
    with caplog.at_level(logging.WARNING):
        rc = main(["steps", *args, "--json"])
    return rc, json.loads(capsys.readouterr().out)


def test_steps_leaves_out_pedalling_like_track_l625(cycling, tmp_path, capsys, caplog):
    d, a, b, walked = cycling
    out = tmp_path / "kept.csv"
    rc, kept = _steps([str(d), "--detector", "accel", "--keep-pedalling", "--out", str(out)], capsys, caplog)
    assert rc == 0
    table = pd.read_csv(out)
    inside = (table["end_s"] > a) & (table["start_s"] < b)
    assert inside.sum() >= 10 and table["pedalling"][inside].all()  # the crank's strides, counted and marked
    assert int(table["pedalling"].sum()) == kept["pedalling_strides"] == int(inside.sum())
    caplog.clear()
    rc, dropped = _steps([str(d), "--detector", "accel"], capsys, caplog)
    assert rc == 0 and dropped["count"] == kept["count"] - kept["pedalling_strides"] == walked
    assert "rest_strides" not in dropped  # the rests inside the crank are no merged strides of the walk
    lines = [r.getMessage() for r in caplog.records if "cycling?" in r.getMessage()]
    assert len(lines) == 1 and "L611" in lines[0] and "--keep-pedalling" in lines[0]


def test_keep_pedalling_with_a_waist_detector_is_one_error_line_l625(cycling, capsys):
    d, *_ = cycling
    assert main(["steps", str(d), "--detector", "pelvic-gyro", "--keep-pedalling"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --keep-pedalling") and "L625" in err[0]
