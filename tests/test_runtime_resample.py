"""Decisions E22 (the runtime resamples a stream at another rate than the bundle's, causally) and E23 (a
stream that stops while the others go on is an error naming it, not a silent wait)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime.resample import InputStage, StreamResampler, lowpass_taps
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs(tmp_path_factory)


def _chunks(rng, t, v, max_n=40):
    i = 0
    while i < len(t):
        n = int(rng.integers(0, max_n))  # 0: an empty push
        yield t[i:i + n], v[i:i + n]
        i += n


def _time_chunks(rng, data: dict, max_s=0.7, skew_s=0.3):
    """Pushes of random lengths (0 .. max_s s), each stream cut up to skew_s s off the common boundary."""
    t_end = max(float(t[-1]) for t, _ in data.values())
    done = {n: 0 for n in data}
    a = 0.0
    while any(done[n] < len(data[n][0]) for n in data):
        a += float(rng.uniform(0, max_s))
        push = {}
        for n, (t, v) in data.items():
            b = len(t) if a >= t_end else int(np.searchsorted(t, a + rng.uniform(-skew_s, 0)))
            b = max(b, done[n])
            push[n] = (t[done[n]:b], v[done[n]:b])
            done[n] = b
        yield push


def _cat(parts):
    parts = list(parts)
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


@pytest.mark.parametrize(("rate_in", "rate_out"), [(400.0, 204.8), (102.4, 204.8), (100.0, 20.0), (50.0, 20.0)])
def test_resampler_chunks_of_any_size_give_one_push_output_bit_for_bit(rate_in, rate_out):
    rng = np.random.default_rng(int(rate_in))
    t = 0.013 + np.arange(3000) / rate_in
    t = np.delete(t, np.arange(1500, 1500 + int(2.5 * rate_in)))  # a 2.5 s gap (> GAP_S: not bridged)
    t = t + rng.uniform(-0.1, 0.1, len(t)) / rate_in  # a jittery clock
    v = rng.standard_normal((len(t), 3))
    r = StreamResampler(rate_in, rate_out)
    whole = _cat([r.push(t, v), r.flush()])
    r = StreamResampler(rate_in, rate_out)
    chunked = _cat([*(r.push(a, b) for a, b in _chunks(rng, t, v)), r.flush()])
    assert np.array_equal(whole[0], chunked[0]) and np.array_equal(whole[1], chunked[1])
    tg = whole[0]
    assert np.array_equal(tg, np.round(tg * rate_out) / rate_out)  # on the grid k / rate_out
    gap0, gap1 = t[1499], t[1500]
    assert not ((tg > gap0 + 1.0 / rate_out) & (tg < gap1 - 1.0 / rate_out)).any()  # nothing made up in the gap
    assert tg[0] >= t[0] and tg[-1] <= t[-1]


def test_anti_alias_filter_passes_gait_and_stops_what_would_alias():
    """400 -> 204.8 Hz: a 10 Hz sine passes (gain within 1 %), 130 Hz (would alias to 74.8 Hz) is
    attenuated by more than 50 dB; the FIR has unit DC gain and is symmetric (linear phase)."""
    h = lowpass_taps(400.0, 204.8)
    assert len(h) % 2 == 1 and abs(h.sum() - 1) < 1e-12 and np.allclose(h, h[::-1])
    t = np.arange(8000) / 400.0
    for f, lo, hi in [(10.0, 0.99, 1.01), (130.0, 0.0, 10 ** (-50 / 20))]:
        r = StreamResampler(400.0, 204.8)
        tg, y = r.push(t, np.sin(2 * np.pi * f * t)[:, None])
        gain = np.sqrt(2 * np.mean(y[400:-400, 0] ** 2))
        assert lo <= gain <= hi, (f, gain)
    r = StreamResampler(400.0, 204.8)  # delay compensated: a 2 Hz sine comes out in phase
    tg, y = r.push(t, np.sin(2 * np.pi * 2.0 * t)[:, None])
    assert np.abs(y[400:-400, 0] - np.sin(2 * np.pi * 2.0 * tg[400:-400])).max() < 2e-3


def _at_rate(session, rate_hz):
    """The session's streams linearly interpolated to ``rate_hz`` (as a device at that rate would give)."""
    out = {}
    for n, st in session.streams.items():
        t = np.arange(st.t[0], st.t[-1], 1.0 / rate_hz)
        out[n] = (t, np.stack([np.interp(t, st.t, st.values[:, j]) for j in range(st.values.shape[1])], axis=1))
    return out


