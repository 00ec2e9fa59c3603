"""`pdrlearn simulate --route`: a path written as text (decision S28)."""

from __future__ import annotations

import json
import math

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import Backward, Curve, Stairs, Stand, Straight, Turn
from pdrlearn.sim.route import parse_route


def test_parse_route_every_kind():
    segs = parse_route(" straight:10:long, curve:-90:2, up:12, down:3:0.15:0.3, backward:4, turn:180, stand:2.5 ")
    assert segs == [
        Straight(10.0, gait="long"),
        Curve(math.radians(-90.0), 2.0),
        Stairs(12, up=True),
        Stairs(3, up=False, rise_m=0.15, run_m=0.3),
        Backward(4),
        Turn(math.pi),
        Stand(2.5),
    ]


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("", "empty"),
        ("straight:10,,up:3", "empty item"),
        ("upp:3", "unknown kind 'upp'"),
        ("straight", "takes 1 or 2 or 3 value"),  # decision S88: :PACE
        ("up:3:0.17", "takes N or N:RISE:RUN"),
        ("up:2.5", "not a whole number"),
        ("straight:-4", "positive"),
        ("straight:nan", "positive"),
        ("straight:10:brisk", "'brisk' must be a gait"),  # decision S88
        ("turn:0", "non-zero"),
        ("curve:0:2", "non-zero"),
        ("backward:x", "not a number"),
    ],
)
def test_parse_route_refuses_bad_items_in_one_line(spec, message):
    with pytest.raises(DataError, match=message) as err:
        parse_route(spec)
    assert "\n" not in str(err.value)


def test_cli_route_simulates_the_written_path(tmp_path, capsys):
    out = tmp_path / "floors"
    route = "straight:4, up:10, turn:180, down:10, backward:3"
    code = main(["simulate", "--route", route, "-u", "1", "-o", str(out), "--json"])
    stdout, err = capsys.readouterr()
    assert code == 0, err
    summary = json.loads(stdout)
    assert summary["scenario"] == "route" and summary["route"].startswith("straight:4")
    assert summary["terrain"]["up"] > 0 and summary["terrain"]["down"] > 0
    meta = json.loads((out / "meta.json").read_text())
    assert "route_u1" in json.dumps(meta)
    steps = (out / "steps.csv").read_text()
    assert "backward" in steps


def test_cli_route_and_scenario_are_exclusive(tmp_path, capsys):
    for args in (["-s", "A", "--route", "straight:5"], []):
        code = main(["simulate", *args, "-u", "1", "-o", str(tmp_path / "x")])
        err = capsys.readouterr().err
        assert code == 2
        assert "either --scenario" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x").exists()
