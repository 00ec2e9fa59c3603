"""Decisions L298, L299, E144, B254, B255 (trial s30 finding 11): wall-clock times. A session whose meta.json gives
its recording start (``recording_start``, a date-time ``pdrlearn import``, a Mobilise-D start) gets ISO 8601 clock
columns on every event table and ``recording_start`` in summary.json; ``--per-align clock`` cuts periods.csv at the
clock's whole periods; ``--window`` takes clock times. Without a start: no clock columns, and the clock options are
refused in one line naming the fix."""

from __future__ import annotations

import json
from datetime import UTC, datetime, timedelta, timezone

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clock import (
    CLOCK_COLUMNS,
    ClockWindow,
    clock_edges,
    parse_clock_window,
    recording_start,
    window_seconds,
    with_clock_columns,
)

ROUTE = "stand:3, straight:8, turn:180, straight:8, sit:40, straight:8, stand:3"
START = "2026-12-05T02:59:30+01:00"  # 30 s before a clock minute and an hour: periods cut there


@pytest.fixture(scope="module")
def night(tmp_path_factory):
    """One simulated session (user 5301) twice: without a start (as simulated) and imported from a CSV of ISO
    date-times at +01:00 (the lower-back unit, as the trial's `pdrlearn import iso.csv --unit waist`)."""
    root = tmp_path_factory.mktemp("clock")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(5301), rate_hz=20, seed=5301)
    write_session(s, root / "plain")
    acc = pd.read_csv(root / "plain" / "wAccelerometer.csv")
    gyr = pd.read_csv(root / "plain" / "wGyroscope.csv")
    df = acc.merge(gyr, on="timestamp", suffixes=("_a", "_g"))
    t0 = pd.Timestamp(START)
    df.insert(0, "time", [(t0 + pd.Timedelta(milliseconds=int(ms))).isoformat(timespec="milliseconds")
                          for ms in df.pop("timestamp")])
    df.columns = ["time", "ax", "ay", "az", "gx", "gy", "gz"]
    df.to_csv(root / "iso.csv", index=False)
    assert main(["import", str(root / "iso.csv"), "--unit", "waist", "--out", str(root / "imp")]) == 0
    return root


def _track(root, name, *args, session="imp"):
    out = root / name
    assert main(["track", "--no-plot", str(root / session), "--out", str(out), *args]) == 0
    return json.loads((out / "summary.json").read_text()), out


def test_import_keeps_the_offset_and_the_start_is_read_from_it(night):
    meta = json.loads((night / "imp" / "meta.json").read_text())
    dt = meta["imported"]["time"]["datetime"]
    assert dt["offset"] == "+01:00" and dt["first"] == "2026-12-05T01:59:30+00:00"  # B43's record stays UTC
    start = recording_start(meta)
    assert start.isoformat() == START  # the instant, at the offset as recorded (not UTC, not the machine's zone)
    assert recording_start(json.loads((night / "plain" / "meta.json").read_text())) is None  # the simulator's: none


def test_start_sources_in_order():
    """L298's order: meta.json recording_start (by hand; no offset -> kept without one), the import, Mobilise-D."""
    imported = {"time": {"origin_s": 1796435970.0, "datetime": {"offset": "-05:00", "first": "x"}}}
    assert recording_start({"imported": imported}).isoformat() == "2026-12-04T20:59:30-05:00"
    assert recording_start({"imported": [imported, {"time": {}}]}).utcoffset() == timedelta(hours=-5)  # --merge
    assert recording_start({"imported": {"time": {"origin_s": 0.0, "unit": "ms"}}}) is None  # a numeric clock
    tod = {"time": {"origin_s": 7980.0, "datetime": {"time_of_day": True}}}
    assert recording_start({"imported": tod}) is None  # B86: a time of day without a date gives no start
    assert recording_start({"start_datetime": "2020-12-10T14:09:03.815+01:00"}).hour == 14  # mobgap converter
    assert recording_start({"recording_start": "2026-12-05T02:13:00", "imported": imported}) == \
        datetime(2026, 12, 5, 2, 13)  # written by hand wins; naive stays naive
    with pytest.raises(DataError, match=r"recording_start '5 Dec 2am' is not an ISO 8601 date-time.*B254"):
        recording_start({"recording_start": "5 Dec 2am"}, "s/meta.json")