def _steps(steps):
    return [(s.start_s, s.end_s, s.classes, s.length_m, s.x, s.y, s.z) for s in steps]


def test_tracker_resamples_another_rate_and_chunks_give_one_push_steps(dirs):
    """A 50 Hz session into the 20 Hz bundle: resampled (announced in ``warnings``, ``resampled_hz``); the
    steps of random-size pushes per stream equal those of one push, and the resampled samples bit for bit."""
    s = synthetic_session(40, seed=11)
    data = _at_rate(s, 50.0)
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    whole = tr.push(data) + tr.flush()
    assert len(whole) >= 20
    used = set(tr.bundle.manifest["sensors"]["required"]) | set(tr.bundle.manifest["sensors"]["optional"])
    assert set(tr.resampled_hz) == used & set(data)
    assert all(abs(r - 50.0) < 1e-6 for r in tr.resampled_hz.values())
    lines = [w for w in tr.warnings if "resampling to 20 Hz" in w]  # one line for the streams of one push (E22)
    assert len(lines) == 1 and all(n in lines[0] for n in tr.resampled_hz) and "sampled at 50 Hz" in lines[0]
    rng = np.random.default_rng(5)
    tr2 = Tracker(dirs["root"] / "bundle", resample=True)
    steps = []
    for push in _time_chunks(rng, data):
        steps += tr2.push(push)
    steps += tr2.flush()
    a, b = _steps(whole), _steps(steps)
    assert [x[:3] for x in a] == [x[:3] for x in b]
    np.testing.assert_allclose(np.array([x[3:] for x in a]), np.array([x[3:] for x in b]), rtol=0, atol=1e-9)
    st1, st2 = InputStage(tr.bundle), InputStage(tr.bundle)
    one = st1.push(data)
    tail = st1.flush()
    one = {n: _cat([one[n], *([tail[n]] if n in tail else [])]) for n in one}
    rng = np.random.default_rng(6)
    parts: dict = {n: [] for n in data}
    for n, tv in data.items():
        for c in _chunks(rng, *tv):
            got = st2.push({n: c}).get(n)
            if got is not None:
                parts[n].append(got)
    for n, tv in st2.flush().items():
        parts[n].append(tv)
    for n in data:
        got = _cat(parts[n])
        assert np.array_equal(got[0], one[n][0]) and np.array_equal(got[1], one[n][1]), n


def test_no_resample_keeps_the_rate_refusal(dirs):
    s = synthetic_session(8, seed=3)
    data = _at_rate(s, 100.0)
    with pytest.raises(DataError, match=r"sampled at 100 Hz .* trained at 20 Hz; resample the data"):
        Tracker(dirs["root"] / "bundle", resample=False).push(data)


def test_a_required_stream_that_stops_is_one_error_naming_it(dirs):
    """Decision E23: the foot accelerometer stops at 10 s, the gyroscope goes on; the push that takes the
    gyroscope past 10 s + max_lag_s raises, naming the accelerometer, before any step is made of held values
    (E9 would process a waiting step then); before, steps come out as usual."""
    s = synthetic_session(40, seed=2)
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    assert tr.max_lag_s == 2.0
    n_steps, raised_at = 0, None
    for a in np.arange(0.0, 30.0, 0.25):
        chunk = {}
        for n, st in s.streams.items():
            m = (st.t >= a) & (st.t < a + 0.25)
            if n == "fAccelerometer":
                m &= st.t < 10.0
            chunk[n] = (st.t[m], st.values[m])
        try:
            n_steps += len(tr.push(chunk))
        except DataError as exc:
            raised_at, msg = a, str(exc)
            break
    # 2 s + its delivery interval (0.25 s pushes, measured between lag ticks) after it stopped
    assert raised_at is not None and 12.0 <= raised_at <= 12.25
    assert msg.startswith("fAccelerometer: no samples since 9.9") and "max_lag_s = 2 s + 0.25 s" in msg
    assert "\n" not in msg
    assert n_steps >= 3
    held = tr._foot._pg if tr._foot is not None else None  # gyroscope samples held for the accelerometer
    assert held is None or len(held[0]) <= 2.5 * 20


