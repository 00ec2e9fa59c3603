"""Live waist-only tracking (:class:`pdrlearn.waist.WaistTracker`, decisions W64-W65): pushed in chunks of any
size it gives the steps and positions of ``track_waist(session, pipeline="waist-pendulum", realtime=True)``."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.sim import simulate
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.live import FRAGMENT_CONTEXT_STEPS
from tests.runtime_helpers import push_waist

ROOT = Path(__file__).resolve().parents[1]
HA001 = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"
_CACHE: dict = {}


def _session(name: str):
    if name not in _CACHE:
        _CACHE[name] = read_session(HA001) if name == "ha001" else simulate("B", 1, speed="slow", rate_hz=100.0)
    return _CACHE[name]


def _run(s, chunks, **kw):
    """Push ``s``'s waist samples in pieces of ``chunks`` sizes (the rest at once), then flush."""
    a = s["wAccelerometer"]
    kw.setdefault("frame", s.require_frame("waist"))
    tr = WaistTracker(a.rate_hz, meta=s.meta, **kw)
    return push_waist(tr, s, chunks), tr


def _whole(s):
    """``_run(s, [all samples])`` with the defaults, pushed once per module (session 42: two tests made it)."""
    key = ("whole", s.name, len(s["wAccelerometer"].t))
    if key not in _CACHE:
        _CACHE[key] = _run(s, [len(s["wAccelerometer"].t)])[0]
    return _CACHE[key]


def _columns(out):
    return {k: np.array([getattr(o, k) for o in out], dtype=float)
            for k in ("t", "end_s", "length_m", "heading_rad", "x", "y")}


def _replay(s, **kw):
    key = (s.name, len(s["wAccelerometer"].t), repr(sorted(kw.items())))
    if key not in _CACHE:
        _CACHE[key] = track_waist(s, pipeline="waist-pendulum", realtime=True, **kw)
    return _CACHE[key]


def _assert_equals_replay(s, out, tol=1e-9, **kw):
    ref = _replay(s, **kw)
    st, trj = ref.steps, ref.trajectory
    c = _columns(out)
    assert len(out) == len(st) > 20
    np.testing.assert_allclose(c["t"], st["event_s"], atol=tol, rtol=0)
    np.testing.assert_allclose(c["end_s"], st["end_s"], atol=tol, rtol=0)
    np.testing.assert_allclose(c["length_m"], st["length_m"], atol=tol, rtol=0)
    dh = np.angle(np.exp(1j * (c["heading_rad"] - st["heading_rad"].to_numpy())))
    assert np.abs(dh).max() < tol
    np.testing.assert_allclose(c["x"], trj["x"].to_numpy()[1:], atol=tol, rtol=0)
    np.testing.assert_allclose(c["y"], trj["y"].to_numpy()[1:], atol=tol, rtol=0)
    assert [o.merged for o in out] == list(st["merged"]) and [o.turning for o in out] == list(st["turning"])


@pytest.mark.parametrize("how", ["all", "random", "one"])
def test_simulated_walk_equals_the_realtime_replay(how):
    s = _session("sim")
    n = len(s["wAccelerometer"].t)
    chunks = {"all": [n], "random": list(np.random.default_rng(3).integers(1, 300, 4000)), "one": [1] * n}[how]
    out, tr = _run(s, chunks)
    _assert_equals_replay(s, out)
    assert tr.position == (out[-1].x, out[-1].y) and len(tr.steps) == len(out)


def test_slow_turn_option_equals_the_realtime_replay():
    """W82: the gentle-curve option reads one stride ahead, which the live tracker always knows: live = replay."""
    s = _session("sim")
    out, _ = _run(s, list(np.random.default_rng(7).integers(1, 300, 4000)), slow_turn_rps=0.035)
    _assert_equals_replay(s, out, slow_turn_rps=0.035)


@pytest.mark.parametrize("how", ["all", "random"])
def test_ha001_test11_without_fragment_merging_equals_the_replay(how):
    """W64: with merge_fragments off nothing is judged on the sequence so far: the replay's steps exactly."""
    s = _session("ha001")
    n = len(s["wAccelerometer"].t)
    chunks = [n] if how == "all" else list(np.random.default_rng(5).integers(1, 400, 4000))
    kw = {"merge_fragments": False}
    if how == "random":  # and the options that change the heading and the start
        kw.update(integrate_stops=True, turn_factor=False, start={"x": 1.0, "y": -2.0, "heading_rad": 0.7})
    out, _ = _run(s, chunks, **kw)
    _assert_equals_replay(s, out, **kw)


