"""Decision W296 (trial s32 finding 9): `pdrlearn report` and a track-all folder's report show the TUG time, its
phases (W293), the chair transfers and the turns' durations when the tracks have them, and no such table when none
has."""

from __future__ import annotations

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.report.tests_table import CLINICAL_TEST_CAPTION, clinical_test_table


def test_table_only_with_a_tug_or_a_transfer():
    df = pd.DataFrame({"run": ["a", "b"], "tug_time_s": [25.9, None], "tug_walk_out_s": [2.4, None],
                       "tug_turn_to_sit_s": [None, None], "n_sit_to_stand": [1, None],
                       "median_turn_duration_s": [2.85, 2.1], "distance_m": [6.0, 9.0]})
    caption, table = clinical_test_table(df, "run")
    assert caption == CLINICAL_TEST_CAPTION
    # the row with a TUG only; the columns with a value only (no turn-to-sit), in the table's order
    assert list(table.columns) == ["run", "tug_time_s", "tug_walk_out_s", "n_sit_to_stand", "median_turn_duration_s"]
    assert table["run"].tolist() == ["a"]
    # turns alone (a foot track) are no clinical test table: they are the gait table's turn_count
    assert clinical_test_table(df.drop(columns=["tug_time_s", "tug_walk_out_s", "n_sit_to_stand"]), "run") is None


def test_report_and_track_all_show_the_tug(tmp_path, capsys):
    study = tmp_path / "study"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3, turn:180", "--sit-start", "5",
                 "--sit-end", "5", "--user-seed", "6645", "--out", str(study / "tug")]) == 0
    assert main(["simulate", "--route", "straight:10", "--user-seed", "6646", "--out", str(study / "walk")]) == 0
    res = tmp_path / "res"
    assert main(["track", str(study / "tug"), "--units", "waist", "--out", str(res / "tug")]) == 0
    # a foot-only track: no transfers (W418: the default two-unit track reads the waist's, 0 here)
    assert main(["track", str(study / "walk"), "--units", "foot", "--out", str(res / "walk")]) == 0
    assert main(["track-all", str(study), "--pipeline", "waist-pendulum", "--out", str(res / "batch")]) == 0
    capsys.readouterr()
    assert main(["report", str(res), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    summary_table = md.split(f"**{CLINICAL_TEST_CAPTION}**", 1)[1].split("**", 1)[0]
    assert "tug_time_s" in summary_table and "tug_walk_out_s" in summary_table and "n_sit_to_stand" in summary_table
    assert "| tug " in summary_table and "| walk " not in summary_table  # the TUG's run only
    batch = md.split(f"**per session: {CLINICAL_TEST_CAPTION}**", 1)[1].split("**", 1)[0]
    sessions = pd.read_csv(res / "batch" / "sessions.csv")
    tug = sessions[sessions["path"] == "tug"].iloc[0]
    assert f"{tug['tug_time_s']:.4g}" in batch and "tug_turn_s" in batch and "| walk " in batch
    # the walk's lower-back track ends standing: its row is there (it has transfer counts, 0) without a TUG time
    assert pd.isna(sessions[sessions["path"] == "walk"].iloc[0]["tug_time_s"])
    # a report of the foot track alone has no such table
    assert main(["report", str(res / "walk"), "--out", str(tmp_path / "rep2")]) == 0
    assert CLINICAL_TEST_CAPTION not in (tmp_path / "rep2" / "report.md").read_text()


def test_plot_draws_a_tracks_transfers(tmp_path, capsys):
    from pdrlearn.io import read_session
    from pdrlearn.plots import session_figure

    d = tmp_path / "tug"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3", "--sit-start", "5", "--sit-end", "5",
                 "--user-seed", "6647", "--out", str(d)]) == 0
    assert main(["track", str(d), "--units", "waist", "--out", str(tmp_path / "t")]) == 0
    transfers = pd.read_csv(tmp_path / "t" / "transfers.csv")
    assert len(transfers) == 2
    s = read_session(d)
    _, fig = session_figure(s, transfers=transfers)
    hatched = [p for p in fig.axes[0].patches if p.get_hatch() == "//"]
    assert len(hatched) == 2 and fig._suptitle.get_text().endswith(", 2 transfer(s)")
    # a window holding the sit only: one span, clipped to the window
    _, fig = session_figure(s, start=float(transfers["start_s"].iloc[1]) - 1.0, transfers=transfers)
    assert len([p for p in fig.axes[0].patches if p.get_hatch() == "//"]) == 1
    capsys.readouterr()
    assert main(["plot", str(d), "--steps", str(tmp_path / "t"), "--out", str(tmp_path / "p.png")]) == 0
    assert (tmp_path / "p.png").stat().st_size > 0
    # a transfers.csv without its columns: one line naming it, no figure
    transfers.drop(columns=["kind"]).to_csv(tmp_path / "t" / "transfers.csv", index=False)
    assert main(["plot", str(d), "--steps", str(tmp_path / "t"), "--out", str(tmp_path / "q.png")]) == 2
    err = capsys.readouterr().err
    assert "transfers.csv: no kind column" in err and not (tmp_path / "q.png").exists()