def test_a_required_stream_that_never_comes_is_an_error_and_an_unused_one_is_ignored(dirs, caplog):
    s = synthetic_session(20, seed=4)
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    with pytest.raises(DataError, match=r"^wGyroscope: no samples at all since the first sample at 0\.00 s"):
        for a in np.arange(0.0, 20.0, 0.5):
            tr.push({n: (st.t[(st.t >= a) & (st.t < a + 0.5)], st.values[(st.t >= a) & (st.t < a + 0.5)])
                     for n, st in s.streams.items() if n != "wGyroscope"})
    # a stream the bundle does not read: ignored from its first sample, logged once (not dropped when it lags,
    # re-added at its next sample and dropped again: a 0.25 Hz stream gave 11 warnings in 60 s); the steps are
    # those of the session without it
    s = synthetic_session(60, seed=3)
    ref = Tracker(dirs["root"] / "bundle", resample=True)
    want = [(x.start_s, x.end_s) for x in ref.push({n: (st.t, st.values) for n, st in s.streams.items()})
            + ref.flush()]  # decision E280: strides held for L611's verdict come out at flush
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    slow = np.arange(0.0, 60.0, 4.0)
    got = []
    caplog.set_level(logging.DEBUG, logger="pdrlearn")
    for a in np.arange(0.0, 61.0, 0.5):
        chunk = {n: (st.t[(st.t >= a) & (st.t < a + 0.5)], st.values[(st.t >= a) & (st.t < a + 0.5)])
                 for n, st in s.streams.items()}
        m = (slow >= a) & (slow < a + 0.5)
        chunk["xTemperature"] = (slow[m], np.full((int(m.sum()), 1), 21.0))
        got += tr.push(chunk)
    got += tr.flush()
    assert "xTemperature" not in tr._buf and tr.inputs.ignored == {"xTemperature": "the bundle does not use it"}
    assert not [w for w in tr.warnings if "xTemperature" in w]
    assert [r.getMessage() for r in caplog.records if "xTemperature" in r.getMessage()] == [
        f"bundle {tr.bundle.path}: xTemperature: the bundle does not use it; its samples are ignored"]
    assert [(x.start_s, x.end_s) for x in got] == want[:len(got)] and len(got) >= len(want) - 1


def _same_steps(got, ref):
    """Equal steps: times and classes exactly, lengths and positions to rounding (the push-time levelling
    sums in push order, decision E15)."""
    a, b = _steps(got), _steps(ref)
    assert [x[:3] for x in a] == [x[:3] for x in b]
    np.testing.assert_allclose(np.array([x[3:] for x in a]), np.array([x[3:] for x in b]), rtol=0, atol=1e-9)


def _push_all(tr, pushes):
    out = []
    for p in pushes:
        out += tr.push(p)
    return out + tr.flush()


def _cut(s, a, b, names=None):
    return {n: (st.t[(st.t >= a) & (st.t < b)], st.values[(st.t >= a) & (st.t < b)])
            for n, st in s.streams.items() if names is None or n in names}


FOOT = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB")
WAIST = ("wAccelerometer", "wGyroscope", "wBarometer")


