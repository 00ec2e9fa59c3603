"""Decision E332 (session 51, I4): ``pdrlearn run --at-times FILE|T1,T2,...`` writes OUT/at_times.csv, the position the
live track showed at each given time - the streamed trajectory's row of the last stride returned by then (E344; E332
read the last stride ended by then), held, not interpolated - and refuses unsorted, out-of-range times, a file
without a time column, and a run without --out, in one line before any replay. One short simulated walk (fresh user
17910, shipped bundle), replayed in-process."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main as cli_main
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.at_times import live_positions, read_times, times_argument
from tests.lean_helpers import ROOT

BUNDLE = ROOT / "models" / "plasys-sim-default"
TIMES = tuple(sorted({1.0, 8.7, 10.0, 12.0, 19.0, *np.round(np.arange(3.0, 18.0, 0.3), 2)}))  # E344: dense


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("e332")
    s = simulate_path(parse_route("stand:2, straight:8, turn:90, straight:3, stand:2"), UserProfile.from_seed(17910),
                      speed="normal", rate_hz=20.0, seed=5, scenario="route")
    write_session(s, d / "walk")
    (d / "cp.csv").write_text("t_s,name\n" + "".join(f"{t},cp{i}\n" for i, t in enumerate(TIMES)))
    logging.disable(logging.WARNING)
    try:
        code = cli_main(["run", "--no-plot", str(BUNDLE), str(d / "walk"), "--out", str(d / "run"),
                         "--at-times", str(d / "cp.csv")])
    finally:
        logging.disable(logging.NOTSET)
    assert code == 0
    return d


def test_at_times_holds_the_last_returned_row(walk):
    """E332's held row, E344's rule: the row of the last stride the replay's 1 s pushes had returned by t."""
    got = pd.read_csv(walk / "run" / "at_times.csv")
    traj = pd.read_csv(walk / "run" / "trajectory.csv")
    assert list(got["t"]) == pytest.approx(TIMES)
    assert list(got.columns[:3]) == ["t", "stride_end_s", "returned_s"]
    assert {"x", "y", "z", "pos_sigma_m"} <= set(got.columns)
    rt = traj["t"].to_numpy(float)
    assert np.isnan(got["stride_end_s"].iloc[0]) and TIMES[0] < rt[0]  # before the first stride: the start row
    t0 = min(float(st.t[0]) for st in read_session(walk / "walk").streams.values() if len(st))
    shown = got.dropna(subset=["returned_s"])
    assert len(shown) >= 10
    # E288: a stride is returned by the push holding its stance's end: after its end, at a 1 s push's last sample
    lag = shown["returned_s"] - shown["stride_end_s"]
    assert (lag > 0.1).all() and (lag < 2.0).all()
    assert np.allclose((shown["returned_s"] - t0 + 0.05) % 1.0, 0.0, atol=1e-6)  # 20 Hz: the push's last sample
    assert (shown["returned_s"] <= shown["t"] + 1e-9).all()
    for _, row in got.iterrows():
        if np.isnan(row["stride_end_s"]):
            k = 0
            assert row["x"] == traj["x"].iloc[0] and np.isnan(row["returned_s"])
        else:
            k = int(np.flatnonzero(np.isclose(rt, row["stride_end_s"]))[0])
        for c in ("x", "y", "z", "pos_sigma_m"):
            assert row[c] == pytest.approx(traj[c].iloc[k], abs=1e-9)
        later = got[(got["t"] > row["t"]) & got["stride_end_s"].notna()]  # held: never an earlier row later on
        assert (later["stride_end_s"] >= (row["stride_end_s"] if k else -np.inf)).all()
    # review s52r1 F2: E332 read the last stride ended by t; the device had not been given it yet at some times
    ended = np.array([rt[np.searchsorted(rt, t, side="right") - 1] for t in got["t"]])
    assert np.any(np.nan_to_num(got["stride_end_s"].to_numpy(), nan=rt[0]) < ended - 1e-9)
    assert got["pos_sigma_m"].iloc[0] == 0
    interp = np.interp(got["t"], rt, traj["x"])  # L638's offline reading would move between the rows
    assert np.any(np.abs(got["x"].to_numpy() - interp) > 0.05)


def test_the_argument_and_its_refusals(walk, capsys):
    table, label = times_argument("60, 125.5,300")
    assert list(table["t"].astype(float)) == [60.0, 125.5, 300.0] and label == "'60, 125.5,300'"
    assert list(read_times(walk / "cp.csv").columns) == ["t"]  # t_s read as t (track's L638 too)
    traj = pd.read_csv(walk / "run" / "trajectory.csv")
    at = live_positions(traj, [traj["t"].iloc[2]], returned_s=traj["t"].iloc[1:])  # E344: returned at the end
    assert at["stride_end_s"].iloc[0] == pytest.approx(traj["t"].iloc[2])
    (walk / "bad.csv").write_text("when\n3\n")
    base = ["run", "--no-plot", str(BUNDLE), str(walk / "walk"), "--force"]
    cases = {"9,4": ("comes before time 1", "sort the times"), "4,1e4": ("lies outside the recording", "row 3"),
             str(walk / "bad.csv"): ("needs exactly one column t or t_s", "bad.csv"),
             "4,x": ("neither a file nor a comma list", "60,125.5,300")}
    for value, words in cases.items():
        assert cli_main([*base, "--out", str(walk / "refused"), "--at-times", value]) != 0
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and all(w in err for w in words), err
        assert not (walk / "refused").exists()  # refused before any output
    assert cli_main([*base, "--at-times", "4"]) != 0
    assert "add --out FOLDER" in capsys.readouterr().err
