"""Review R2 (session 45) findings 1-6 on this session's walk-test and walkway merges: L673's passes (a march's legs
are no near misses; a pass is timed or refused by itself, whatever follows it; a turn's slower stride and a 90 deg
turn measured at 80-90 deg end a pass), C185's periods.csv after ``--common-span``, and D51's dropped toe-offs."""

from __future__ import annotations

import json
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.walk_test import pass_rows, ten_metre_walk, ten_metre_walk_trials
from tests.test_walkway_s45_l673 import _pass, _turn

ZONES = (2.0, 8.0, 2.0)


def _legs(metres, turn, speed: float = 0.9, t0: float = 3.0) -> pd.DataFrame:
    """Straight legs of ``metres`` (strides of ``speed`` m, 1 s) with the turn ``turn`` (deg per stride) between them,
    one walking bout."""
    rows, t, h = [], t0, 0.0
    for k, m in enumerate(metres):
        rows += _pass(t, speed, m, h)
        t = rows[-1]["end_s"]
        if k < len(metres) - 1:
            rows += _turn(t, turn, h)
            t, h = rows[-1]["end_s"], rows[-1]["heading_rad"]
    return pd.DataFrame(rows).assign(unit="foot")


def test_a_march_legs_are_no_near_misses_finding_1():
    """A 16 m walk, then a 126.6 m march of 13.5 m legs at 90 deg corners (L552: over 100 m, stays whole): no near
    miss per leg (main: "walking bout 2 pass 1 tracked 13.80 m, short of 14 m; ..." eight times)."""
    first = pd.DataFrame(_pass(3.0, 1.0, 16.0, 0.0)).assign(unit="foot")
    march = _legs((13.5,) * 8 + (16.2,), (45.0, 45.0), t0=float(first["end_s"].iloc[-1]) + 20.0)
    assert march["length_m"].sum() > 100.0
    got = ten_metre_walk(pd.concat([first, march], ignore_index=True))
    assert got["ten_m_walk_time_s"] == pytest.approx(10.0) and got["n_ten_m_walk_trials"] == 1
    assert got["ten_m_walk_note"] is None, got["ten_m_walk_note"]


def test_a_pass_is_timed_or_refused_whatever_follows_it_finding_2():
    """The same 11.1 m first leg (10.8 m and 0.3 m of turn strides; a 12 m walkway) is refused whether a 4.5 m or a
    13.5 m leg follows the corner (main timed it before the 4.5 m leg, its deceleration zone through the corner)."""
    before_short = ten_metre_walk(_legs((10.8, 4.5), (45.0, 45.0)), ZONES)
    before_long = ten_metre_walk(_legs((10.8, 13.5), (45.0, 45.0)), ZONES)
    assert before_short["n_ten_m_walk_trials"] == 0 and before_short["ten_m_walk_time_s"] is None
    assert "the longest 11.10 m" in before_short["ten_m_walk_note"]
    assert before_long["n_ten_m_walk_trials"] == 1
    assert "walking bout 1 pass 1 tracked 11.10 m, short of 12 m" in before_long["ten_m_walk_note"]
    # a leg 1.5 m short, then a short one: judged whole for its note only, never timed whole
    assert ten_metre_walk(_legs((10.5, 4.5), (45.0, 45.0)), ZONES)["ten_m_walk_time_s"] is None


def test_three_passes_each_just_short_get_the_run_out_note_finding_2():
    """T3's three-pass walkway with each pass 0.9 m short: L349's run-out advice (main: L313's "not straight")."""
    got = ten_metre_walk(_legs((10.8, 10.8, 10.8), (120.0, 60.0)), ZONES)
    assert got["ten_m_walk_time_s"] is None
    assert "not straight" not in got["ten_m_walk_note"] and "run-out" in got["ten_m_walk_note"], got["ten_m_walk_note"]


def test_a_slower_stride_inside_a_turn_does_not_split_it_finding_3():
    """A turnaround with a stride under 15 deg inside it (a pivot's shuffle) ends the pass: two passes, two trials
    (main: one pass, its 10 deg strides cutting the 200 deg turn into runs of 60 deg)."""
    turn = (60.0, 10.0, 60.0, 10.0, 60.0)
    steps = _legs((16.0, 16.0), turn, speed=1.0)
    n = len(steps)
    first = 16 + len(turn)  # the turn's rows close the first pass
    assert pass_rows(steps, 0, n) == [(0, first), (first, n)]
    assert len(ten_metre_walk_trials(steps, ZONES)) == 2


