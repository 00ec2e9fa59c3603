"""Trial T3 (session 39) finding 3, decision W416: a lower-back track finds flight phases on the waist accelerometer
(W363/W409's rule) and says the pipelines count jumps as forward steps; D10's waist line on a session without a foot
unit can name side or backward travel first (opt-in). Users 10037-10038 (fixer FB's fresh-test range)."""

from __future__ import annotations

import json

import pandas as pd

import pdrlearn.track.frame_inference as fi
from pdrlearn.cli import main


def add_jumps(folder, rest_s: float, first_s: float, files=("wAccelerometer",)) -> list[float]:
    """Trial T3's synthetic jumps (trial/make_jump.py) from ``first_s``, 1.5 s apart: 0.25 s push-off at 2x the rest
    specific force, 0.4 s flight at 0 g, 0.1 s landing at 4x, 0.25 s at 1.3x; the jump starts returned."""
    starts = [first_s, first_s + 1.5, first_s + 3.0]
    for name in files:
        path = folder / f"{name}.csv"
        a = pd.read_csv(path)
        t = a["timestamp"].to_numpy(float) / 1000.0
        v = a[["x", "y", "z"]].to_numpy(float)
        rest = v[(t > rest_s) & (t < rest_s + 0.15)].mean(0)
        for j in starts:
            for lo, hi, k in ((0.0, 0.25, 2.0), (0.25, 0.65, 0.0), (0.65, 0.75, 4.0), (0.75, 1.0, 1.3)):
                v[(t >= j + lo) & (t < j + hi)] = rest * k
        a[["x", "y", "z"]] = v
        a.to_csv(path, index=False)
    return starts


def _sim(tmp_path, route: str, user: int, name: str):
    sim = tmp_path / name
    assert main(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    return sim


def test_waist_track_finds_flight_phases_and_says_so_w416(tmp_path):
    sim = _sim(tmp_path, "stand:2, straight:6, stand:2", 10037, "jump")
    add_jumps(sim, 1.0, 2.0)
    out = tmp_path / "jump_tr"
    assert main(["track", "--no-plot", str(sim), "--units", "waist", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_flight_phases"] == 3 and abs(summary["flight_time_s"] - 1.2) < 0.11, summary
    lines = [ln for ln in summary["info"]["warnings"] if "flight phase" in ln]
    assert len(lines) == 1 and "lower-back accelerometer" in lines[0] and "decision W416" in lines[0], lines


def test_side_travel_words_lead_the_waist_line_without_a_foot_unit_when_asked_w416(tmp_path):
    assert fi.side_travel_words(40.0) == ""
    assert "side or backward movement" in fi.side_travel_words(95.0)
    sim = _sim(tmp_path, "stand:2, side:3, side:-3, stand:2", 10038, "sh")
    for f in sim.glob("f*.csv"):
        f.unlink()
    from pdrlearn.io import read_session

    session = read_session(sim)
    msg = fi.check_declared_frame(session, "waist", session.frames["waist"], side_words=True).message
    assert msg.startswith("the waist unit's measured walking direction is ") and "decision W416" in msg, msg
    # the default (W416 (b) not adopted): D10's line as before
    msg = fi.check_declared_frame(session, "waist", session.frames["waist"]).message
    assert msg.startswith("the waist unit's frame") and "W416" not in msg, msg


def test_flights_csv_lists_each_units_jumps_with_a_height_w417(tmp_path):
    """Trial T3 finding 6, decision W417: flights.csv, one row per flight phase of the foot and the lower back."""
    from pdrlearn.track.flight import FLIGHT_COLUMNS, jump_height

    assert abs(float(jump_height(0.4)) - 9.80665 * 0.16 / 8) < 1e-12  # g t^2 / 8
    sim = _sim(tmp_path, "stand:2, straight:6, stand:2", 10039, "jump2")
    starts = add_jumps(sim, 1.0, 2.0, files=("fAccelerometer", "wAccelerometer"))
    out = tmp_path / "jump2_tr"
    assert main(["track", "--no-plot", str(sim), "--out", str(out)]) == 0
    table = pd.read_csv(out / "flights.csv")
    assert tuple(table.columns) == FLIGHT_COLUMNS
    assert sorted(table["unit"]) == ["foot"] * 3 + ["waist"] * 3
    for unit in ("foot", "waist"):
        rows = table[table["unit"] == unit]
        # the 0 g stretch runs 0.25-0.65 s after each jump start: 0.4 s, within one 20 Hz sample
        assert (abs(rows["start_s"].to_numpy() - [s + 0.25 for s in starts]) <= 0.051).all(), rows
        assert (abs(rows["flight_time_s"] - 0.4) <= 0.051).all() and (abs(rows["jump_height_m"] - 0.196) < 0.05).all()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_flight_phases"] == 3 and "flights" not in summary["info"]  # the tracked unit's count
