"""Decision L691 (session 46, FH, trial T2 finding F7): segments.csv and periods.csv count a row's left and right turns
and sum their rotation (``n_turns_left``, ``n_turns_right``, ``net_rotation_deg``), so a dance figure's rotation needs
no join of turns.csv by time."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.periods import PERIOD_COLUMNS, turn_totals

#: a left half turn, a right quarter turn and a left quarter turn (about 45 s)
ROUTE = "stand:3, straight:5, turn:180, straight:5, turn:-90, straight:4, turn:90, straight:4, stand:3"


def test_turn_totals_split_by_side_and_sum_signed():
    assert turn_totals([181.5, -92.0, 88.0]) == {"n_turns_left": 2, "n_turns_right": 1, "net_rotation_deg": 177.5}
    assert turn_totals([]) == {"n_turns_left": 0, "n_turns_right": 0, "net_rotation_deg": 0.0}


def test_the_columns_come_last_w448s_way():
    # L725's stance %, then W603's n_steps_with_turns last
    assert PERIOD_COLUMNS[-5:-2] == ("n_turns_left", "n_turns_right", "net_rotation_deg")
    assert PERIOD_COLUMNS[-2:] == ("median_stance_pct", "n_steps_with_turns")
    assert PERIOD_COLUMNS.index("n_sit_to_stand") == len(PERIOD_COLUMNS) - 6


@pytest.fixture(scope="module")
def figure(tmp_path_factory):
    """User 12910 (50 Hz) tracked once with --per 10s and two legs (the first turn; the other two)."""
    root = tmp_path_factory.mktemp("segturns")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(12910), rate_hz=50, seed=12910, scenario="route")
    write_session(s, root / "walk")
    out = root / "out"
    assert main(["track", "--no-plot", str(root / "walk"), "--per", "10s", "--out", str(out)]) == 0
    turns = pd.read_csv(out / "turns.csv")
    assert len(turns) == 3, turns  # the figure's three turns: the legs are cut between them
    cut = float(0.5 * (turns["end_s"].iloc[0] + turns["start_s"].iloc[1]))
    end = float(pd.read_csv(out / "periods.csv")["end_s"].iloc[-1])
    (root / "legs.csv").write_text(f"start_s,end_s,label\n0,{cut:.3f},half turn\n{cut:.3f},{end:.3f},two quarters\n")
    out2 = root / "out2"
    assert main(["track", "--no-plot", str(root / "walk"), "--segments", str(root / "legs.csv"),
                 "--out", str(out2)]) == 0
    return out, out2


def test_segments_and_periods_count_left_and_right_turns_and_net_rotation(figure):
    """Each row's left + right turns are its n_turns; its net rotation is the signed sum of the turns.csv angles
    starting in it; the legs read +180 and -90 + 90 within the track's turn angles (fails without L691's columns)."""
    out, out2 = figure
    turns = pd.read_csv(out / "turns.csv")
    for table in (pd.read_csv(out / "periods.csv"), pd.read_csv(out2 / "segments.csv")):
        assert (table["n_turns_left"] + table["n_turns_right"] == table["n_turns"]).all()
        assert table["n_turns_left"].sum() == 2 and table["n_turns_right"].sum() == 1
        assert table["net_rotation_deg"].sum() == pytest.approx(turns["angle_deg"].sum(), abs=1e-6)
    seg = pd.read_csv(out2 / "segments.csv")
    assert list(seg["n_turns_left"]) == [1, 1] and list(seg["n_turns_right"]) == [0, 1]
    assert seg["net_rotation_deg"].iloc[0] == pytest.approx(turns["angle_deg"].iloc[0], abs=1e-6)
    assert seg["net_rotation_deg"].iloc[0] == pytest.approx(180.0, abs=10.0)
    assert seg["net_rotation_deg"].iloc[1] == pytest.approx(0.0, abs=10.0)


def test_the_columns_are_in_the_dictionary(figure):
    from pdrlearn.columns import undocumented

    out, out2 = figure
    assert undocumented("periods.csv", pd.read_csv(out / "periods.csv").columns) == []
    assert undocumented("segments.csv", pd.read_csv(out2 / "segments.csv").columns) == []
