"""Decision S70 (session 32 review item 8): ``backward:N:direct`` where there is no forward level walking to reverse
(before any step, after a stop, after stairs) gets S64's stop as ``backward:N`` does, and simulate says so in one
warning line; a direct reversal out of walking, and backward steps after backward steps (no stop either way), none."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

FS = 20.0


def _lines(route: str, caplog) -> list[str]:
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn.sim"):
        simulate_path(parse_route(route), UserProfile.from_seed(6705), rate_hz=FS, seed=1)
    return [r.getMessage() for r in caplog.records if "decision S70" in r.getMessage()]


@pytest.mark.parametrize("route, where", [("stand:3, backward:4:direct", "before any step"),
                                          ("straight:4, turn:90, backward:4:direct", "after a stop"),
                                          ("straight:4, up:3, backward:3:direct", "after stairs")])
def test_no_walk_to_reverse_is_one_line_s70(route, where, caplog):
    (line,) = _lines(route, caplog)
    n = route.rsplit("backward:", 1)[1].split(":")[0]
    assert f"backward:{n}:direct {where}" in line and f"as backward:{n} does, with S64's stop" in line


@pytest.mark.parametrize("route", ["straight:4, backward:4:direct", "straight:4, backward:3, backward:3:direct",
                                   "stand:3, backward:4"])
def test_a_reversal_or_no_stop_asked_is_silent_s70(route, caplog):
    assert _lines(route, caplog) == []


def test_the_cli_prints_it_once_s70(tmp_path, capsys):
    capsys.readouterr()
    assert main(["simulate", "--route", "stand:3, backward:8:direct", "--user-seed", "6706", "--rate", "20",
                 "--out", str(tmp_path / "s")]) == 0
    err = [ln for ln in capsys.readouterr().err.splitlines() if "decision S70" in ln]
    assert len(err) == 1 and err[0].startswith("warning: simulate: backward:8:direct before any step"), err