@pytest.mark.parametrize("batch_s", [0.5, 3.0, 5.0])
def test_units_pushed_separately_in_batches_track_like_one_push(dirs, batch_s):
    """E23 amended: each unit pushed on its own in batches of up to 5 s (the foot's batch, then the waist's)
    is not a stopped stream (it was: 'no samples at all since ...' from 2 s batches on); the steps equal
    those of one push per chunk. A foot unit that then stops is still an error, one batch later (a waist unit pauses,
    decision E115)."""
    s = synthetic_session(40, seed=3, rate_hz=20.0)
    ref = _push_all(Tracker(dirs["root"] / "bundle", resample=True),
                    (_cut(s, a, a + 1.0) for a in np.arange(0, 45, 1.0)))
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    got = _push_all(tr, (_cut(s, a, a + batch_s, g) for a in np.arange(0, 45, batch_s) for g in (FOOT, WAIST)))
    _same_steps(got, ref)
    assert len(got) >= 30
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    stop = r"^fAccelerometer: no samples since 1?[19]\.95 s .* max_lag_s = 2 s \+ [0-9.]+ s "
    with pytest.raises(DataError, match=stop):
        _push_all(tr, (_cut(s, a, a + batch_s, g) for a in np.arange(0, 45, batch_s) for g in (FOOT, WAIST)
                       if g == WAIST or a < 10.0 - 1e-9))


def test_an_optional_stream_that_stops_is_ignored_with_one_warning(dirs):
    """E23 amended: the barometer (optional) stops at 10 s: one warning, the steps go on without it (it
    stopped the tracker before)."""
    s = synthetic_session(40, seed=3)
    baro = s.streams["wBarometer"]
    s.streams["wBarometer"] = type(baro)("wBarometer", baro.t[baro.t < 10.0], baro.values[baro.t < 10.0])
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    got = _push_all(tr, (_cut(s, a, a + 0.5) for a in np.arange(0, 45, 0.5)))
    assert len(got) >= 35 and "wBarometer" not in tr._buf and "wBarometer" in tr.inputs.ignored
    w = [x for x in tr.warnings if x.startswith("wBarometer")]
    assert len(w) == 1 and w[0].startswith("wBarometer (optional): no samples since 9.9") and "ignored" in w[0]


def test_a_slow_optional_stream_is_not_a_stopped_one(dirs):
    """A 0.4 Hz barometer (2.5 s between samples, more than max_lag_s) is judged on its own sample
    interval: resampled, never dropped."""
    s = synthetic_session(40, seed=3)
    b = s.streams["wBarometer"]
    t = np.arange(0.0, b.t[-1], 2.5)
    s.streams["wBarometer"] = type(b)("wBarometer", t, np.interp(t, b.t, b.values[:, 0])[:, None])
    tr = Tracker(dirs["root"] / "bundle", resample=True)
    got = _push_all(tr, (_cut(s, a, a + 0.5) for a in np.arange(-1, 45, 0.5)))
    assert len(got) >= 35 and not any("optional" in w for w in tr.warnings)
    assert tr.resampled_hz == {"wBarometer": pytest.approx(0.4)}


def test_a_burst_at_the_start_does_not_decide_a_streams_rate(dirs):
    """E22 amended: a 20 Hz session whose foot streams start with 4 extra samples 10 ms apart was judged
    100 Hz from its first 5 intervals (167-tap filter, then a false stop); the rate is the median interval
    of the first 32 samples / 1 s now: not resampled, the steps of the clean session. ``pdrlearn run``
    gives the tracker the session's rates (``input_rates_hz``), the rates its announcement names."""
    s = synthetic_session(40, seed=3)
    ref = _push_all(Tracker(dirs["root"] / "bundle", resample=True),
                    (_cut(s, a, a + 1.0) for a in np.arange(-1, 45, 1.0)))
    for n in ("fAccelerometer", "fGyroscope"):
        x = s.streams[n]
        t = np.concatenate([[x.t[0]], x.t[0] + np.array([0.01, 0.02, 0.03, 0.04]), x.t[1:]])
        s.streams[n] = type(x)(n, t, np.concatenate([np.repeat(x.values[:1], 5, axis=0), x.values[1:]]))
    for kw in ({}, {"input_rates_hz": {n: st.rate_hz for n, st in s.streams.items()}}):
        tr = Tracker(dirs["root"] / "bundle", resample=True, **kw)
        got = _push_all(tr, (_cut(s, a, a + 1.0) for a in np.arange(-1, 45, 1.0)))
        assert tr.resampled_hz == {}
        _same_steps(got, ref)