@pytest.mark.slow
def test_ha001_test11_one_sample_pushes_equal_one_push():
    """W64's fragment rule reads the same rows whatever arrived when: every chunking gives the same steps."""
    s = _session("ha001")
    # one sample at a time over 0-15 s and 84-104 s (1 s pushes between and after): the windows hold both W27
    # fragments the live tracker judges (4.1 s and 86.7 s) and a turn (9.9 s): the fragment rule runs sample by sample
    one = _columns(_run(s, [1] * 1500 + [100] * 69 + [1] * 2000 + [100] * 34)[0])
    whole = _columns(_whole(s))
    rand = _columns(_run(s, list(np.random.default_rng(9).integers(1, 500, 4000)))[0])
    for k in one:
        np.testing.assert_allclose(one[k], whole[k], atol=1e-9, rtol=0)
        np.testing.assert_allclose(rand[k], whole[k], atol=1e-9, rtol=0)


def test_ha001_test11_defaults_differ_from_the_replay_only_at_w27_decisions():
    """W64: with the default merge_fragments the contacts and headings are the replay's; a step length differs
    only where a W27 fragment is judged on the sequence so far (the replay: on the whole sequence)."""
    s = _session("ha001")
    out = _whole(s)
    st = _replay(s).steps
    c = _columns(out)
    np.testing.assert_array_equal(c["t"], st["event_s"])
    assert np.abs(np.angle(np.exp(1j * (c["heading_rad"] - st["heading_rad"].to_numpy())))).max() < 1e-9
    differs = np.flatnonzero(np.abs(c["length_m"] - st["length_m"].to_numpy()) > 1e-9)
    merged = np.flatnonzero(np.array([o.merged for o in out]) | st["merged"].to_numpy(bool))
    assert differs.size <= 2 and all(np.abs(merged - i).min() <= 1 for i in differs)
    assert abs(c["length_m"].sum() - st["length_m"].sum()) < 0.01 * st["length_m"].sum()


def test_dropped_samples_and_a_gap_as_the_replay():
    """W59/W34: 6 single dropped samples and a 1.5 s gap (ends the sequence, B11) give the replay's track, with
    the replay's gap warning."""
    s = read_session(HA001)
    n = len(s["wAccelerometer"])
    drop = np.zeros(n, dtype=bool)
    drop[np.random.default_rng(0).choice(np.arange(50, n - 50), 6, replace=False)] = True
    drop[3000:3150] = True
    for name in ("wAccelerometer", "wGyroscope"):
        st = s[name]
        s.streams[name] = Stream(name, st.t[~drop], st.values[~drop])
    out, tr = _run(s, list(np.random.default_rng(1).integers(1, 250, 5000)), merge_fragments=False)
    _assert_equals_replay(s, out, merge_fragments=False)
    assert sum("1 gap(s) longer than 1 s" in w for w in tr.warnings) == 1


def _inferred(s):
    """HA001 pushed in 50-sample pieces without its frame (meta without "frames"), merge_fragments off: (the steps,
    the tracker), made once per module (session 46: the W65 test and the B108 hint test each pushed it)."""
    key = ("inferred", s.name, len(s["wAccelerometer"].t))
    if key not in _CACHE:
        meta = {k: v for k, v in s.meta.items() if k not in ("source_project", "frames")}
        a, g = s["wAccelerometer"], s["wGyroscope"]
        tr = WaistTracker(a.rate_hz, meta=meta, merge_fragments=False)
        out = []
        for i in range(0, len(a.t), 50):
            out += tr.push(a.t[i:i + 50], a.values[i:i + 50], g.values[i:i + 50])
        out += tr.flush()
        _CACHE[key] = (out, tr)
    return _CACHE[key]


def test_frame_inferred_from_the_first_walking():
    """W65: without a frame the tracker holds the samples until the inference fixes one, then tracks them all."""
    s = _session("ha001")
    out, tr = _inferred(s)
    assert any("inferred from the first" in w and "decision W65" in w for w in tr.warnings)
    _assert_equals_replay(s, out, merge_fragments=False)


