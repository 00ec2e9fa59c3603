"""Decision B64: scattered dropped samples are bridged when a session is read; the rest is warned."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.io.plasys import write_session
from pdrlearn.io.session import Session, Stream
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.plasys import track_plasys


def _stream(t: np.ndarray) -> Stream:
    v = np.column_stack([np.sin(t), np.cos(3 * t), t])
    return Stream("fAccelerometer", t, v)


def test_bridged_inserts_the_missing_samples_linearly():
    t = np.arange(1000) * 0.01
    drop = np.r_[50, 120, 121, 300:330]  # one, two in a row (0.03 s) and 0.31 s
    s = _stream(np.delete(t, drop))
    b = s.bridged()
    assert len(b) == len(s) + 3  # the 0.31 s interval is not bridged
    assert np.allclose(b.t[:300], t[:300])
    assert np.all(np.isin(s.t, b.t))  # the recorded samples are kept as they are
    kept = np.searchsorted(b.t, s.t)
    assert np.array_equal(b.values[kept], s.values)
    i = int(np.searchsorted(b.t, 0.5 - 1e-9))
    assert b.t[i] == pytest.approx(0.5)
    assert np.allclose(b.values[i], 0.5 * (s.values[49] + s.values[50]))
    assert [round(g.duration_s, 3) for g in b.gaps()] == [0.31]


def test_clean_stream_is_the_same_object():
    s = _stream(np.arange(500) * 0.01)
    assert s.bridged() is s


def _walk(tmp_path, drop_rate: float, name: str):
    sim = simulate("walk", 2, rate_hz=100.0, seed=0, length_m=20.0, drop_rate=drop_rate)
    return write_session(sim, tmp_path / name), float(sim.steps["length_m"].sum())


def _distance(folder) -> float:
    return track_plasys(read_session(folder)).distance_m


def test_scattered_drops_keep_the_clean_distance_when_bridged(tmp_path, caplog):
    clean, truth = _walk(tmp_path, 0.0, "clean")
    dropped, _ = _walk(tmp_path, 0.03, "dropped")
    d_clean = _distance(clean)
    d_bridged = track_plasys(read_session(dropped, bridge_drops=True)).distance_m
    assert abs(d_bridged - d_clean) / truth < 0.015  # the rule's bound per walk: 1.5 pp
    assert track_plasys(read_session(clean, bridge_drops=True)).distance_m == d_clean
    with caplog.at_level(logging.WARNING):
        d_default = _distance(dropped)  # B64 not adopted: the default leaves them, and says so
    assert (d_clean - d_default) / truth > 0.015
    assert len([r for r in caplog.records if "B64" in r.getMessage()]) == 1


def test_clean_session_reads_bit_identical(tmp_path):
    clean, _ = _walk(tmp_path, 0.0, "clean")
    on, off = read_session(clean, bridge_drops=True), read_session(clean)
    for n, s in on.streams.items():
        assert np.array_equal(s.t, off[n].t) and np.array_equal(s.values, off[n].values)


def _with_interval(tmp_path, seconds: float):
    t = np.arange(2000) * 0.01
    cut = (t > 5.0) & (t < 5.0 + seconds - 0.005)
    acc = np.column_stack([0.1 * np.sin(t), 0.1 * np.cos(t), np.full_like(t, 9.81)])
    gyr = np.column_stack([0.1 * np.sin(2 * t), np.zeros_like(t), np.zeros_like(t)])
    s = Session(name="drops", streams={"fAccelerometer": Stream("fAccelerometer", t[~cut], acc[~cut]),
                                       "fGyroscope": Stream("fGyroscope", t[~cut], gyr[~cut])})
    return write_session(s, tmp_path / f"s{seconds:g}")


def _b64(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if "B64" in r.getMessage()]


def test_dropped_samples_are_warned_once(tmp_path, caplog):
    short = _with_interval(tmp_path, 0.02)  # one sample
    with caplog.at_level(logging.WARNING):
        assert read_session(short)["fAccelerometer"].gaps()
    lines = _b64(caplog)
    assert len(lines) == 1 and str(short) in lines[0] and "fAccelerometer, fGyroscope have 1 interval(s)" in lines[0]
    assert "longest 0.020 s" in lines[0] and "not bridged" in lines[0]
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # bridged on request: nothing left to warn
        assert not read_session(short, bridge_drops=True)["fAccelerometer"].gaps()
        assert not read_session(short, bridge_drops=False)["fAccelerometer"].bridged().gaps()
    assert not _b64(caplog)
    longer = _with_interval(tmp_path, 0.3)
    with caplog.at_level(logging.WARNING):
        read_session(longer, bridge_drops=True)  # B64's option (a keyword, decision E251)
    lines = _b64(caplog)
    assert len(lines) == 1 and "longest 0.300 s" in lines[0] and "of 0.1-1 s, not bridged" in lines[0]


def test_waist_only_drops_are_not_warned_with_the_foot_advice(tmp_path, caplog):
    """A waist-only session: the B64 line says that the waist pipelines interpolate the dropped samples (W34),
    not the foot's -2.5 % figure nor `track --streaming` (a foot option that refuses a waist-only session); a
    foot stream keeps the foot line."""
    t = np.arange(2000) * 0.01
    cut = (t > 5.0) & (t < 5.015)
    acc = np.column_stack([0.1 * np.sin(t), np.full_like(t, 9.81), 0.1 * np.cos(t)])
    gyr = np.column_stack([np.zeros_like(t), 0.1 * np.sin(2 * t), np.zeros_like(t)])
    s = Session(name="wdrops", streams={"wAccelerometer": Stream("wAccelerometer", t[~cut], acc[~cut]),
                                        "wGyroscope": Stream("wGyroscope", t[~cut], gyr[~cut])})
    folder = write_session(s, tmp_path / "w")
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    lines = _b64(caplog)
    assert len(lines) == 1 and "wAccelerometer, wGyroscope have 1 interval(s)" in lines[0]
    assert "the waist pipelines interpolate them onto a uniform clock (decision W34" in lines[0]
    assert "or a phone app's sampling" in lines[0]  # decision B149: a waist unit may be a phone, not Bluetooth
    assert "-2.5 %" not in lines[0] and "`track --streaming` integrates" not in lines[0]
    assert "not bridged" not in lines[0] and "of 1 s or less (longest 0.020 s)" in lines[0]
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        read_session(_with_interval(tmp_path, 0.02))
    assert "`track --streaming` integrates on the timestamps" in _b64(caplog)[0]


def test_the_foot_drops_line_is_coded_by_its_own_decision(tmp_path):
    """Decision E170 (session 35, lead): the foot's dropped-samples line names "decisions B64, B183" and quotes
    L83 last (the --params alternative); E168's text reader coded it L83. It is raised with its own code, B64."""
    from pdrlearn.warning_lines import captured_warnings, warning_code

    short = _with_interval(tmp_path, 0.02)
    with captured_warnings() as lines:
        read_session(short)
    drops = [w for w in lines if "B183" in w]
    assert len(drops) == 1 and warning_code(drops[0]) == "B64"