def test_resampler_filters_only_the_centres_it_interpolates_from():
    """E22 amended (speed): the FIR is evaluated only at the input samples around an output time; the
    output equals filtering every input sample and interpolating (the reference below), to rounding."""
    rate_in, rate_out = 1000.0, 20.0
    rng = np.random.default_rng(1)
    t = np.arange(4000) / rate_in
    v = rng.standard_normal((len(t), 2))
    r = StreamResampler(rate_in, rate_out)
    calls = []
    orig = r._filter_at
    r._filter_at = lambda hv, idx: calls.append(len(idx)) or orig(hv, idx)
    got = _cat([*(r.push(t[i:i + 1], v[i:i + 1]) for i in range(len(t))), r.flush()])
    h, d = r.taps, r.delay
    pad = np.concatenate([np.repeat(v[:1], d, axis=0), v, np.repeat(v[-1:], d, axis=0)])
    y = np.stack([np.convolve(pad[:, j], h[::-1], mode="valid") for j in range(2)], axis=1)
    ref = np.stack([np.interp(got[0], t, y[:, j]) for j in range(2)], axis=1)
    np.testing.assert_allclose(got[1], ref, rtol=0, atol=1e-12)
    assert sum(calls) <= 2 * len(got[0]) + len(calls)  # ~2 centres per output sample, not 50


@pytest.mark.parametrize("which", ["wAccelerometer", "wBarometer"])
def test_run_replays_a_gap_in_a_used_stream_the_same_at_any_chunk(dirs, tmp_path, capsys, which):
    """E23 amended: a recording whose waist accelerometer (required) or barometer (optional) pauses for 2.6 s
    and resumes: ``run`` knows where each stream ends, so the pause is a gap the steps wait for, not a stopped
    sensor ('wBarometer: no samples since 9.95 s ... stopped' aborted it; the accelerometer's depended on
    --chunk-s); every chunk size gives the same steps.csv."""
    import pandas as pd

    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s = synthetic_session(40, seed=3, name="gap")
    st = s.streams[which]
    keep = (st.t < 10.0) | (st.t > 12.6)
    s.streams[which] = type(st)(which, st.t[keep], st.values[keep])
    write_session(s, tmp_path / "gap")
    tables = []
    for chunk in ("0.25", "1", "2", "5"):
        out = tmp_path / f"run{chunk}"
        assert main(["run", "--no-plot", str(dirs["root"] / "bundle"), str(tmp_path / "gap"), "--chunk-s", chunk,
                     "--out", str(out), "--resample"]) == 0, capsys.readouterr()[1]
        tables.append(pd.read_csv(out / "steps.csv"))
    capsys.readouterr()
    assert len(tables[0]) >= 36
    for t in tables[1:]:  # the same steps; lengths and positions to rounding (push-time levelling, E15)
        pd.testing.assert_frame_equal(t, tables[0], check_exact=False, rtol=0, atol=1e-9)


