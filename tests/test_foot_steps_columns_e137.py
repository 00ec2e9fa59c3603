"""Decision E137: `pdrlearn columns` (and docs/columns.md) documents a foot track's steps.csv, every column `track`
writes for a foot recording (with and without --toe-off, with references) included."""

from __future__ import annotations

import dataclasses
import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import expanded, undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    root = tmp_path_factory.mktemp("footcols")
    user = dataclasses.replace(UserProfile.from_seed(4943), step_length_m=0.54, step_time_s=0.54)
    write_session(simulate_path([Stand(2), Straight(10), Stand(2)], user, rate_hz=100, seed=0), root / "walk")
    return root


@pytest.mark.parametrize("extra", [[], ["--toe-off"], ["--streaming"]])
def test_every_foot_steps_column_is_documented(walk, extra):
    out = walk / ("t" + "".join(extra))
    assert main(["track", "--no-plot", str(walk / "walk"), "--out", str(out), *extra]) == 0
    cols = list(pd.read_csv(out / "steps.csv").columns)
    assert "ref_match" in cols and "raw_length_m" in cols
    assert undocumented("steps.csv (foot)", cols) == []
    assert undocumented("steps.csv (foot)", ["p_terrain_up", "ood_score", "no_such"]) == ["no_such"]


def test_columns_steps_gives_both_tables(capsys):
    assert main(["columns", "steps.csv", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert list(got) == ["steps.csv", "steps.csv (foot)"]
    assert {c["column"] for c in got["steps.csv (foot)"]} >= {"raw_length_m", "stride_time_s", "speed_mps", "event_s",
                                                               "gap_s", "impossible", "ref_composed"}
    assert expanded("steps.csv (foot)")["speed_mps"][1] == "m/s"
