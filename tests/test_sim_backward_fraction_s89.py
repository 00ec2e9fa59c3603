"""Decision S89 (session 38, trial T5 finding 10): ``backward:N`` takes a fraction of a backward step (0.5 = half a
step, one short step); under a quarter of a step is one line, exit 2."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim.path import Backward
from pdrlearn.sim.route import parse_route


def test_fractional_backward_steps_parse():
    assert parse_route("backward:0.6, backward:3, backward:1.5:direct") == [
        Backward(0.6), Backward(3), Backward(1.5, direct=True)]
    with pytest.raises(DataError, match="under 0.25 of a step"):
        parse_route("backward:0.1")


def test_half_a_step_backward_is_half_as_long(tmp_path):
    """User 9790: the backward stride of 'backward:0.5' is about half that of 'backward:1' (main refused 0.5)."""
    from pdrlearn.cli import main

    lengths = []
    for n in ("0.5", "1"):
        out = tmp_path / n
        assert main(["simulate", "--route", f"straight:3, backward:{n}, stand:2", "--user-seed", "9790",
                     "--out", str(out)]) == 0
        steps = pd.read_csv(out / "steps.csv")
        back = steps[steps["direction"] == "backward"]
        assert len(back) == 1
        lengths.append(float(back["length_m"].iloc[0]))
    assert 0.4 < lengths[0] / lengths[1] < 0.6


def test_too_small_backward_is_one_line(tmp_path, capsys):
    from pdrlearn.cli import main

    assert main(["simulate", "--route", "backward:0.1", "--user-seed", "9791", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "decision S89" in err and "Traceback" not in err
    assert not (tmp_path / "x").exists()
