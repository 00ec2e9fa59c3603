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
    tr = Tracker(dirs["root"] / "bundle")
    whole = tr.push(data) + tr.flush()
    assert len(whole) >= 20
    used = set(tr.bundle.manifest["sensors"]["required"]) | set(tr.bundle.manifest["sensors"]["optional"])
    assert set(tr.resampled_hz) == used & set(data)
    assert all(abs(r - 50.0) < 1e-6 for r in tr.resampled_hz.values())
    assert sum("resampling it to 20 Hz" in w for w in tr.warnings) == len(tr.resampled_hz)
    rng = np.random.default_rng(5)
    tr2 = Tracker(dirs["root"] / "bundle")
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
    tr = Tracker(dirs["root"] / "bundle")
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
    assert raised_at is not None and 11.75 <= raised_at <= 12.0  # 2 s after, in the push that passes 12 s
    assert msg.startswith("fAccelerometer: no samples since 9.9") and "max_lag_s = 2 s" in msg and "\n" not in msg
    assert n_steps >= 3
    held = tr._foot._pg if tr._foot is not None else None  # gyroscope samples held for the accelerometer
    assert held is None or len(held[0]) <= 2.5 * 20


def test_a_required_stream_that_never_comes_is_an_error_and_an_unused_one_is_dropped(dirs, caplog):
    s = synthetic_session(20, seed=4)
    tr = Tracker(dirs["root"] / "bundle")
    with pytest.raises(DataError, match=r"^wGyroscope: no samples at all since the first sample at 0\.00 s"):
        for a in np.arange(0.0, 20.0, 0.5):
            tr.push({n: (st.t[(st.t >= a) & (st.t < a + 0.5)], st.values[(st.t >= a) & (st.t < a + 0.5)])
                     for n, st in s.streams.items() if n != "wGyroscope"})
    # a stream the bundle does not read (here a second, extra sensor) stops: a warning, and the steps are those
    # of the session without it
    ref = Tracker(dirs["root"] / "bundle")
    want = [(x.start_s, x.end_s) for x in ref.push({n: (st.t, st.values) for n, st in s.streams.items()})]
    tr = Tracker(dirs["root"] / "bundle")
    extra = s.streams["wBarometer"] if "wBarometer" in s.streams else s.streams["fGyroscope"]
    got = []
    with caplog.at_level(logging.WARNING):
        for a in np.arange(0.0, 21.0, 0.5):
            chunk = {n: (st.t[(st.t >= a) & (st.t < a + 0.5)], st.values[(st.t >= a) & (st.t < a + 0.5)])
                     for n, st in s.streams.items()}
            m = (extra.t >= a) & (extra.t < min(a + 0.5, 5.0))
            chunk["xTemperature"] = (extra.t[m], extra.values[m, :1])
            got += tr.push(chunk)
    got += tr.flush()
    assert "xTemperature" not in tr._buf
    assert any(w.startswith("xTemperature stopped at 4.9") for w in tr.warnings)
    assert [(x.start_s, x.end_s) for x in got] == want[:len(got)] and len(got) >= len(want) - 1


# -- real data: a 102.4 Hz recording with a bundle trained at 204.8 Hz (decision E22) --------------------

@pytest.fixture(scope="module")
def real_bundle(tmp_path_factory):
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.io import read_session
    from tests.conftest import REAL

    root = tmp_path_factory.mktemp("real204")
    train = [read_session(REAL / n) for n in ("gaitmap_level_left", "gaitmap_stairs_up_left",
                                              "gaitmap_stairs_down_left")]
    train_user(train, tasks=["terrain"], cv=3, seed=0, methods=["svm"]).save(root / "model")
    export_model(root / "model", root / "bundle", frames={"foot": train[0].frames["foot"].to_dict()})
    return root


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


def test_run_a_102hz_recording_with_a_204hz_bundle_like_track_streaming(real_bundle, tmp_path, capsys):
    """``pdrlearn run`` resamples (one warning line), ``--no-resample`` refuses (the old line); the strides
    and classes are close to ``track --model --streaming`` at the data's own rate. Tolerances from the 102.4 Hz
    external recordings (experiments/results/runtime_resample_compare.md: up to 1 extra stride, 88-97 % of
    the matched strides with the same class, distance within 5 %), not from this recording."""
    import json

    from pdrlearn.cli import main
    from tests.conftest import REAL

    dec = _decimated(REAL / "gaitmap_level_right", tmp_path / "right102")
    b = real_bundle / "bundle"
    assert main(["run", str(b), str(dec), "--json", "--out", str(tmp_path / "run")]) == 0
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if "resampling" in ln]
    assert len(lines) == 1 and "fAccelerometer, fGyroscope sampled at 102.4 Hz" in lines[0]
    assert "resampling to 204.8 Hz" in lines[0] and "--no-resample" in lines[0]
    run = json.loads(out)
    assert main(["track", str(dec), "--model", str(real_bundle / "model"), "--streaming", "--json",
                 "--out", str(tmp_path / "track")]) == 0
    track = json.loads(capsys.readouterr()[0])
    assert abs(run["n_steps"] - track["n_steps"]) <= 1
    assert abs(run["distance_m"] / track["distance_m"] - 1) <= 0.05
    import pandas as pd

    rs, ts = pd.read_csv(tmp_path / "run" / "steps.csv"), pd.read_csv(tmp_path / "track" / "steps.csv")
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


def test_run_says_where_a_short_foot_accelerometer_ends_the_walk(real_bundle, tmp_path, capsys):
    """A recording whose foot accelerometer ends 0.9 s before its gyroscope (B21 lets up to 1 s through):
    one warning line with where it ends and the last tracked step."""
    from pdrlearn.cli import main
    from tests.conftest import REAL

    dec = _decimated(REAL / "gaitmap_level_left", tmp_path / "short", every=1, acc_short_s=0.9)
    assert main(["run", str(real_bundle / "bundle"), str(dec)]) == 0
    err = capsys.readouterr()[1]
    lines = [ln for ln in err.splitlines() if "before fGyroscope" in ln]
    assert len(lines) == 1
    assert "fAccelerometer ends at" in lines[0] and "nothing after" in lines[0] and "last step ends at" in lines[0]
