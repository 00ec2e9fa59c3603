"""Decisions L275-L278: a track's time split into walking / between steps / no steps / no data, summing to the
window's length and adding up over windows; `track --per` writes periods.csv, whose totals are the summary's."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.periods import TIME_KEYS, Timeline, parse_per

ROUTE = "stand:4, straight:20, turn:180, straight:10, sit:40, straight:12, up:17, straight:10, stand:6, straight:8"


@pytest.fixture(scope="module")
def shift(tmp_path_factory):
    root = tmp_path_factory.mktemp("periods")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(5230), rate_hz=20, seed=5230)
    write_session(s, root / "walk")
    return root


_TRACKED: dict = {}


def _track(root, name, *args, session="walk"):
    """``track --json`` of ``root / session`` into ``root / name``; the same session and options tracked again by
    another test reuse the first folder (a track is deterministic; the tests only read its files)."""
    key = (str(root), session, args)
    if key not in _TRACKED:
        out = root / name
        assert main(["track", "--no-plot", str(root / session), "--out", str(out), "--json", *args]) == 0
        _TRACKED[key] = out
    out = _TRACKED[key]
    return json.loads((out / "summary.json").read_text()), out


def test_timeline_budget_kernel():
    """L275 on a hand-made table: two strides, a 10 s stand, two strides, a 5 s data gap row, one stride."""
    steps = pd.DataFrame({"start_s": [2.0, 3.0, 14.0, 15.0, 16.0, 22.0], "end_s": [3.0, 4.0, 15.0, 16.0, 22.0, 23.0],
                          "length_m": [1.0, 1.0, 1.0, 1.0, 0.0, 1.0], "gap_s": [0, 0, 0, 0, 5.0, 0],
                          "heading_rad": [0.0] * 6})
    tl = Timeline.of(steps, [(16.5, 21.5)])
    whole = tl.budget(0.0, 25.0)
    # walking 2-4, 14-16, 22-23; no data 16.5-21.5; between 4-14, 16-16.5, 21.5-22; no steps 0-2, 23-25
    assert whole == pytest.approx({"time_walking_s": 5.0, "time_between_steps_s": 11.0, "time_no_steps_s": 4.0,
                                   "time_no_data_s": 5.0})
    assert sum(whole.values()) == pytest.approx(25.0)
    # a window inside the stand: no step, all of it no-step time
    assert tl.budget(6.0, 12.0) == pytest.approx({"time_walking_s": 0.0, "time_between_steps_s": 0.0,
                                                  "time_no_steps_s": 6.0, "time_no_data_s": 0.0})
    # walking and no data add up over consecutive windows; between + no steps only together
    parts = [tl.budget(a, b) for a, b in ((0.0, 10.0), (10.0, 18.0), (18.0, 25.0))]
    for k in ("time_walking_s", "time_no_data_s"):
        assert sum(p[k] for p in parts) == pytest.approx(whole[k])
    assert sum(p["time_between_steps_s"] + p["time_no_steps_s"] for p in parts) == pytest.approx(
        whole["time_between_steps_s"] + whole["time_no_steps_s"])


def test_parse_per():
    assert parse_per("1h") == 3600.0 and parse_per("30min") == 1800.0 and parse_per("900") == 900.0
    assert parse_per("90s") == 90.0 and parse_per(None) is None
    for bad in ("0", "-1h", "1 hour", "h", "nan"):
        with pytest.raises(DataError, match="--per"):
            parse_per(bad)


def test_periods_total_the_summary(shift):
    """L277 / L278: periods.csv's totals are the summary's (distance, steps, walking time, floors, bouts, turns);
    each row's four times sum to its length; the last, shorter period is marked partial."""
    summ, out = _track(shift, "per", "--per", "40s")
    per = pd.read_csv(out / "periods.csv")
    assert len(per) > 2 and per["partial"].tolist() == [False] * (len(per) - 1) + [True]
    assert per["start_s"].iloc[0] == 0.0 and per["end_s"].iloc[-1] == pytest.approx(summ["time_span_s"])
    np.testing.assert_allclose(per[list(TIME_KEYS)].sum(axis=1), per["duration_s"], atol=1e-6)
    assert per["distance_m"].sum() == pytest.approx(summ["distance_m"])
    assert per["n_steps"].sum() == summ["n_steps"]
    assert per["time_walking_s"].sum() == pytest.approx(summ["walking_time_s"])
    assert summ["time_walking_s"] == pytest.approx(summ["walking_time_s"])
    assert per["floors_up"].sum() == summ["floors_up"] >= 1 and per["floors_down"].sum() == summ["floors_down"]
    assert per["n_bouts"].sum() == summ["n_bouts"] and per["n_turns"].sum() == summ["turn_count"] >= 1
    assert (per["time_between_steps_s"] + per["time_no_steps_s"]).sum() == pytest.approx(
        summ["time_between_steps_s"] + summ["time_no_steps_s"])
    assert not per["data_gap"].any() and per["position_sigma_end_m"].iloc[-1] == pytest.approx(
        summ["final_position_sigma_m"])
    assert sum(summ[k] for k in TIME_KEYS) == pytest.approx(summ["time_span_s"])