def test_event_tables_get_clock_columns_and_the_summary_its_start(night):
    summary, out = _track(night, "t")
    assert summary["recording_start"] == "2026-12-05T02:59:30.000+01:00"
    for name in ("bouts.csv", "turns.csv", "transfers.csv"):
        table = pd.read_csv(out / name)
        assert len(table), name
        for col, clock in CLOCK_COLUMNS.items():
            if col in table:
                got = pd.to_datetime(table[clock], format="ISO8601")
                want = pd.Timestamp(START) + pd.to_timedelta(table[col], unit="s")
                assert (abs(got - want) < pd.Timedelta(milliseconds=1)).all(), (name, clock)
                assert table[clock].str.endswith("+01:00").all()
    assert pd.read_csv(out / "transfers.csv")["peak_time"].notna().all()
    from pdrlearn.columns import undocumented  # the dictionary lists the new columns (docs/columns.md)

    for name in ("bouts.csv", "turns.csv", "transfers.csv"):
        assert undocumented(name, pd.read_csv(out / name).columns) == [], name
    assert undocumented("sessions.csv", ["recording_start", "per_align"]) == []
    assert list(pd.read_csv(out / "bouts.csv").columns)[-1] == "speed_m_s"  # E98's deprecated column stays last
    plain_summary, plain = _track(night, "p", "--units", "waist", session="plain")
    assert "recording_start" not in plain_summary
    for name in ("bouts.csv", "turns.csv", "transfers.csv"):
        assert not set(CLOCK_COLUMNS.values()) & set(pd.read_csv(plain / name).columns), name


def test_per_align_clock_cuts_at_the_clock_and_marks_both_ends_partial(night):
    summary, out = _track(night, "h", "--per", "1min", "--per-align", "clock")
    per = pd.read_csv(out / "periods.csv")
    assert summary["per_align"] == "clock"
    assert per["start_s"].tolist()[:2] == [0.0, 30.0]  # 02:59:30 -> 03:00:00, the clock's minute
    assert per["start_time"].tolist()[:2] == ["2026-12-05T02:59:30.000+01:00", "2026-12-05T03:00:00.000+01:00"]
    assert per["partial"].tolist() == [True, True]  # 30 s, then the recording's last 55 s
    assert per["n_steps"].sum() == summary["n_steps"]  # L278's totals hold
    from pdrlearn.columns import undocumented

    assert undocumented("periods.csv", per.columns) == []
    _, out0 = _track(night, "h0", "--per", "1min")  # the default: from the recording's start, as before
    assert pd.read_csv(out0 / "periods.csv")["start_s"].tolist()[:2] == [0.0, 60.0]


def test_clock_edges_kernel():
    start = datetime(2026, 12, 5, 23, 40, tzinfo=timezone(timedelta(hours=1)))
    # 23:40 -> midnight (1200 s), 01:00, 02:00, recording to 02:30
    assert clock_edges(0.0, 3 * 3600.0 - 600.0, 3600.0, start).tolist() == [0.0, 1200.0, 4800.0, 8400.0]
    assert clock_edges(0.0, 100.0, 3600.0, start.replace(minute=0)).tolist() == [0.0]  # starts on the hour: 1 edge


def test_clock_window(night):
    summary, _ = _track(night, "w", "--window", "02:59:40,03:00:00")
    assert (summary["window_start_s"], summary["window_end_s"]) == (10.0, 30.0)
    iso, _ = _track(night, "wi", "--window", "2026-12-05T01:59:40Z,2026-12-05T02:00:00Z")  # the same, in UTC
    assert (iso["window_start_s"], iso["window_end_s"]) == (10.0, 30.0)


def test_window_seconds_kernel():
    start = datetime(2026, 12, 5, 23, 40, tzinfo=UTC)
    assert window_seconds(ClockWindow("23:50,00:10", "23:50", "00:10"), start, 3600.0, 0.0, "s") == (600.0, 1800.0)
    with pytest.raises(DataError, match=r"starts at 2026-12-06T01:00:00\+00:00, outside the recording.*B255"):
        window_seconds(ClockWindow("01:00,01:10", "01:00", "01:10"), start, 3600.0, 0.0, "s")
    with pytest.raises(DataError, match="not a mix"):
        parse_clock_window("02:10,600")
    assert parse_clock_window("5,15") is None


def test_clock_options_refused_without_a_start(night, capsys):
    for args, option in ((["--per", "1h", "--per-align", "clock"], "--per-align clock"),
                         (["--window", "02:10,02:20"], "--window 02:10,02:20")):
        assert main(["track", str(night / "plain"), "--out", str(night / "x"), *args]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and f"{option} needs the recording's clock time" in err[0], err
        assert "pdrlearn import" in err[0] and '"recording_start"' in err[0] and "B254" in err[0]
        assert not (night / "x").exists()
    assert main(["track", str(night / "plain"), "--out", str(night / "x"), "--per-align", "clock"]) == 2
    assert "give --per" in capsys.readouterr().err


def test_a_start_written_by_hand_gives_the_columns(night, tmp_path):
    import shutil

    d = tmp_path / "hand"
    shutil.copytree(night / "plain", d)
    meta = json.loads((d / "meta.json").read_text())
    (d / "meta.json").write_text(json.dumps({**meta, "recording_start": "2026-12-05T02:13:00Z"}))
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(d), "--out", str(out), "--units", "waist"]) == 0
    bouts = pd.read_csv(out / "bouts.csv")
    want = [(datetime(2026, 12, 5, 2, 13, tzinfo=UTC) + timedelta(seconds=t)).isoformat(timespec="milliseconds")
            for t in bouts["start_s"]]
    assert bouts["start_time"].tolist() == want and want[0].endswith("+00:00")


