"""Decision L381 (session 33, trial T4 finding 6): periods.csv from the test's start - ``--per-align first-step``
(a 6MWT's minutes from "go") and ``--per`` inside ``--window`` (periods from the window's start); decision B292: no
step to start from is one line."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main

ROUTE = ("stand:5, straight:30, curve:180:0.5, straight:30, curve:180:0.5, straight:30, curve:180:0.5, "
         "straight:30:short, curve:180:0.5, straight:30:short, stand:3")


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("l381")
    assert main(["simulate", "--route", ROUTE, "--user-seed", "7282", "--out", str(d / "s")]) == 0
    return d


def _truth_m(session, a, b):
    """The simulated waist's path length (m) from a to b s (trial T4's truth.py: the trajectory, 23-sample mean)."""
    tr = pd.read_csv(session / "trajectory.csv")
    t = tr["timestamp"].to_numpy(float) / 1000.0
    xy = tr[["x", "y"]].rolling(23, center=True, min_periods=1).mean().to_numpy()
    cum = np.cumsum(np.r_[0.0, np.hypot(*np.diff(xy, axis=0).T)])
    return float(np.interp(b, t, cum) - np.interp(a, t, cum))


def test_minutes_from_the_first_step_match_the_truth(walk):
    out = walk / "first"
    assert main(["track", "--no-plot", str(walk / "s"), "--per", "60", "--per-align", "first-step", "--out",
                 str(out)]) == 0
    p = pd.read_csv(out / "periods.csv")
    summary = json.loads((out / "summary.json").read_text())
    first = pd.read_csv(walk / "s" / "steps.csv")["start_ms"].min() / 1000.0  # the simulated walk's first step
    assert summary["per_align"] == "first-step" and summary["per_start_s"] == pytest.approx(p["start_s"].iloc[0])
    assert p["start_s"].iloc[0] == pytest.approx(first, abs=0.6) and p["start_s"].iloc[0] > 3.0  # not 0 s
    full = p[~p["partial"]]
    assert len(full) >= 2
    for _, row in full.iterrows():  # the foot's minutes within 3 % of the truth (trial T4: +0.5 % from "go")
        assert row["distance_m"] == pytest.approx(_truth_m(walk / "s", row["start_s"], row["end_s"]), rel=0.03)


def test_per_inside_a_window_is_each_periods_own_window(walk):
    out = walk / "win"
    assert main(["track", "--no-plot", str(walk / "s"), "--window", "5,125", "--per", "60", "--out", str(out)]) == 0
    p = pd.read_csv(out / "periods.csv")
    assert p["start_s"].tolist() == pytest.approx([5.0, 65.0]) and p["end_s"].tolist() == pytest.approx([65.0, 125.0])
    one = walk / "w1"
    assert main(["track", "--no-plot", str(walk / "s"), "--window", "5,65", "--out", str(one)]) == 0
    alone = json.loads((one / "summary.json").read_text())
    assert p["distance_m"].iloc[0] == pytest.approx(alone["distance_m"], abs=1e-6)
    assert p["n_steps"].iloc[0] == alone["n_steps"]


def test_first_step_without_a_step_is_one_line(walk, capsys):
    out = walk / "none"
    code = main(["track", "--no-plot", str(walk / "s"), "--window", "0,3", "--per", "60", "--per-align", "first-step",
                 "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "--per-align first-step" in err and "B292" in err and "Traceback" not in err
    assert not out.exists()
    assert main(["track", str(walk / "s"), "--per-align", "first-step", "--out", str(walk / "x")]) == 2
