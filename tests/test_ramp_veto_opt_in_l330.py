"""Decision L330 (session 31 review, F1): L314's veto - no ramp of the steps W108 puts in a barometric climb - is
the opt-in PARAMS.json option ``climb_veto``. A 1:12 ramp walked fast rises W108's 0.1 m/s, so under the veto by
default a lower-back track lost its ramps (n_ramps 2 -> 0, reviewer's user 6239); steps.csv keeps ``climb``."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.waist.live import unapplied_options_line

#: the reviewer's fast 1:12 ramp (45 m of 8.33 %), user 6239, 100 Hz
RAMP = "straight:5, slope:45:8.33, straight:5"


@pytest.fixture(scope="module")
def ramp(tmp_path_factory):
    d = tmp_path_factory.mktemp("ramp")
    assert main(["simulate", "--route", RAMP, "--user-seed", "6239", "--rate", "100", "--speed", "fast",
                 "--out", str(d / "sim")]) == 0
    return d


def _track(d, name, extra=()):
    out = d / name
    assert main(["track", "--no-plot", str(d / "sim"), "--pipeline", "waist-pendulum", *extra, "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    return s.get("summary", s), pd.read_csv(out / "steps.csv")


def test_a_fast_ramp_keeps_its_ramps_by_default(ramp):
    s, steps = _track(ramp, "default")
    assert steps["climb"].sum() >= 30  # W108 calls most of the ramp a climb: the column is still written
    assert s["n_ramps"] >= 1  # failed under L314's default veto (0 ramps)


def test_the_veto_is_an_option(ramp):
    (ramp / "veto.json").write_text(json.dumps({"options": {"climb_veto": True}}))
    s, _ = _track(ramp, "veto", ("--params", str(ramp / "veto.json")))
    assert s["n_ramps"] == 0  # L314's behaviour, asked for


def test_live_names_the_veto_only_when_set():
    class P:
        options = {"climb_veto": True}
    assert "climb_veto" in (unapplied_options_line(P()) or "")
    P.options = {}
    assert "climb_veto" not in (unapplied_options_line(P()) or "")
