"""Decision L432 (session 35, trial T3 finding 6): a foot track's ``stairs.csv``, one row per stair flight (consecutive
stair strides of one direction, ended by a level stride, a pause, a data gap or a reversal), ``n_stairs`` from the
height with ``--stair-rise``, and the summary's flights and stair strides up / down. L433: the landing-stride cut is
an option. B348: ``--stair-rise`` in centimetres is one error line."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.stair_flights import FLIGHT_COLUMNS, LANDING_GRADE_RATIO, flight_runs, flight_table


def _steps(dz, length=None, start=None, dur=1.0):
    n = len(dz)
    start = np.arange(n) * dur if start is None else np.asarray(start, float)
    return pd.DataFrame({"start_s": start, "end_s": start + dur, "length_m": length if length is not None else
                         np.where(np.abs(dz) > 0, 0.56, 1.2), "dz_m": dz, "gap_s": 0.0, "unit": "foot",
                         "heading_rad": 0.0})


def test_flights_end_at_a_level_stride_a_pause_and_a_reversal_l432():
    dz = [0, 0.17, 0.34, 0.34, 0, 0.34, 0.34, -0.34, -0.34, 0, -0.34, -0.34, -0.34, -0.17, 0]
    start = np.arange(len(dz), dtype=float)
    start[12:] += 5.0  # a 5 s pause inside the last descent (L104's pause: 1 s over the rhythm)
    t = flight_table(_steps(dz, start=start), stair_rise_m=0.17)
    assert list(t.columns) == list(FLIGHT_COLUMNS)
    assert t["direction"].tolist() == ["up", "up", "down", "down", "down"]  # a reversal ends a flight too
    assert t["n_strides"].tolist() == [3, 2, 2, 2, 2]
    assert t["n_stairs"].tolist() == [5, 4, 4, 4, 3]
    assert t["height_m"].round(2).tolist() == [0.85, 0.68, -0.68, -0.68, -0.51]
    first = t.iloc[0]
    assert first["start_s"] == 1.0 and first["end_s"] == 4.0 and first["time_s"] == 3.0
    assert first["cadence_spm"] == pytest.approx(120.0)  # 3 strides = 6 steps in 3 s
    assert first["median_stride_dz_m"] == pytest.approx(0.34)
    assert first["stride_dz_cv_pct"] == pytest.approx(100 * np.std([0.17, 0.34, 0.34], ddof=1) / np.mean([0.17, 0.34,
                                                                                                          0.34]))
    assert first["stairs_per_min"] == pytest.approx(100.0)
    assert flight_table(_steps(dz, start=start))["n_stairs"].isna().all()  # without a rise: strides count no stairs


def test_lower_back_and_missing_heights_give_the_header_alone_l432():
    st = _steps([0.17, 0.17, 0.17]).assign(unit="waist")
    assert flight_table(st).empty and list(flight_table(st).columns) == list(FLIGHT_COLUMNS)
    assert flight_table(_steps([0.3, 0.3]).drop(columns="dz_m")).empty


def test_landing_cut_is_an_option_l433():
    # a landing walked without a level stride: +0.16 / +0.15 m over 1.04 m inside +0.33 m / 0.56 m strides
    dz = np.array([0.17, 0.32, 0.33, 0.32, 0.35, 0.16, 0.15, 0.33, 0.31, 0.37])
    length = np.array([1.04, 0.57, 0.56, 0.57, 0.55, 1.04, 1.04, 0.56, 0.57, 0.55])
    stair = np.ones(10, bool)
    assert LANDING_GRADE_RATIO is None  # not adopted (L433's measurement)
    assert flight_runs(dz, stair, [(0, 10)], length) == [(0, 10, 1)]
    assert flight_runs(dz, stair, [(0, 10)], length, landing_ratio=0.5) == [(0, 6, 1), (6, 10, 1)]
    # a skipped stair's long stride climbs at the stair's grade: no landing
    assert flight_runs([0.34, 0.34, 0.51, 0.34, 0.34], np.ones(5, bool), [(0, 5)], [0.56, 0.56, 0.86, 0.56, 0.56],
                       landing_ratio=0.5) == [(0, 5, 1)]


ROUTE = "straight:3, up:12, turn:180, up:12, straight:2, turn:180, down:12, turn:180, down:12, straight:3"


def test_simulated_flights_and_stairs_match_the_truth_and_the_cli_writes_them_l432(tmp_path, capsys):
    sim, out = tmp_path / "sim", tmp_path / "trk"
    assert main(["simulate", "--route", ROUTE, "-u", "8472", "-o", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--stair-rise", "0.17", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    t = pd.read_csv(out / "stairs.csv")
    assert t["direction"].tolist() == ["up", "up", "down", "down"]
    assert t["n_stairs"].tolist() == [12, 12, 12, 12]  # the route's four flights of 12 stairs
    s = json.loads((out / "summary.json").read_text())
    assert (s["n_flights_up"], s["n_flights_down"]) == (2, 2)
    assert s["n_stair_strides_up"] + s["n_stair_strides_down"] == s["n_stair_strides"]
    assert s["n_stair_strides_up"] == int(t.loc[t["direction"] == "up", "n_strides"].sum())
    assert "stair flights 2 up / 2 down" in printed and "stairs.csv" in printed


def test_stair_rise_in_centimetres_is_one_line_b348(tmp_path, capsys):
    assert main(["track", str(tmp_path), "--stair-rise", "17", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "--stair-rise 17" in err and "write 0.17" in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_run_takes_stair_rise_and_prints_the_flights(tmp_path_factory, tmp_path, capsys):
    """Decision L432 (review R3 finding 6): `run` writes stairs.csv, so it takes `--stair-rise` (the shared option)
    and prints track's "stair flights" line; user 8632's two flights of 12 stairs."""
    from tests.runtime_helpers import trained_dirs

    bundle = trained_dirs(tmp_path_factory)["root"] / "bundle"
    sim, out = tmp_path / "sim", tmp_path / "run"
    assert main(["simulate", "--route", "straight:3, up:12, turn:180, up:12, straight:3", "-u", "8632",
                 "-o", str(sim)]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(bundle), str(sim), "--stair-rise", "0.17", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    t = pd.read_csv(out / "stairs.csv")
    assert t["direction"].tolist() == ["up", "up"] and t["n_stairs"].notna().all()
    assert "stair flights 2 up / 0 down" in printed
    assert json.loads((out / "run.json").read_text())["options"]["stair_rise"] == 0.17
