"""Decisions L618, L619 (session 43, trial T3 finding F11): `track --segments LEGS.csv` writes segments.csv, one row
per trip leg with periods.csv's totals from one track; a bad LEGS.csv is one error line naming the file before any
tracking."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.periods import PERIOD_COLUMNS
from pdrlearn.track.segments import closed_legs, segment_columns

ROUTE = "stand:3, straight:12, stand:6, turn:90, straight:10, stand:3"  # about 43 s


@pytest.fixture(scope="module")
def day(tmp_path_factory):
    """One short simulated session (50 Hz, user 12110) tracked once with --per 10s and two legs equal to its
    second and third periods."""
    root = tmp_path_factory.mktemp("segments")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(12110), rate_hz=50, seed=12110)
    write_session(s, root / "walk")
    (root / "legs.csv").write_text("start_s,end_s,label\n10,20,walk\n20,30,bus\n")
    out = root / "out"
    assert main(["track", "--no-plot", str(root / "walk"), "--per", "10s", "--segments", str(root / "legs.csv"),
                 "--out", str(out)]) == 0
    return root, out


def test_segments_have_the_totals_of_the_equal_periods(day):
    """L619: legs equal to --per's periods give its rows, every total, from the same track."""
    _, out = day
    seg, per = pd.read_csv(out / "segments.csv"), pd.read_csv(out / "periods.csv")
    assert list(seg.columns) == list(segment_columns())
    assert list(seg["segment"]) == [1, 2] and list(seg["label"]) == ["walk", "bus"]
    totals = [c for c in PERIOD_COLUMNS if c not in ("period", "partial")]
    assert set(totals) < set(seg.columns)
    pd.testing.assert_frame_equal(seg[totals], per.iloc[1:3][totals].reset_index(drop=True), check_dtype=False)
    assert seg["n_steps"].sum() > 0 and seg["distance_m"].sum() > 0  # the legs hold walking: not a vacuous match


def test_a_leg_holds_its_end_unless_the_next_leg_starts_there():
    """L619: back-to-back legs [0, 10) [10, 20], as periods; a leg with a gap after it holds its end."""
    assert list(closed_legs([0, 10], [10, 20])) == [False, True]
    assert list(closed_legs([0, 12, 20], [10, 20, 30])) == [True, False, True]
    assert list(closed_legs([5], [9])) == [True]


def test_segments_csv_is_in_the_dictionary(day):
    from pdrlearn.columns import undocumented

    _, out = day
    assert undocumented("segments.csv", pd.read_csv(out / "segments.csv").columns) == []


@pytest.mark.parametrize(("text", "said"), [
    (None, "no such file"),
    ("start,end\n0,5\n", "no column start_s, end_s"),
    ("start_s,end_s\n", "no leg"),
    ("start_s,end_s\n0,nan\n", "not two finite numbers"),
    ("start_s,end_s\n5,5\n", "ends at or before its start"),
    ("start_s,end_s\n0,10\n8,12\n", "legs may not overlap"),
    ("start_s,end_s\n10,12\n0,5\n", "sort the legs by start_s"),
    ("start_s,end_s\n0,10\n30,99\n", "ends after the recording"),
    # decision L726 (trial T1 F6): a `name` column was dropped silently, the label left empty
    ("start_s,end_s,name\n0,10,lap1\n", "column name is not read (--segments reads start_s, end_s, label): a leg's "
                                       "name is the column label - rename name to label"),
    # review R2 F6 (session 48): with a label column there, another column is only to drop
    ("start_s,end_s,label,notes\n0,10,lap1,x\n", "column notes is not read (--segments reads start_s, end_s, label): "
                                                  "drop it (decision L726)"),
])
def test_a_bad_legs_file_is_one_line_before_any_tracking(day, tmp_path, monkeypatch, capsys, text, said):
    """L618: each bad LEGS.csv is refused in one `error:` line naming the file, before the session is tracked
    (the pipeline is never called) and with no output folder."""
    import pdrlearn.track.base as base

    root, _ = day
    legs = tmp_path / "legs.csv"
    if text is not None:
        legs.write_text(text)

    def tracked(*a, **k):
        raise AssertionError("the session was tracked")

    monkeypatch.setattr(base, "get_pipeline", tracked)
    capsys.readouterr()
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(root / "walk"), "--segments", str(legs), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and said in err[0] and str(legs) in err[0], err
    assert not out.exists()


def test_segments_with_a_window_is_refused(day, tmp_path, capsys):
    root, _ = day
    assert main(["track", "--no-plot", str(root / "walk"), "--segments", str(root / "legs.csv"), "--window", "0,10",
                 "--out", str(tmp_path / "o")]) == 2
    assert "drop --window" in capsys.readouterr().err


def test_an_out_folder_holding_the_legs_file_is_not_replaced(day, tmp_path, capsys):
    """L618: LEGS.csv is one of track's inputs: --force never replaces the folder that holds it."""
    root, out = day
    import shutil

    legs = tmp_path / "o" / "legs.csv"
    shutil.copytree(out, legs.parent)  # an earlier track, which --force may replace
    legs.write_text((root / "legs.csv").read_text())
    assert main(["track", "--no-plot", str(root / "walk"), "--segments", str(legs), "--out", str(legs.parent),
                 "--force"]) == 2
    assert "replacing it would delete it" in capsys.readouterr().err and legs.is_file()
