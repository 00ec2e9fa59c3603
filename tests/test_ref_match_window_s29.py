"""E135's ref_match under --window is the labelled stride's row in the session's steps.csv (decision E138)."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

RIGHT = Path(__file__).resolve().parents[1] / "datasets/real/gaitmap_level_right"


@pytest.mark.skipif(not RIGHT.is_dir(), reason="real gaitmap recording absent")
def test_windowed_ref_match_is_the_sessions_row(tmp_path):
    from pdrlearn.cli import main
    from pdrlearn.io import read_session

    labels = read_session(RIGHT).steps
    tables = {}
    for name, args in (("all", []), ("win", ["--window", "12,30"])):  # review S29 item 3's window
        assert main(["track", "--no-plot", str(RIGHT), "--out", str(tmp_path / name), *args]) == 0
        tables[name] = pd.read_csv(tmp_path / name / "steps.csv")
    win = tables["win"].dropna(subset=["ref_match"])
    assert len(win) >= 5 and win["ref_match"].min() > 0  # the window starts after the first labelled stride
    rows = win["ref_match"].astype(int).to_numpy()
    assert win["ref_length_m"].to_numpy() == pytest.approx(labels["length_m"].to_numpy(float)[rows])
    whole = tables["all"].set_index("start_s")["ref_match"]
    assert (whole.loc[win["start_s"]].to_numpy() == rows).all()  # the same pair numbers as the whole track's
