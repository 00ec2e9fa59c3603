"""Decision steps 85 (session 45, I4): ``pdrlearn score-steps`` leaves a foot table's pedalling strides (L611: a bike
ride's crank turns) out of its count and scores, with L611's one line, as ``steps`` does (L625);
``--keep-pedalling`` scores them. Before, score-steps judged no pedalling: on L625's ride (user 12140) the table
``steps --keep-pedalling --out`` writes scored precision 0.270. L625's fixture, shared."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from tests.test_rides_s44_l625 import cycling  # noqa: F401  (L625's ride, a module fixture)


@pytest.fixture(scope="module")
def detections(cycling, tmp_path_factory):  # noqa: F811
    """``steps --detector accel --keep-pedalling``'s table: every stride, the crank's marked."""
    d, *_ = cycling
    out = tmp_path_factory.mktemp("s85") / "det.csv"
    logging.disable(logging.WARNING)
    try:
        assert main(["steps", str(d), "--detector", "accel", "--keep-pedalling", "--out", str(out)]) == 0
    finally:
        logging.disable(logging.NOTSET)
    return d, out


def _score(args, capsys, caplog):
    capsys.readouterr()
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        rc = main(["score-steps", *args, "--json"])
    return rc, json.loads(capsys.readouterr().out), [r.getMessage() for r in caplog.records]


def test_score_steps_leaves_out_pedalling_like_steps_85(cycling, detections, capsys, caplog):  # noqa: F811
    d, a, b, walked = cycling
    _, det = detections
    rc, steps = _score_steps_json(d, capsys)
    rc, scored, lines = _score([str(d), str(det)], capsys, caplog)
    assert rc == 0 and scored["count"] == steps["count"] == walked  # main: the crank's strides counted too
    assert scored["pedalling_strides"] == steps["pedalling_strides"] > 0
    assert scored["precision"] == scored["f1"] == 1.0 and scored["count_error_pct"] == 0.0
    said = [m for m in lines if "cycling?" in m]
    assert len(said) == 1 and "left out of the count" in said[0] and "L611" in said[0]
    rc, kept, lines = _score([str(d), str(det), "--keep-pedalling"], capsys, caplog)
    assert rc == 0 and kept["count"] == walked + scored["pedalling_strides"] and kept["precision"] < 0.5
    assert sum("cycling?" in m for m in lines) == 1


def _score_steps_json(d, capsys):
    capsys.readouterr()
    logging.disable(logging.WARNING)
    try:
        rc = main(["steps", str(d), "--detector", "accel", "--json"])
    finally:
        logging.disable(logging.NOTSET)
    return rc, json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("extra", [["--all-rows"], ["--unit", "waist"]])
def test_keep_pedalling_where_nothing_is_judged_is_one_error_line_85(detections, capsys, extra):
    d, det = detections
    capsys.readouterr()
    assert main(["score-steps", str(d), str(det), "--keep-pedalling", *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --keep-pedalling") and "leave --keep-pedalling out" in err[0]
