"""Session 40, fixer FB (trial T4 findings F4-F7): the clock check names the offset a step period from its estimate
(E228), goes on estimating after its line and takes a known drift live (E229), dropped samples are counted and said
live with one tolerance for float rounding at 0.25 s (E230), and a second thread inside push is refused (E231).
Simulated users 10740-10742 (the session's range)."""

from __future__ import annotations

import logging
import threading
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import ConcurrentUseError, DataError
from pdrlearn.kernels.align import twin_line, unit_offset_message
from pdrlearn.kernels.gaps import streamed_drops_line
from pdrlearn.kernels.window import gap_clock
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.sim import simulate

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # foot + waist units


def _sim(user: int, length_m: float):
    logging.disable(logging.WARNING)
    try:
        return simulate("walk", user, length_m=length_m)
    finally:
        logging.disable(logging.NOTSET)


@pytest.fixture(scope="module")
def long_walk():
    return _sim(10740, 250)


@pytest.fixture(scope="module")
def walk():
    return _sim(10741, 60)


def _streams(session, clock=None, keep=None):
    """``{sensor: (t, values)}`` with the waist times through ``clock`` and each stream's samples ``keep(name, t)``."""
    out = {}
    for n, st in session.streams.items():
        if not len(st):
            continue
        t = clock(st.t) if clock is not None and st.placement == "waist" else st.t
        m = np.ones(len(t), bool) if keep is None else keep(n, st.t)
        out[n] = (t[m], st.values[m])
    return out


def _losing_foot_packets(walk, n: int):
    """A ``keep`` for :func:`_streams`: every foot stream loses ``n`` 4-sample packets (0.15 s of samples, 0.25 s
    between the samples either side at 20 Hz), one every 10 s from 10 s on; the waist keeps all."""
    t0 = float(walk["fAccelerometer"].t[0])
    lost = [(t0 + 10.0 * k, t0 + 10.0 * k + 0.15) for k in range(1, n + 1)]

    def keep(name, t):
        if not name.startswith("f"):
            return np.ones(len(t), bool)
        return ~np.any([(t >= a - 1e-9) & (t <= b + 1e-9) for a, b in lost], axis=0)

    return keep


def _replay(streams, chunk_s=1.0, watch=None, **kw):
    tr = Tracker(load_bundle(BUNDLE), **kw)
    for push in replay_chunks(streams, chunk_s):
        tr.push(push)
        if watch is not None:
            watch(tr)
    tr.flush()
    return tr, [w for w in tr.warnings if "decision L161" in w]


def test_a_warned_offset_names_its_twin_a_step_period_away_e228(walk):
    """The waist clock 0.3 s ahead: the line names the estimate and the offset a step period from it, with the
    Tracker keyword for each (one of them the truth, less the ~0.04 s event bias of L161); T4's line had named only
    the estimate, -0.25 s, with the wrong sign."""
    tr, (line,) = _replay(_streams(walk, clock=lambda t: t + 0.3))
    named = [float(x.split(")")[0]) for x in line.split("waist_clock_offset_s=")[1:]]
    assert len(named) == 2 and "decision E228" in line
    assert "s from the foot unit's, or " in line
    assert 0.4 < abs(named[1] - named[0]) < 0.7  # a step period apart, on either side of 0
    assert min(abs(x - 0.3) for x in named) < 0.06
    est = tr.clock_offset
    period = est["step_period_s"]
    a = est["offset_s"]
    b = a - period if a > 0 else a + period
    # offline (track / run): the same two, as --clock-offset, and --align-units' line when it applied one
    off = unit_offset_message(a, 0.0, "pdrlearn run", estimate={**est, "drift": 0.0, "ref_s": 0.0})
    assert f"`pdrlearn run --clock-offset {a:.3f}`" in off and f"`pdrlearn run --clock-offset {b:.3f}`" in off
    applied = twin_line({**est, "drift": 0.0, "ref_s": 0.0})
    assert f"--clock-offset {b:.3f} instead of --align-units" in applied and "decision E228" in applied
    assert twin_line({**est, "offset_s": 0.1}) is None  # under L161's 0.2 s: the closest to 0 stands


