"""Decision D53 (session 46, I5): after ``--common-span``, segments.csv's legs are accounted from the first sample the
session holds, as periods.csv's periods are (C185 amended): the seconds the cut took are ``common_span_cut_s``, not
"no steps"; a leg wholly before the cut is one ``error:`` line before any tracking."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main

PARTS = ["time_walking_s", "time_between_steps_s", "time_no_steps_s", "time_no_data_s"]


@pytest.fixture(scope="module")
def late_foot(tmp_path_factory):
    """C185's session: user 12860, the foot files start 2 s late."""
    sess = tmp_path_factory.mktemp("d53") / "s"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:3", "--user-seed", "12860", "--rate", "100",
                 "--out", str(sess)]) == 0
    for f in sess.glob("f[A-Z]*.csv"):
        t = pd.read_csv(f)
        t[t["timestamp"] >= 2000].to_csv(f, index=False)
    return sess


def test_segments_leave_the_cut_seconds_out_as_periods_do_d53(late_foot, tmp_path):
    legs = tmp_path / "legs.csv"
    legs.write_text("start_s,end_s,label\n0,5,a\n5,10,b\n10,20,c\n")
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(late_foot), "--common-span", "--segments", str(legs), "--per", "5s",
                 "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    seg, per = pd.read_csv(out / "segments.csv"), pd.read_csv(out / "periods.csv")
    assert summary["common_span_cut_s"] == pytest.approx(2.0, abs=0.02)
    first = seg.iloc[0]
    assert first["start_s"] == pytest.approx(2.0, abs=0.02) and first["duration_s"] == pytest.approx(3.0, abs=0.02)
    assert first["time_no_steps_s"] == pytest.approx(3.0, abs=0.02)  # before D53: 5.000, the cut's 2 s counted
    for col in ("start_s", "end_s", "duration_s", *PARTS):  # legs 1, 2 are periods 1, 2; leg 3 periods 3 and 4
        assert seg[col].iloc[:2].tolist() == pytest.approx(per[col].iloc[:2].tolist(), abs=1e-9), col
    assert seg[PARTS].iloc[2].tolist() == pytest.approx(per[PARTS].iloc[2:4].sum().tolist(), abs=1e-9)
    assert seg[PARTS].sum().sum() == pytest.approx(seg["duration_s"].sum(), abs=0.05)


def test_a_leg_wholly_before_the_cut_is_one_error_line_d53(late_foot, tmp_path, capsys):
    legs = tmp_path / "legs.csv"
    legs.write_text("start_s,end_s\n0,1.5\n1.5,20\n")
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(late_foot), "--common-span", "--segments", str(legs), "--out",
                 str(out)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    line = [ln for ln in err if ln.startswith("error:")]
    assert len(line) == 1 and "line 2, leg 0,1.5 s ends before 2.00 s" in line[0] and "(decision D53)" in line[0]
    assert not out.exists()  # refused before any tracking: nothing written
