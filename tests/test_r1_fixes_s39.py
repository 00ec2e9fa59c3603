"""Review R1's findings fixed in session 39 (fixer FL): decisions W425, W425, L528, L529, L530."""

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.test_court_flags_w416 import add_jumps


@pytest.fixture(scope="module")
def jumps_then_walk(tmp_path_factory):
    sim = tmp_path_factory.mktemp("w424") / "jw"
    assert main(["simulate", "--route", "stand:2, straight:14, stand:2", "--user-seed", "10250",
                 "--out", str(sim)]) == 0
    add_jumps(sim, 1.0, 2.0, files=("fAccelerometer", "wAccelerometer"))  # flights at about 2.25-6 s
    return sim


@pytest.mark.parametrize("units", ["foot", "waist"])
def test_a_window_after_the_jumps_has_no_flights_w424(jumps_then_walk, tmp_path, units):
    out, whole = tmp_path / "win", tmp_path / "whole"
    assert main(["track", str(jumps_then_walk), "--units", units, "--window", "9,16", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert (s["n_flight_phases"], s["flight_time_s"]) == (0, 0.0)
    assert pd.read_csv(out / "flights.csv").empty
    assert not [w for w in s["info"]["warnings"] if "flight phase" in w]
    # the window holding the jumps keeps them (the cut is the window's, not a loss of the test)
    assert main(["track", str(jumps_then_walk), "--units", units, "--window", "0,9", "--out", str(whole)]) == 0
    s = json.loads((whole / "summary.json").read_text())
    assert s["n_flight_phases"] == 3
    assert len(pd.read_csv(whole / "flights.csv")) >= 3