def test_run_verbose_says_the_resampling_once(dirs, tmp_path, capsys):
    """E22: with -v, ``run`` printed the resampling 8 times (its warning + one info line per stream)."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s = synthetic_session(20, seed=9, name="s50")
    for n, (t, v) in _at_rate(s, 50.0).items():
        s.streams[n] = type(s.streams[n])(n, t, v)
    write_session(s, tmp_path / "s50")
    assert main(["-v", "run", str(dirs["root"] / "bundle"), str(tmp_path / "s50"), "--resample"]) == 0
    err = capsys.readouterr()[1]
    lines = [ln for ln in err.splitlines() if "resampling" in ln]
    assert len(lines) == 1 and lines[0].startswith("warning: ") and "sampled at 50 Hz" in lines[0]


# -- real data: a 102.4 Hz recording with a bundle trained at 204.8 Hz (decision E22) --------------------

@pytest.fixture(scope="module")
def real_bundle(tmp_path_factory):
    """An SVM terrain model of three gaitmap foot recordings and its bundle (made once per test run and shared
    with test_runtime_parity.py: read-only)."""
    from tests._shared_i2 import gaitmap_bundle

    return gaitmap_bundle(tmp_path_factory)


def _decimated(src, dst, every=2, acc_short_s=0.0):
    """``src`` with every ``every``-th sample (204.8 -> 102.4 Hz: a device at half the rate), its foot
    accelerometer optionally ending ``acc_short_s`` before the gyroscope."""
    from pdrlearn.io import read_session, write_session

    s = read_session(src)
    for n, st in s.streams.items():
        keep = np.arange(0, len(st.t), every)
        if n == "fAccelerometer" and acc_short_s:
            keep = keep[st.t[keep] <= st.t[-1] - acc_short_s]
        s.streams[n] = type(st)(n, st.t[keep], st.values[keep])
    s.meta["rate_hz"] = s.meta.get("rate_hz", 204.8) / every
    write_session(s, dst)
    return dst


@pytest.fixture(scope="module")
def right102(real_bundle, tmp_path_factory):
    """gaitmap_level_right at 102.4 Hz and its ``track --model --streaming`` at the data's own rate, made once for
    the two tests that compare ``run`` with it (session 41): ``(session, track summary, track stderr, track
    steps.csv)``."""
    import contextlib
    import io
    import json

    from pdrlearn.cli import main
    from tests.conftest import REAL

    root = tmp_path_factory.mktemp("right102")
    dec = _decimated(REAL / "gaitmap_level_right", root / "right102")
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(["track", "--no-plot", str(dec), "--model", str(real_bundle / "model"), "--streaming", "--json",
                   "--out", str(root / "track")])
    assert rc == 0, err.getvalue()
    return dec, json.loads(out.getvalue()), err.getvalue(), root / "track" / "steps.csv"


def test_run_a_102hz_recording_with_a_204hz_bundle_like_track_streaming(real_bundle, right102, tmp_path, capsys):
    """``pdrlearn run`` resamples (one warning line), ``--no-resample`` refuses (the old line); the strides
    and classes are close to ``track --model --streaming`` at the data's own rate. Tolerances from the 102.4 Hz
    external recordings (experiments/results/runtime_resample_compare.md: up to 1 extra stride, 88-97 % of
    the matched strides with the same class, distance within 5 %), not from this recording."""
    import json

    from pdrlearn.cli import main

    dec, track, _, track_steps = right102
    b = real_bundle / "bundle"
    assert main(["run", "--no-plot", str(b), str(dec), "--json", "--out", str(tmp_path / "run"), "--resample"]) == 0
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if "resampling" in ln]
    assert len(lines) == 1 and "fAccelerometer, fGyroscope sampled at 102.4 Hz" in lines[0]
    assert "resampling to 204.8 Hz" in lines[0] and "--no-resample" in lines[0]
    run = json.loads(out)
    assert abs(run["n_steps"] - track["n_steps"]) <= 1
    assert abs(run["distance_m"] / track["distance_m"] - 1) <= 0.05
    import pandas as pd

    rs, ts = pd.read_csv(tmp_path / "run" / "steps.csv"), pd.read_csv(track_steps)
    same = matched = 0
    for _, r in ts.iterrows():
        d = np.abs(rs["start_s"] - r["start_s"]) + np.abs(rs["end_s"] - r["end_s"])
        j = int(np.argmin(d))
        if d[j] < 0.1:
            matched += 1
            same += rs["terrain"][j] == r["terrain"]
    assert matched >= 0.9 * len(ts) and same >= 0.85 * matched
    assert main(["run", str(b), str(dec), "--no-resample"]) == 2
    err = capsys.readouterr()[1]
    assert "fAccelerometer is sampled at 102.4 Hz but bundle" in err and "resample the data to 204.8 Hz" in err


def _check_short_line(line, session_dir, steps_csv, name="fAccelerometer"):
    """The numbers of run's short-stream warning against the session and the run's steps.csv."""
    import re

    import pandas as pd

    from pdrlearn.io import read_session

    acc_end = float(read_session(session_dir).streams[name].t[-1])
    steps = pd.read_csv(steps_csv)
    past = steps[steps["end_s"] > acc_end]
    m = re.search(name + r" ends at ([0-9.]+) s, ", line)
    assert m and float(m[1]) == round(acc_end, 2), line
    if len(past):
        m = re.search(r": (\d+) step\(s\) \(([0-9.]+) to ([0-9.]+) s\) ran past its end and were measured with its "
                      r"last sample held; the walk is tracked to ([0-9.]+) s", line)
        assert m, line
        assert int(m[1]) == len(past) and float(m[2]) == round(past["start_s"].iloc[0], 2)
        assert float(m[3]) == round(past["end_s"].iloc[-1], 2)
    else:
        m = re.search(r": no step runs past its end; the walk is tracked to ([0-9.]+) s", line)
        assert m, line
    assert float(m[m.lastindex]) == round(steps["end_s"].iloc[-1], 2)
    return len(past)


def test_run_says_where_a_short_foot_accelerometer_ends_the_walk(real_bundle, dirs, tmp_path, capsys):
    """A recording whose foot accelerometer ends 0.9 s before its gyroscope (B21 lets up to 1 s through):
    one warning line with where it ends, the steps that ran past it (measured with its last sample held) and
    where the tracked walk ends, each number checked against the run's steps.csv ('nothing after 29.10 s is
    tracked (last step ends at 29.18 s)' contradicted itself). A real walk (no step past the end) and a
    simulated one whose waist accelerometer ends early (steps past it)."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from tests.conftest import REAL

    dec = _decimated(REAL / "gaitmap_level_left", tmp_path / "short", every=1, acc_short_s=0.9)
    s = synthetic_session(30, seed=3, name="simshort")
    for n, st in s.streams.items():  # every stream to 30.0 s, the waist accelerometer to 29.1 s
        keep = st.t <= (29.1 if n == "wAccelerometer" else 30.0) + 1e-9
        s.streams[n] = type(st)(n, st.t[keep], st.values[keep])
    write_session(s, tmp_path / "simshort")
    n_past = []
    for b, sess, name in ((real_bundle / "bundle", dec, "fAccelerometer"),
                          (dirs["root"] / "bundle", tmp_path / "simshort", "wAccelerometer")):
        out = tmp_path / f"out_{sess.name}"
        assert main(["run", "--no-plot", str(b), str(sess), "--out", str(out)]) == 0
        lines = [ln for ln in capsys.readouterr()[1].splitlines() if "before fGyroscope" in ln]
        assert len(lines) == 1
        n_past.append(_check_short_line(lines[0], sess, out / "steps.csv", name))
    assert n_past[1] >= 1