def test_the_check_goes_on_after_its_line_and_warns_again_as_the_clock_drifts_e229(long_walk):
    """A waist clock 0.1 s ahead drifting 2500 ppm (0.43 s over the walk): the first line, then the estimate keeps
    moving (T4: frozen at its warned value) and a second line comes when it moved more than 0.1 s."""
    seen = []

    def watch(tr):
        if tr._clock.warned and tr.clock_offset["offset_s"] not in seen:
            seen.append(tr.clock_offset["offset_s"])

    _, lines = _replay(_streams(long_walk, clock=lambda t: t + 0.1 + 2500e-6 * t), watch=watch)
    assert len(lines) >= 2 and len(seen) >= 2
    first = float(lines[0].split("fall ")[1].split(" s")[0])
    second = float(lines[1].split("fall ")[1].split(" s")[0])
    assert abs(second - first) > 0.1


def test_a_known_drift_moves_the_waist_clock_live_as_run_does_e229(long_walk):
    """``waist_clock_drift_ppm`` with ``waist_clock_offset_s``: the waist samples on the foot clock again
    (``to_foot_clock``, run's --clock-drift-ppm mechanism): no line and the clean walk's track."""
    clean, _ = _replay(_streams(long_walk), chunk_s=2.0)
    fixed, lines = _replay(_streams(long_walk, clock=lambda t: t + 0.1 + 2500e-6 * t), chunk_s=2.0,
                           waist_clock_offset_s=0.1, waist_clock_drift_ppm=2500)
    assert not lines and abs(fixed.clock_offset["offset_s"]) < 0.1
    assert np.allclose(fixed.position, clean.position, atol=1e-6)
    bundle = load_bundle(BUNDLE)
    for bad in ("200", float("nan"), 2e5, True):
        with pytest.raises(DataError, match="waist_clock_drift_ppm=.*must be the waist clock's drift in ppm"):
            Tracker(bundle, waist_clock_drift_ppm=bad)
    with pytest.raises(DataError, match="waist_clock_drift_ppm=100: the tracker follows foot only"):
        Tracker(bundle, units=("foot",), waist_clock_drift_ppm=100)


def test_dropped_samples_are_counted_and_said_live_as_run_says_them_e230(walk):
    """Lost 4-sample foot packets (0.25 s between the samples either side, at 20 Hz): counted per stream and said at
    flush in run's line (T4: silent live); ``stream_checks=False`` (run, which says them when it reads) counts them."""
    streams = _streams(walk, keep=_losing_foot_packets(walk, 4))
    tr, _ = _replay(streams)
    stats = tr.drop_stats()
    assert stats["fAccelerometer"]["intervals"] == 4
    assert stats["fAccelerometer"]["longest_s"] == pytest.approx(0.25)
    line = streamed_drops_line([(n, s["intervals"], s["longest_s"]) for n, s in stats.items()])
    assert line in tr.warnings and "4 interval(s) of dropped samples" in line
    assert tr._gap_limit("fAccelerometer") > 32.2 - 31.95  # E30's live gap: not by float rounding either
    quiet, _ = _replay(streams, stream_checks=False)
    assert quiet.drop_stats() == stats and line not in quiet.warnings
    assert not _replay(_streams(walk))[0].drop_stats()
    with pytest.raises(DataError, match="stream_checks='no' must be True or False"):
        Tracker(load_bundle(BUNDLE), stream_checks="no")