@pytest.mark.parametrize("turn", [(15.0,) * 6, (45.0, 44.99), (84.0,), (15.0, 35.0, 30.0)])
def test_a_90_deg_turn_is_measured_from_80_deg_finding_4(turn):
    """Six strides of 15 deg (1.5707963267948963 rad < radians(90)), a corner tracked at 84-89.99 deg, and 15 + 35 + 30
    deg (2.2e-16 rad under radians(80)): a pass ends
    (L104's 80 deg, a 1e-9 rad tolerance; 70 deg stays in its pass: tests/test_walkway_s45_l673.py)."""
    steps = _legs((16.0, 16.0), turn, speed=1.0)
    assert len(pass_rows(steps, 0, len(steps))) == 2
    assert len(ten_metre_walk_trials(steps, ZONES)) == 2


def test_periods_add_up_to_the_cut_span_after_common_span_finding_5(tmp_path):
    """C185's session (foot files start 2 s late), ``track --common-span --per 5s``: periods.csv's time columns add up
    to the summary's ``time_span_s`` (main: 2 s more, the cut seconds counted as "no steps" in period 1)."""
    from pdrlearn.cli import main

    sess = tmp_path / "s"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:3", "--user-seed", "12860", "--rate", "100",
                 "--out", str(sess)]) == 0
    for f in sess.glob("f[A-Z]*.csv"):
        t = pd.read_csv(f)
        t[t["timestamp"] >= 2000].to_csv(f, index=False)
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(sess), "--common-span", "--per", "5s", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    periods = pd.read_csv(out / "periods.csv")
    parts = ("time_walking_s", "time_between_steps_s", "time_no_steps_s", "time_no_data_s")
    assert periods["duration_s"].sum() == pytest.approx(summary["time_span_s"], abs=0.01)
    assert periods[list(parts)].sum().sum() == pytest.approx(summary["time_span_s"], abs=0.05)
    assert periods["time_no_steps_s"].sum() == pytest.approx(summary["time_no_steps_s"], abs=0.05)
    assert periods["start_s"].iloc[0] == pytest.approx(summary["common_span_cut_s"], abs=0.02)
    assert periods["end_s"].iloc[0] == pytest.approx(5.0)  # the edges stay the recording's (B81)


def _walkway_import(tmp_path, caplog, name: str, rows: list[dict]):
    from pdrlearn import sim
    from pdrlearn.io.importer import import_steps

    session = sim.simulate("walk", 4501, length_m=12)
    path = tmp_path / f"{name}.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        st = import_steps(path, session, 0.0, foot="right").steps
    return st, " ".join(r.getMessage() for r in caplog.records)


def _right_footfalls():
    from pdrlearn import sim

    ic = np.sort(sim.simulate("walk", 4501, length_m=12).steps["ic_s"].to_numpy(float))
    return [{"side": "R", "ic_ms": 1e3 * t, "tc_ms": 1e3 * (t + 0.65), "length_m": 1.3} for t in ic]


def test_toe_offs_outside_their_stride_are_said_finding_6(tmp_path, caplog):
    """Every toe-off after the next contact (another convention, or a shifted column): dropped, and said with how
    many (main: only "kept tc_ms ... on 0")."""
    rows = [dict(r, tc_ms=r["ic_ms"] + 2000.0) for r in _right_footfalls()]
    st, said = _walkway_import(tmp_path, caplog, "late_tc", rows)
    assert st["tc_s"].notna().sum() == 0
    n = len(st)
    assert f"tc_ms: {n} of {n} toe-off(s) lie outside the stride" in said and "--labels-offset" in said, said
    st, said = _walkway_import(tmp_path, caplog, "good_tc", _right_footfalls())
    assert st["tc_s"].notna().all() and "lie outside" not in said


def test_a_non_numeric_tc_column_is_named_finding_6(tmp_path, caplog):
    """A tc_ms of "n/a" in every row is named in the not-read line (main: neither kept nor named)."""
    st, said = _walkway_import(tmp_path, caplog, "tc_text", [dict(r, tc_ms="n/a") for r in _right_footfalls()])
    assert "tc_s" not in st and "tc_ms (no number in it) not read" in said, said
