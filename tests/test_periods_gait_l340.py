"""Decision L340 (load trial s32, finding 9): periods.csv's median stride length, speed and stride-time / stride-length
CVs against the simulated truth; ``pdrlearn columns periods`` names periods.csv. Decision S69 (finding 4): ``track
--per`` of a lower-back pendulum track says when the simulated session's pelvis bounce is the constant default."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.track.periods import PERIOD_GAIT_KEYS, constant_bounce_line

#: long strides, then short ones: a stride length falling by half, as a tiring marcher's
ROUTE = "stand:5, straight:150:long, straight:150:short, stand:5"


@pytest.fixture(scope="module")
def fatigue(tmp_path_factory):
    d = tmp_path_factory.mktemp("periods")
    assert main(["simulate", "--route", ROUTE, "--user-seed", "6371", "--out", str(d / "s")]) == 0
    assert main(["simulate", "--route", ROUTE, "--user-seed", "6372", "--bounce", "pendulum",
                 "--out", str(d / "p")]) == 0
    return d


def _truth(session, a, b):
    tru = pd.read_csv(session / "steps.csv")
    mid = 0.5 * (tru["start_ms"] + tru["end_ms"]) / 1000.0
    x = tru[(mid >= a) & (mid < b)]
    t = (x["end_ms"] - x["start_ms"]) / 1000.0
    steady = x["steady"].astype(bool)
    cv = (lambda v: 100.0 * v.std() / v.mean()) if steady.sum() >= 10 else (lambda v: np.nan)
    return x["length_m"].median(), (x["length_m"] / t).median(), cv(t[steady]), cv(x["length_m"][steady])


def test_periods_give_stride_length_speed_and_cvs_as_the_truth_l340(fatigue, capsys):
    out = fatigue / "foot"
    assert main(["track", "--no-plot", str(fatigue / "s"), "--per", "40s", "--out", str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    s = json.loads((out / "summary.json").read_text())
    assert undocumented("periods.csv", per.columns) == [] and set(PERIOD_GAIT_KEYS) <= set(per.columns)
    walked = per[per["n_steps"] >= 20]
    assert len(walked) >= 6
    for _, row in walked.iterrows():
        length, speed, cv_t, cv_l = _truth(fatigue / "s", row["start_s"], row["end_s"])
        assert row["median_stride_length_m"] == pytest.approx(length, abs=0.03)
        assert row["median_speed_mps"] == pytest.approx(speed, abs=0.03)
        assert row["stride_time_cv_pct"] == pytest.approx(cv_t, abs=1.5)
        assert row["stride_length_cv_pct"] == pytest.approx(cv_l, abs=1.5)
        assert row["n_cv_strides"] >= 10
    # the trend a fatigue study reads: long strides first, short ones last (truth ~1.87 -> ~0.80 m)
    assert walked["median_stride_length_m"].iloc[0] > 1.5 > 1.0 > walked["median_stride_length_m"].iloc[-1]
    assert per["n_cv_strides"].sum() <= s["n_cv_strides"]  # the summary's strides, cut by period
    assert "bounces the same" not in capsys.readouterr().err  # S69: a foot track reads its own strides


def test_lower_back_periods_leave_the_foot_only_columns_empty_and_name_the_constant_bounce_s69(fatigue, capsys):
    out = fatigue / "waist"
    assert main(["track", "--no-plot", str(fatigue / "s"), "--pipeline", "waist-pendulum", "--per", "40s", "--out",
                 str(out)]) == 0
    per = pd.read_csv(out / "periods.csv")
    for k in ("stride_time_cv_pct", "stride_length_cv_pct", "n_cv_strides"):
        assert per[k].isna().all()
    assert (per.loc[per["n_steps"] > 0, "median_speed_mps"] > 0).all()
    # decision W537 (session 47): the lower back's stride length, two consecutive steps summed, in every walked period
    assert (per.loc[per["n_steps"] > 2, "median_stride_length_m"] > 0).all()
    line = "pelvis bounces the same on every step"
    assert line in capsys.readouterr().err
    assert any(line in w for w in json.loads((out / "summary.json").read_text())["info"]["warnings"])
    assert main(["track", "--no-plot", str(fatigue / "p"), "--pipeline", "waist-pendulum", "--per", "40s",
                 "--out", str(fatigue / "waist_p")]) == 0
    assert line not in capsys.readouterr().err  # --bounce pendulum: its steps follow the stride
    assert main(["track", "--no-plot", str(fatigue / "s"), "--pipeline", "waist-pendulum", "--out",
                 str(fatigue / "w1")]) == 0
    assert line not in capsys.readouterr().err  # only with --per


def test_constant_bounce_line_reads_meta_json_only_s69():
    info = {"methods": {"length": "pendulum"}}
    sim = {"source_project": "pdrlearn.sim", "knobs": {"noise": True}}
    assert constant_bounce_line(sim, info) is not None
    assert "said on every simulated constant-bounce session" in constant_bounce_line(sim, info)  # review item 6
    assert constant_bounce_line({**sim, "knobs": {"bounce": "constant"}}, info) is not None
    assert constant_bounce_line({**sim, "knobs": {"bounce": "pendulum"}}, info) is None
    assert constant_bounce_line({"source_project": "mobgap"}, info) is None  # a real recording
    assert constant_bounce_line({"source_project": "pdrlearn.sim"}, info) is None  # no knobs: nothing known
    assert constant_bounce_line(sim, {"methods": {"length": "frequency"}}) is None  # waist-pll reads no bounce


def test_columns_takes_a_tables_stem(capsys):
    assert main(["columns", "periods"]) == 0
    by_stem = capsys.readouterr().out
    assert main(["columns", "periods.csv"]) == 0
    assert capsys.readouterr().out == by_stem and "## periods.csv" in by_stem and "median_stride_length_m" in by_stem
    assert main(["columns", "ramps"]) == 0 and "## ramps.csv" in capsys.readouterr().out
    assert main(["columns", "nonsense"]) != 0
