"""Session 42, fixer FG (trial T3 finding F1, decision L602): the "ramps / grades need --altitude fused" line (L574)
counts only the barometer's climb the track's stair flights do not explain (``flights_rise_m`` / ``flights_drop_m``,
stairs.csv's heights) over L146's 0.5 m band, so scenario D (``make demo``'s four tracks) and README's floors route
stay quiet, while a ramp beside stairs is still said."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import ramps_need_fused_warning
from pdrlearn.track.stair_flights import KEYS, flight_summary

LINE = "ramps / grades need --altitude fused"
#: README's "your own path" route (T3's walks/floors)
FLOORS = "straight:5, up:17, turn:180, down:17, backward:3"
#: stairs up, a 24 m 1:12 ramp down (2.0 m): the descent is no stair flight's
MIX = "stand:3, straight:4, up:17, straight:4, turn:180, slope:24:-8.33, straight:4, stand:3"


def _track(tmp_path, capsys, sim_args, user):
    d = tmp_path / "s"
    assert main(["simulate", *sim_args, "--user-seed", str(user), "--out", str(d)]) == 0
    capsys.readouterr()
    assert main(["track", str(d), "--out", str(tmp_path / "t"), "--no-plot"]) == 0
    return json.loads((tmp_path / "t" / "summary.json").read_text()), capsys.readouterr().err


@pytest.mark.parametrize(("sim_args", "user"), [(["--scenario", "D"], 1), (["--route", FLOORS], 11866)])
def test_stair_walks_are_quiet_l602(tmp_path, capsys, sim_args, user):
    s, err = _track(tmp_path, capsys, sim_args, user)
    assert s["barometer_unused"] and s["barometer_ascent_m"] > 2.0  # the barometer climbed a storey ...
    flights = pd.read_csv(tmp_path / "t" / "stairs.csv")["height_m"]
    assert s["flights_rise_m"] == pytest.approx(flights[flights > 0].sum())  # ... which stairs.csv explains
    assert s["flights_drop_m"] == pytest.approx(-flights[flights < 0].sum() + 0.0)
    assert LINE not in err and ramps_need_fused_warning(s) is None


def test_a_ramp_beside_stairs_is_still_said_l602(tmp_path, capsys):
    s, err = _track(tmp_path, capsys, ["--route", MIX], 11869)
    assert s["flights_drop_m"] == 0.0 and s["barometer_descent_m"] > 1.0
    line = next(ln for ln in err.splitlines() if LINE in ln)
    assert "more than stairs.csv's flights, L602" in line


def test_the_rule_l602():
    s = {"barometer_unused": True, "grade_source": None, "barometer_ascent_m": 3.78, "barometer_descent_m": 0.0}
    assert LINE in ramps_need_fused_warning(s)  # L574 alone: no flight explains the climb
    assert ramps_need_fused_warning({**s, "flights_rise_m": 3.97, "flights_drop_m": 0.0}) is None
    assert ramps_need_fused_warning({**s, "flights_rise_m": 3.30, "flights_drop_m": 0.0}) is None  # 0.48 m: band
    assert "0.59 m / 0.00 m more" in ramps_need_fused_warning({**s, "flights_rise_m": 3.19, "flights_drop_m": 0.0})
    steps = pd.DataFrame({"start_s": range(6), "end_s": range(1, 7), "length_m": 0.6, "unit": "foot",
                          "dz_m": [0.0, 0.34, 0.33, 0.0, -0.3, -0.31]})
    assert set(flight_summary(steps)) == set(KEYS)
    assert flight_summary(steps)["flights_rise_m"] == pytest.approx(0.67)
    assert flight_summary(steps)["flights_drop_m"] == pytest.approx(0.61)
    assert flight_summary(steps.assign(unit="waist"))["flights_rise_m"] is None  # no flights on the lower back