def test_with_clock_columns_keeps_a_table_without_start():
    t = pd.DataFrame({"start_s": [1.0, np.nan], "end_s": [2.0, 3.0]})
    assert with_clock_columns(t, None) is t
    got = with_clock_columns(t, datetime(2026, 1, 1, tzinfo=UTC))
    assert got["start_time"].tolist() == ["2026-01-01T00:00:01.000+00:00", None]


def test_run_replay_has_the_clock_columns_e144(night, tmp_path):
    """E144: `pdrlearn run` of a session folder writes track's clock columns (a capture has no start)."""
    from pdrlearn.cli.export import _write
    from pdrlearn.io import read_session
    from pdrlearn.track.base import get_pipeline
    from pdrlearn.track.bouts import detected_bouts

    session = read_session(night / "imp")
    result = get_pipeline("waist-pendulum")(session)
    bouts = detected_bouts(result.steps, None)
    summary: dict = {}
    _write(tmp_path / "r", result, summary, session, "s", record={}, bouts=bouts)
    assert summary["recording_start"] == "2026-12-05T02:59:30.000+01:00"
    assert pd.read_csv(tmp_path / "r" / "bouts.csv")["start_time"].notna().all()


def test_freezes_csv_gets_them_at_a_negative_offset(tmp_path):
    """freezes.csv (W213) through the same mechanism; the offset written (-05:00) is the one kept."""
    s = simulate_path(parse_route("stand:3, straight:5, freeze:15:5:5, straight:5, stand:3"),
                      UserProfile.from_seed(5303), rate_hz=20, seed=5303)
    write_session(s, tmp_path / "fz")
    meta = json.loads((tmp_path / "fz" / "meta.json").read_text())
    (tmp_path / "fz" / "meta.json").write_text(json.dumps({**meta, "recording_start": "2026-12-05T02:10:00-05:00"}))
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(tmp_path / "fz"), "--units", "waist", "--freeze-index", "--out",
                 str(out)]) == 0
    fz = pd.read_csv(tmp_path / "o" / "freezes.csv")
    assert len(fz) == 1 and fz["start_time"].str.endswith("-05:00").all()
    assert fz["start_time"].iloc[0] == (datetime(2026, 12, 5, 2, 10, tzinfo=timezone(timedelta(hours=-5)))
                                        + timedelta(seconds=float(fz["start_s"].iloc[0]))).isoformat(
        timespec="milliseconds")


def test_a_null_recording_start_is_no_start_b258():
    """Review F6: an exporter's ``"recording_start": null`` refused every track of the session (B254's line)."""
    imported = {"time": {"origin_s": 1796435970.0, "datetime": {"offset": "-05:00", "first": "x"}}}
    assert recording_start({"recording_start": None}) is None  # main: DataError
    assert recording_start({"recording_start": None, "imported": imported}).isoformat() == "2026-12-04T20:59:30-05:00"
    # the default where: not "meta.json: meta.json recording_start"
    with pytest.raises(DataError, match=r"^meta\.json recording_start 12 is not an ISO 8601"):
        recording_start({"recording_start": 12})
    with pytest.raises(DataError, match=r"^s: meta\.json recording_start 12 is not"):
        recording_start({"recording_start": 12}, "s")


def test_a_reversed_time_of_day_window_past_the_end_is_refused_b259():
    """Review F5: ``01:00:30,00:59:55`` on a 90 s recording from 00:59:50 was read as 40 s to the next day's
    00:59:55 (86405 s) and clipped to the recording: a typo turned into another window."""
    start = datetime(2026, 12, 5, 0, 59, 50, tzinfo=UTC)
    with pytest.raises(DataError, match=r"^s: --window 01:00:30,00:59:55 ends at 2026-12-06T00:59:55\+00:00, after "
                                        r"midnight and after the recording's end.*END before START\?.*B259"):
        window_seconds(ClockWindow("01:00:30,00:59:55", "01:00:30", "00:59:55"), start, 90.0, 0.0, "s")
    # crossing midnight inside the recording, and an END past the end on the same day (B242's clip), still work
    late = datetime(2026, 12, 5, 23, 40, tzinfo=UTC)
    assert window_seconds(ClockWindow("23:50,00:10", "23:50", "00:10"), late, 3600.0, 0.0, "s") == (600.0, 1800.0)
    assert window_seconds(ClockWindow("23:50,23:59", "23:50", "23:59"), late, 900.0, 0.0, "s") == (600.0, 1140.0)