def test_a_quarter_second_loss_is_one_thing_whatever_its_float_rounding_e230():
    """``32.2 - 31.95`` is 0.25000000000000355 and ``31.2 - 30.95`` 0.25: both are the same lost packet and neither
    is over E36's 0.25 s (T4: the first was a gap, the other five not)."""
    assert 32.2 - 31.95 > 0.25 and 31.2 - 30.95 == 0.25
    for a, b in ((31.95, 32.2), (30.95, 31.2)):
        t = np.array([a - 0.1, a - 0.05, a, b, b + 0.05, b + 0.1])
        assert np.array_equal(gap_clock(t), t)
    t = np.array([0.0, 0.05, 0.1, 0.36, 0.41])  # a real gap (0.26 s) is still one
    assert not np.array_equal(gap_clock(t), t)


def test_a_second_thread_inside_push_is_refused_in_one_line_e231(walk):
    """Another thread inside push (here: its lock held) makes push and flush raise ConcurrentUseError, which is
    not a DataError a service catches per push; pushes one at a time go on as before."""
    tr = Tracker(load_bundle(BUNDLE))
    pushes = list(replay_chunks(_streams(walk), 1.0))
    tr.push(pushes[0])
    got = []

    def other():
        for call in (lambda: tr.push(pushes[1]), tr.flush):
            try:
                call()
            except Exception as exc:  # noqa: BLE001 - the test looks at what came out
                got.append(exc)

    with tr._busy:  # "another thread is inside push"
        th = threading.Thread(target=other)
        th.start()
        th.join()
    assert len(got) == 2 and all(isinstance(e, ConcurrentUseError) for e in got)
    assert not isinstance(got[0], DataError) and "decision E231" in str(got[0]) and "\n" not in str(got[0])
    for push in pushes[1:]:
        tr.push(push)
    tr.flush()
    assert tr.n_steps > 10


def test_the_foot_vs_barometer_check_is_said_live_as_run_says_it_e232(tmp_path, capsys):
    """A barometer that climbs ~1.7 m mid-walk while the foot stays level: `pdrlearn run` warns L145's line; the live
    Tracker pushed the same samples says the same line at flush (T4: silent live), once; with ``stream_checks=False``
    (run's own Tracker) it does not."""
    import json

    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.io.session import Stream

    walk = _sim(10742, 60)
    b = walk.streams["wBarometer"]
    p = b.values.copy()
    mid = 0.5 * (b.t[0] + b.t[-1])
    p[:, 0] -= 0.2 * np.clip((b.t - mid) / 5.0, 0, 1)
    walk.streams["wBarometer"] = Stream("wBarometer", b.t, p)
    streams = _streams(walk)
    tr, _ = _replay(streams)
    live = [w for w in tr.warnings if "disagrees with the waist barometer" in w]
    assert len(live) == 1 and "foot altitude change +0.00 m" in live[0]
    folder = write_session(walk, tmp_path / "S")
    assert main(["run", str(BUNDLE), str(folder), "--json"]) == 0
    warned = json.loads(capsys.readouterr().out)["info"]["warnings"]
    assert live[0] in [w["message"] if isinstance(w, dict) else w for w in warned]
    quiet, _ = _replay(streams, stream_checks=False)
    assert not [w for w in quiet.warnings if "disagrees with the waist barometer" in w]


def test_one_sample_pushes_count_dropped_samples_as_chunks_do_e230(walk):
    """Review R2 finding 1: a tracker fed one sample per push (a Bluetooth callback's feed, E17's fast path) counted
    no dropped samples (its limit was read before any chunked push had set it); now as 1 s chunks count them."""
    t0 = float(walk["fAccelerometer"].t[0])
    streams = {n: (t[t < t0 + 30.0], v[t < t0 + 30.0])
               for n, (t, v) in _streams(walk, keep=_losing_foot_packets(walk, 2)).items()}
    chunked = _replay(streams)[0].drop_stats()
    single = _replay(streams, chunk_s=0.05)[0].drop_stats()
    assert chunked["fAccelerometer"]["intervals"] == 2
    assert single["fAccelerometer"] == chunked["fAccelerometer"]
