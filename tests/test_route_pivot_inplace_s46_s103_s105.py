"""Decisions S103 / S104 / S105 (session 46, FK, trial T2 finding F6): a pivot over its per-step cap is one line in
the route's own words (S103: it printed ``Pivot(angle_rad=6.28..., ...)``), naming the steps it needs and the curve
for a spin (S104: the cap stays); ``inplace:N`` steps on the spot (S105)."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim.path import MAX_TURN_STEP_RAD, InPlace, Pivot, check_pivot
from pdrlearn.sim.route import parse_route


@pytest.mark.parametrize("item, least", [("pivot:360:2", 6), ("pivot:90:1", 2), ("pivot:-200:3", 4)])
def test_a_pivot_over_the_cap_is_named_in_the_route_s_words_s103(item, least):
    with pytest.raises(DataError) as err:
        parse_route(f"stand:2, straight:2, {item}, straight:2")
    msg = str(err.value)
    deg = item.split(":")[1]
    assert msg.startswith(f"--route item '{item}': a pivot turns at most {math.degrees(MAX_TURN_STEP_RAD):.0f} deg")
    assert f"pivot:{deg}:{least} or more steps" in msg and f"curve:{deg}:" in msg
    assert "Pivot(" not in msg and "angle_rad" not in msg and "\n" not in msg


def test_the_cap_holds_and_its_least_steps_parse_s104():
    for deg, n in ((360, 6), (90, 2), (-200, 4)):
        assert parse_route(f"pivot:{deg}:{n}") == [Pivot(math.radians(deg), n_steps=n, step_m=0.15)]
    with pytest.raises(DataError, match="the step must be 0-0.3 m"):
        parse_route("pivot:90:2:0.5")
    with pytest.raises(DataError, match=r"n_steps >= 6"):  # the Python segment's own terms
        check_pivot(2 * math.pi, 2, 0.15, "Pivot(...)")


def test_simulate_cli_error_is_one_line_without_a_repr_s103(tmp_path, capsys):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", "stand:2, pivot:360:2", "-u", "21", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--route item 'pivot:360:2'" in err and "Pivot(" not in err and "Traceback" not in err
    assert not out.exists()


def test_inplace_steps_on_the_spot_s105(tmp_path, capsys):
    assert parse_route("inplace:6") == [InPlace(6)]
    for bad in ("inplace:0", "inplace:2.5", "inplace:x", "inplace:2:3"):
        with pytest.raises(DataError, match=f"--route item '{bad}'"):
            parse_route(bad)
    out = tmp_path / "s"
    assert main(["simulate", "--route", "stand:2, straight:2, inplace:6, straight:2, stand:2", "-u", "21",
                 "--rate", "20", "--out", str(out)]) == 0
    capsys.readouterr()
    truth = pd.read_csv(out / "steps.csv")
    spot = truth[(truth["kind"] == "turn")]
    assert len(spot) >= 2  # the instrumented foot's strides on the spot
    assert (spot["heading_change_deg"].abs() < 1e-6).all()
    assert (spot["length_m"].iloc[1:] < 0.05).all()  # the first leaves the walk; the others stay put
    walked = pd.read_csv(out / "trajectory.csv")
    assert abs(float(walked["x"].iloc[-1]) - 4.0) < 0.5 and abs(float(walked["y"].iloc[-1])) < 0.1
