"""Session 41, fixer FK (review R1 finding 1): a fix CSV whose numeric ``t`` is on a session's own epoch clock
(PLASYS sessions may carry epoch-ms timestamps) is kept as session seconds, not placed as UTC (D47 amends D46)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.aid import aid_track, read_fixes
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.aid.track import SESSION_CLOCK_MARGIN_S, on_session_epoch_clock
from pdrlearn.io.session import Session, Stream
from pdrlearn.track.base import TrackResult
from tests.test_gnss_s40 import ORIGIN, _legs, _pdr, _write_csv

E = 1773568800.0  # R1's shift: 2026-03-15 10:00 UTC in epoch seconds


def _session(t0: float, t1: float) -> Session:
    t = np.arange(t0, t1, 0.05)
    acc = Stream("fAccelerometer", t, np.tile([0.0, 0.0, 9.81], (len(t), 1)))
    return Session(name="w", streams={"fAccelerometer": acc})


def _shifted(result: TrackResult, by: float) -> TrackResult:
    st = result.steps.copy()
    st[["start_s", "end_s", "event_s"]] += by
    return TrackResult(st, result.trajectory.assign(t=result.trajectory["t"] + by), dict(result.info))


def _tracks(tmp_path):
    """R1's reproducer in memory: a 300 m walk, 5 m fixes from 60 s (a receiver's cold start), the same walk and
    fixes on the session clock from 0 s and on an epoch clock (every time + E)."""
    steps, truth = _legs((300.0,))
    fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=3, outages=[(0.0, 60.0)])
    assert fx["t"].iloc[0] >= 60.0
    plain = _write_csv(fx, tmp_path / "s.csv")
    epoch = _write_csv(fx.assign(t=fx["t"] + E), tmp_path / "e.csv")
    span = (float(truth["t"].iloc[0]), float(truth["t"].iloc[-1]))
    return _pdr(steps, bias_deg=4.0), plain, epoch, span, truth[["x", "y"]].to_numpy()[-1]


def test_epoch_seconds_on_the_sessions_own_clock_stay_session_seconds_d47(tmp_path):
    pdr, plain, epoch, (t0, t1), end = _tracks(tmp_path)
    a = aid_track(pdr, _session(t0, t1), gnss_path=plain, start=ORIGIN)
    b = aid_track(_shifted(pdr, E), _session(t0 + E, t1 + E), gnss_path=epoch, start=ORIGIN)
    assert not any("cannot be placed" in w for w in b.info.get("warnings", []))
    g = b.info["aid"]["gnss"]
    assert g["time_source"] == "session_epoch_clock" and "first_epoch_s" not in g and "time_alignment" not in g
    assert b.info["aid"]["gnss"]["fixes_used"] == a.info["aid"]["gnss"]["fixes_used"] > 100
    # the same track but for fixes at a step's edge that + E's rounding moves to the next step (0.20 m at most)
    assert b.trajectory[["x", "y"]].to_numpy() == pytest.approx(a.trajectory[["x", "y"]].to_numpy(), abs=0.3)
    err = [float(np.hypot(*(r.trajectory[["x", "y"]].to_numpy()[-1] - end))) for r in (a, b)]
    assert err[1] == pytest.approx(err[0], abs=0.01) and err[1] < 1.0, err  # R1: 1.90 m; placed as UTC: 121.77 m


def test_epoch_seconds_outside_the_sessions_span_are_still_utc_d47(tmp_path):
    """D46 unchanged: a session on its own small clock (0 s ...) takes epoch-second fixes as UTC (D38 places them)."""
    pdr, plain, epoch, (t0, t1), _ = _tracks(tmp_path)
    log = read_fixes(epoch)
    assert log.stats["time_source"] == "epoch_seconds" and log.stats["time_base"] == "utc"
    assert not on_session_epoch_clock(log.stats, _session(t0, t1))
    assert on_session_epoch_clock(log.stats, _session(t0 + E, t1 + E))
    # the span's edges: the fixes' [first, last] overlapping the session's, widened by the margin
    first, last = log.stats["first_epoch_s"], log.stats["last_epoch_s"]
    assert on_session_epoch_clock(log.stats, _session(last + SESSION_CLOCK_MARGIN_S - 1, last + 100))
    assert not on_session_epoch_clock(log.stats, _session(last + SESSION_CLOCK_MARGIN_S + 1, last + 100))
    assert not on_session_epoch_clock(log.stats, _session(first - 100, first - SESSION_CLOCK_MARGIN_S - 1))
    assert read_fixes(plain).stats.get("time_source") is None  # session seconds under 1e9: not epoch seconds
    iso = tmp_path / "iso.csv"
    iso.write_text("t,lat,lon,accuracy_m\n2026-03-15T10:01:00Z,51.0,-1.8,5\n2026-03-15T10:01:01Z,51.0,-1.8,5\n")
    assert read_fixes(iso).stats.get("time_source") is None  # ISO times are UTC whatever the session's clock
    b = aid_track(pdr, _session(t0, t1), gnss_path=epoch, start=ORIGIN)
    assert any("cannot be placed" in w for w in b.info.get("warnings", []))