def test_period_row_is_its_window(shift):
    """L275 / L277: a period's time columns are what `track --window` of its span reports; windows add up."""
    _, out = _track(shift, "per2", "--per", "40s")
    per = pd.read_csv(out / "periods.csv")
    whole, _ = _track(shift, "whole")
    got = []
    for _, r in per.iloc[:2].iterrows():
        win, _ = _track(shift, f"w{int(r.period)}", "--window", f"{r.start_s:g},{r.end_s:g}")
        for k in TIME_KEYS:
            assert win[k] == pytest.approx(r[k], abs=1e-6), k
        assert sum(win[k] for k in TIME_KEYS) == pytest.approx(win["time_span_s"]) == pytest.approx(r.duration_s)
        got.append(win)
    rest, _ = _track(shift, "wrest", "--window", f"{per['start_s'].iloc[2]:g},{per['end_s'].iloc[-1]:g}")
    assert sum(w["time_walking_s"] for w in [*got, rest]) == pytest.approx(whole["walking_time_s"])


def test_window_of_only_sitting_walks_zero_with_a_note(shift, capsys):
    """L276: a window without a step walked 0 s: walking_time_s 0 (not null), one "note:" line, no warning."""
    whole, out = _track(shift, "whole2")
    steps = pd.read_csv(out / "steps.csv")
    gaps = steps["start_s"].to_numpy()[1:] - steps["end_s"].to_numpy()[:-1]
    k = int(np.argmax(gaps))  # the sit: the longest time between two strides
    a, b = steps["end_s"].iloc[k] + 5.0, steps["start_s"].iloc[k + 1] - 5.0
    capsys.readouterr()
    win, _ = _track(shift, "sit", "--window", f"{a:g},{b:g}")
    err = capsys.readouterr().err.splitlines()
    assert win["n_steps"] == 0 and win["walking_time_s"] == 0.0 and win["distance_m"] == 0.0
    assert win["time_no_steps_s"] == pytest.approx(b - a, abs=0.01) and win["time_walking_s"] == 0.0
    notes = [ln for ln in err if "holds no step" in ln]
    assert len(notes) == 1 and notes[0].startswith("note: ") and "walking 0 s, 0 m" in notes[0]
    assert not any("holds no step" in w for w in win["info"].get("warnings", []))