def test_standing_without_a_frame_tracks_nothing_with_one_warning():
    t = np.arange(1000) / 100.0
    tr = WaistTracker(100.0, sensor_height_m=0.95)
    assert tr.push(t, np.tile([0.0, 0.0, 9.81], (1000, 1)), np.zeros((1000, 3))) == []
    assert tr.flush() == [] and tr.position == (0.0, 0.0)
    assert sum(w.startswith("no walking to track") for w in tr.warnings) == 1


@pytest.mark.slow
def test_state_stays_bounded_on_a_long_stream():
    """Decision W64: a stream of 8 loops of a 40 s simulated walk (5.3 min at 20 Hz; the hour of
    experiments/waist_live.py --hours 1 likewise) keeps a bounded state: the sample buffer, the pending rows (at
    most FRAGMENT_CONTEXT_STEPS + 3) and the W31 window (loops 7-8 no larger than loops 1-4; 12 loops until
    session 39)."""
    s = simulate("B", 1, speed="slow", rate_hz=20.0)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    t1 = a.t - a.t[0]
    period = t1[-1] + 1.0 / 20.0
    tr = WaistTracker(20.0, meta=s.meta, frame=s.require_frame("waist"), keep_steps=50)
    sizes, n_steps = [], 0
    for k in range(8):
        for i in range(0, len(t1), 20):
            n_steps += len(tr.push(t1[i:i + 20] + k * period, a.values[i:i + 20], g.values[i:i + 20]))
        sizes.append(tr.state_size())
    assert n_steps > 8 * 40 and len(tr.steps) == 50
    assert len(tr._rows) <= FRAGMENT_CONTEXT_STEPS + 3
    assert max(sizes[6:]) <= max(sizes[:4])  # no growth after the first loops


def test_inputs_checked_in_one_line():
    tr = WaistTracker(100.0, frame={"x": "up", "y": "right", "z": "forward"}, sensor_height_m=0.95)
    with pytest.raises(DataError, match=r"shape \(2, 3\)"):
        tr.push([0.0, 0.01], np.zeros((2, 2)), np.zeros((2, 3)))
    tr.push([0.0, 0.01], np.zeros((2, 3)), np.zeros((2, 3)))
    with pytest.raises(DataError, match="increase strictly"):
        tr.push([0.01], np.zeros((1, 3)), np.zeros((1, 3)))
    with pytest.raises(DataError, match="NaN"):
        tr.push([0.02], np.full((1, 3), np.nan), np.zeros((1, 3)))
    with pytest.raises(DataError, match=r"^WaistTracker: frame= .up-right-forward.: write e.g. x=forward,y=up,z=right"):
        WaistTracker(100.0, frame="up-right-forward")
    with pytest.raises(DataError, match=r"^start=\(200.0, 13.0\): latitude must be in \[-90, 90\]"):  # W137, L157
        WaistTracker(100.0, frame="x=up,y=right,z=forward", start=(200.0, 13.0))
    with pytest.raises(DataError, match="W56"):
        WaistTracker(100.0, frame="x=up,y=right,z=forward", params={"options": {"length_smoothing": "mobgap"}})
    with pytest.raises(DataError, match="sampling rate"):
        WaistTracker(0.0)


def test_a_params_heading_the_live_tracker_cannot_honour_is_warned():
    """W82: PARAMS.json "options": {"heading": "ellipse"} is not silently replaced by the gyro heading live."""
    asked = WaistTracker(100.0, frame="x=up,y=right,z=forward", params={"options": {"heading": "ellipse"}})
    assert asked.options["heading"] == "gyro"
    assert [w for w in asked.warnings if "heading 'ellipse'" in w and "W82" in w]
    plain = WaistTracker(100.0, frame="x=up,y=right,z=forward", params={"options": {"heading": "gyro"}})
    assert not [w for w in plain.warnings if "W82" in w]


