"""Decision S48: `simulate` warns when a custom step is faster than 2.0 m/s (no running gait in the simulator);
walking speeds do not warn (a runner's trial, session 27, F5)."""
from __future__ import annotations

from pdrlearn.cli import main


def _sim(tmp_path, name, length, time, capsys):
    out = tmp_path / name
    code = main(["simulate", "--route", "stand:2, straight:6, stand:2", "--step-length", str(length),
                 "--step-time", str(time), "--user-seed", "1", "--out", str(out)])
    return code, capsys.readouterr().err


def test_a_running_speed_warns_once(tmp_path, capsys):
    code, err = _sim(tmp_path, "run", 1.0, 0.32, capsys)
    lines = [ln for ln in err.splitlines() if "decision S48" in ln]
    assert code == 0 and len(lines) == 1 and "3.12 m/s" in lines[0] and "not running" in lines[0]


def test_a_walking_speed_does_not_warn(tmp_path, capsys):
    code, err = _sim(tmp_path, "walk", 0.7, 0.5, capsys)
    assert code == 0 and "S48" not in err
    code, err = _sim(tmp_path, "edge", 1.0, 0.5, capsys)  # exactly 2.0 m/s: not over
    assert code == 0 and "S48" not in err