def test_data_gap_is_no_data_time(shift, tmp_path):
    """L275: a 20 s foot-data gap is time_no_data_s (the warned gap), flagged in its period; the totals hold."""
    gap = tmp_path / "gap"
    gap.mkdir()
    for f in (shift / "walk").iterdir():
        if f.is_file():
            t = f.read_text()
            if f.name.startswith("f") and f.suffix == ".csv":
                df = pd.read_csv(f)
                t = df[(df.iloc[:, 0] < 30000) | (df.iloc[:, 0] > 50000)].to_csv(index=False)
            (gap / f.name).write_text(t)
    summ, out = _track(tmp_path, "tgap", "--per", "40s", session="gap")
    per = pd.read_csv(out / "periods.csv")
    assert summ["time_no_data_s"] == pytest.approx(20.0, abs=0.2)
    assert per["data_gap"].tolist()[:2] == [True, True] and per["time_no_data_s"].sum() == pytest.approx(
        summ["time_no_data_s"])
    assert per["distance_m"].sum() == pytest.approx(summ["distance_m"])
    assert per["time_walking_s"].sum() == pytest.approx(summ["walking_time_s"])
    np.testing.assert_allclose(per[list(TIME_KEYS)].sum(axis=1), per["duration_s"], atol=1e-6)


def test_per_with_window_cuts_the_window(shift):
    """L277 refused --per with --window; L381 (session 33) cuts the window into periods from its start."""
    assert main(["track", "--no-plot", str(shift / "walk"), "--out", str(shift / "x"), "--per", "1h", "--window",
                 "0,10"]) == 0
    per = pd.read_csv(shift / "x" / "periods.csv")
    assert len(per) == 1 and per["start_s"].iloc[0] == 0.0 and per["end_s"].iloc[0] == pytest.approx(10.0)
    assert bool(per["partial"].iloc[0])


def test_track_all_stacks_the_periods(shift, tmp_path):
    """L277: track-all --per writes each session's periods.csv and OUT/periods.csv, stacked as bouts.csv (L165)."""
    root = tmp_path / "study"
    root.mkdir()
    for name in ("a", "b"):
        shutil.copytree(shift / "walk", root / name)
    out = tmp_path / "ta"
    assert main(["track-all", "--no-plot", str(root), "--out", str(out), "--per", "40s", "--jobs", "1"]) == 0
    allp = pd.read_csv(out / "periods.csv")
    one = pd.read_csv(out / "a" / "periods.csv")
    assert list(allp.columns[:2]) == ["path", "visit"] and len(allp) == 2 * len(one)
    assert allp["path"].tolist() == ["a"] * len(one) + ["b"] * len(one)
    np.testing.assert_allclose(allp["distance_m"].to_numpy()[:len(one)], one["distance_m"].to_numpy())


@pytest.mark.parametrize("text", ["5m", "0.5 m"])
def test_per_in_m_is_refused_as_metres_b305(shift, tmp_path, capsys, text):
    """B305 (trial T3 finding 10): `--per 5m` read 5 minutes while every distance prints in metres: one line naming
    "min", exit 2, no output folder."""
    with pytest.raises(DataError, match="min for minutes"):
        parse_per(text)
    out = tmp_path / "out"
    capsys.readouterr()
    assert main(["track", str(shift / "walk"), "--per", text, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--per" in err[0] and "min" in err[0] and "Traceback" not in err[0]
    assert not out.exists()
    assert parse_per("5min") == 300.0


@pytest.mark.parametrize("text", ["10M", "m", " M "])
def test_per_in_metres_of_any_spelling_and_too_short_periods_are_one_line_b329(shift, tmp_path, capsys, text):
    """Review R2 #13: `--per 10M` and a bare `--per m` got the generic line, not B305's metres line; `--per 0.0001`
    wrote 367,801 period rows."""
    with pytest.raises(DataError, match="'m' reads as metres"):
        parse_per(text)
    for short in ("0.0001", "0.05s", "0.001min"):
        with pytest.raises(DataError, match=r"shorter than a step; give --per 0.1s or more \(decision B329\)"):
            parse_per(short)
    assert parse_per("0.1") == 0.1
    out = tmp_path / "out"
    capsys.readouterr()
    assert main(["track", str(shift / "walk"), "--per", "0.0001", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "decision B329" in err[0] and "Traceback" not in err[0]
    assert not out.exists()