def test_the_docs_example_runs(monkeypatch, capsys):
    """docs/waist.md "Live tracking": the example runs and prints what the docs show."""
    monkeypatch.chdir(ROOT)
    text = (ROOT / "docs" / "waist.md").read_text()
    section = text.split("## Live tracking", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert len(code.strip().splitlines()) <= 16
    ns: dict = {}
    exec(compile(code, "docs/waist.md", "exec"), ns)
    assert len(ns["tracker"].steps) > 50 and ns["tracker"].position != (0.0, 0.0)
    shown = re.search(r"```console\n(.*?)```", section, re.S).group(1).splitlines()[1:]  # (the log line: stderr)
    assert capsys.readouterr().out.splitlines() == shown


def test_frame_inferred_after_a_long_stand():
    """W65: the held samples are capped at INFER_MAX_S; inference keeps trying after the cap."""
    from pdrlearn.waist.live import INFER_MAX_S

    s = simulate("B", 1, speed="slow", rate_hz=20.0)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    r = s.require_frame("waist").matrix()  # body = r @ sensor: standing, the specific force is up in the body frame
    n0 = int((INFER_MAX_S + 10.0) * 20)
    t = np.concatenate([np.arange(n0) / 20.0, a.t - a.t[0] + n0 / 20.0])
    acc = np.vstack([np.tile(r.T @ np.array([0.0, 0.0, 9.81]), (n0, 1)), a.values])
    gyr = np.vstack([np.zeros((n0, 3)), g.values])
    tr = WaistTracker(20.0, sensor_height_m=0.95)
    n = sum(len(tr.push(t[i:i + 20], acc[i:i + 20], gyr[i:i + 20])) for i in range(0, len(t), 20))
    n += len(tr.flush())
    assert any("decision W65" in w for w in tr.warnings) and n > 20


@pytest.mark.parametrize("pushes", ["per sample", "one chunk"])
def test_timestamps_in_ms_are_refused_in_one_line(pushes):
    """E29's unit check as the runtime's (before: in ms the W31 detector re-ran its window on every sample, for
    minutes on 90 s of walking, and gave no step)."""
    s = _session("sim")
    a, g = s["wAccelerometer"], s["wGyroscope"]
    tr = WaistTracker(a.rate_hz, frame=s.require_frame("waist"), sensor_height_m=0.95)
    with pytest.raises(DataError, match=r"^WaistTracker.push: the pushed timestamps give 0\.1 Hz, 1000x below "
                                        r"fs=100 Hz: are they in ms\? push t in seconds \(t_ms / 1000\)"):
        if pushes == "one chunk":
            tr.push(a.t * 1000.0, a.values, g.values)
        for i in range(10):
            tr.push(a.t[i:i + 1] * 1000.0, a.values[i:i + 1], g.values[i:i + 1])
    if pushes == "per sample":
        assert i == 5  # the fifth interval
    out = _run(s, [1] * 50)[0]  # in seconds, sample by sample: the check passes once and tracks
    assert len(out) > 20


# -- B108: the frame hint is JSON; a declared frame is checked against the data as offline ----------------------
def _push_all(s, **kw):
    a, g = s["wAccelerometer"], s["wGyroscope"]
    tr = WaistTracker(a.rate_hz, **kw)
    for i in range(0, len(a.t), 50):
        tr.push(a.t[i:i + 50], a.values[i:i + 50], g.values[i:i + 50])
    tr.flush()
    return tr


def test_the_inferred_frame_hint_is_json_to_paste_into_meta_json():
    s = _session("ha001")
    (w,) = [w for w in _inferred(s)[1].warnings if "inferred from the first" in w]
    frames, _ = json.JSONDecoder().raw_decode(w[w.index('"frames": ') + len('"frames": '):])
    assert frames == {"waist": s.require_frame("waist").to_dict()}


def test_a_declared_frame_the_data_contradict_is_warned_live_as_offline():
    s = _session("ha001")
    flip = {"up": "down", "down": "up", "left": "right", "right": "left", "forward": "forward",
            "backward": "backward"}  # 180 deg about forward: right-handed, up and left reversed
    wrong = {k: flip[v] for k, v in s.require_frame("waist").to_dict().items()}
    for kw in ({"frame": wrong}, {"meta": {**s.meta, "frames": {"waist": wrong}}}):
        lines = [w for w in _push_all(s, **kw).warnings if "contradicts its data" in w]
        assert len(lines) == 1 and "decision D8" in lines[0] and "the declared frame is still used" in lines[0]
        fix = lines[0][lines[0].index('write "frames": ') + len('write "frames": '):]
        assert json.JSONDecoder().raw_decode(fix)[0] == {"waist": s.require_frame("waist").to_dict()}
    assert not [w for w in _push_all(s, frame=s.require_frame("waist")).warnings if "contradicts" in w]
