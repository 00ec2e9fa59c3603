"""Decisions S90 (``simulate --stand``: the standstill before and after the walk) and S91 (``simulate --route``'s
help lists every item kind the parser accepts)."""

import json

import pandas as pd
import typer

from pdrlearn.cli import app, main
from pdrlearn.sim.route import ROUTE_KINDS, parse_route


def _param_help(command: str, name: str) -> str:
    cmd = typer.main.get_command(app).commands[command]
    return next(p.help for p in cmd.params if p.name == name).replace("[i][/i]", "")


def test_route_help_lists_every_kind_the_parser_accepts_s91():
    text = _param_help("simulate", "route")
    for kind in ROUTE_KINDS:
        assert f"'{kind}:" in text, kind
    for form in ("'sit:S'", "'pivot:DEG[:N[:STEP]]'", "'straight:M[:GAIT][:PACE]'"):  # the trial's missing three
        assert form in text
    parse_route("sit:2, pivot:90, straight:5:fast")  # the listed forms parse



def test_simulate_stand_sets_the_standstill_around_the_walk_s90(tmp_path, capsys):
    short, default = tmp_path / "short", tmp_path / "default"
    base = ["simulate", "--route", "straight:3", "-u", "10095", "--rate", "20"]
    assert main([*base, "--stand", "0.5", "--out", str(short)]) == 0
    assert main([*base, "--out", str(default)]) == 0
    span = {f: pd.read_csv(f / "trajectory.csv")["timestamp"].iloc[-1] / 1000.0 for f in (short, default)}
    assert span[default] - span[short] > 8.0  # 2 x (5 - 0.5) s of standstill less (13.2 s -> 4.2 s)
    assert json.loads((short / "meta.json").read_text())["knobs"]["stand_s"] == 0.5
    capsys.readouterr()
    assert main([*base, "--stand", "0.1", "--out", str(tmp_path / "bad")]) == 2
    err = capsys.readouterr().err
    assert "--stand 0.1: give the standstill" in err and "Traceback" not in err
    assert not (tmp_path / "bad").exists()