def test_run_tracks_another_rate_at_the_native_rate_by_default(real_bundle, right102, tmp_path, capsys):
    """E22 amended: by default ``run`` tracks data at another rate at its own rate, exactly as ``track
    --streaming`` (resampling a 50 Hz walk into a 20 Hz bundle mislabelled half its steps: the models'
    features are defined in seconds and cut from the data's own samples)."""
    import json

    from pdrlearn.cli import main

    dec, track, track_err, _ = right102
    b = real_bundle / "bundle"
    assert main(["run", "--no-plot", str(b), str(dec), "--json", "--out", str(tmp_path / "run")]) == 0
    out, err = capsys.readouterr()
    assert any("tracked at the data's own rate" in ln for ln in err.splitlines())
    # decision C18 amended: run says what track says of the classifiers' rate (it said only the line above)
    c18 = [ln for ln in err.splitlines() if "step classifiers were trained at" in ln]
    assert len(c18) == 1 and "trained at 204.8 Hz, the session's foot unit runs at 102.4 Hz" in c18[0], err
    run = json.loads(out)
    line = c18[0][c18[0].index("the model's step classifiers"):]
    assert line in track_err, track_err  # the same words as track's
    assert run["n_steps"] == track["n_steps"]
    assert abs(run["distance_m"] - track["distance_m"]) < 1e-6
    assert main(["run", str(b), str(dec), "--out", str(tmp_path / "x"), "--resample", "--no-resample"]) == 2
