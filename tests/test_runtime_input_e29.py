"""Decision E29 (docs/decisions/export.md): the live runtime's input side, from a new-user trial of an app
engineer embedding ``Tracker``.

- a push is all or nothing: every sensor of it is checked before any state changes (before: a NaN in the second
  sensor refused the push after the first was buffered, and the retry failed naming the wrong sensor);
- the values' shape is checked per sensor (before: a raw numpy broadcast error), timestamps in ms are refused;
- a gap in the pushed samples is warned once (time, length); a stride across a foot gap over 1 s (B11) moves
  0 m with no classes, as ``pdrlearn track`` (plasys) counts no displacement inside one, and
  ``track --streaming`` gives the same trajectory (before: a phantom stride of metres, no warning);
- values held for a stopped stream (``max_lag_s = inf``) are warned once; a foot-only stream is named;
- the embedding example of docs/deploying.md runs.
"""

from __future__ import annotations

import pickle
import re
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import SENSORS, Stream, write_session
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime import tracker as T
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import per_timestamp, replay, synthetic_session, trained_dirs, without

DOCS = Path(__file__).resolve().parents[1] / "docs" / "deploying.md"


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=11, name="walk", turn_rad_per_step=0.3)




def _state(tr: Tracker) -> tuple:
    return ({n: (len(r), r.last) for n, r in tr._buf.items()}, {n: len(p[0]) for n, p in tr.inputs._probe.items()},
            tr._latest, len(tr._foot_q), tr.n_steps)


def test_the_sensor_table_is_the_io_registry():
    assert T.SENSOR_WIDTH == {n: s.n_axes for n, s in SENSORS.items()}


@pytest.mark.parametrize("when", ["first push", "mid-stream"])
def test_a_refused_push_changes_nothing_and_its_retry_without_the_bad_sensor_goes_on(root, walk, when):
    chunks = per_timestamp(walk)
    k = 0 if when == "first push" else 200
    ref = Tracker(root / "bundle")
    want = [st for c in chunks for st in ref.push(c)] + ref.flush()
    tr = Tracker(root / "bundle")
    got = [st for c in chunks[:k] for st in tr.push(c)]
    bad = dict(chunks[k])
    assert list(bad)[0] == "fAccelerometer" and "wGyroscope" in bad  # a sensor before the bad one in the dict
    t, v = bad["wGyroscope"]
    bad["wGyroscope"] = (t, np.where(np.arange(v.size).reshape(v.shape) == 0, np.nan, v))
    before = _state(tr)
    with pytest.raises(DataError, match=r"^wGyroscope: pushed samples contain NaN"):
        tr.push(bad)
    assert _state(tr) == before
    got += tr.push({n: tv for n, tv in chunks[k].items() if n != "wGyroscope"})  # before: "fAccelerometer: ...
    got += [st for c in chunks[k + 1:] for st in tr.push(c)] + tr.flush()  # timestamps are not increasing"
    assert len(got) == len(want) >= 20
    assert abs(got[-1].x - want[-1].x) + abs(got[-1].y - want[-1].y) < 0.05  # one waist sample fewer


@pytest.mark.parametrize("rows", [1, 50])
def test_values_of_the_wrong_shape_are_one_line_naming_the_sensor_and_the_shape(root, walk, rows):
    st = walk.streams["fAccelerometer"]
    tr = Tracker(root / "bundle")
    with pytest.raises(DataError, match=rf"^fAccelerometer: pushed values of shape \({rows}, 2\) for {rows} "
                                        rf"timestamp\(s\); push an array of shape \({rows}, 3\) \(x, y, z\)"):
        tr.push({"fGyroscope": (walk.streams["fGyroscope"].t[:rows], walk.streams["fGyroscope"].values[:rows]),
                 "fAccelerometer": (st.t[:rows], st.values[:rows, :2])})
    assert not tr._buf and not tr.inputs._probe  # the gyroscope before it was not taken either
    with pytest.raises(DataError, match=r"^fAccelerometer: pushed values of shape \(150,\) for 50 timestamp"):
        tr.push({"fAccelerometer": (st.t[:50], st.values[:50].ravel())})  # not silently reshaped to (50, 3)
    b = walk.streams["wBarometer"]
    tr.push({"wBarometer": (b.t[:50], b.values[:50].ravel())})  # a one-value sensor as a flat array is fine


def test_timestamps_in_ms_are_refused_naming_the_unit(root, walk):
    ms = {n: (st.t * 1000.0, st.values) for n, st in walk.streams.items()}
    with pytest.raises(DataError, match=r"^fAccelerometer: the pushed timestamps give 0\.02 Hz, 1000x below the "
                                        r"bundle's 20 Hz: are they in ms\? push t in seconds \(t_ms / 1000\)"):
        Tracker(root / "bundle").push(ms)  # before: no step and a "0.02 Hz" warning
    tr = Tracker(root / "bundle")
    with pytest.raises(DataError, match="1000x below"):  # sample by sample: when the rate is learned (5 samples)
        for i in range(10):
            tr.push({n: (t[i:i + 1], v[i:i + 1]) for n, (t, v) in ms.items()})
    assert i == 4


@pytest.mark.parametrize("pushes", ["per sample", "chunks"])
def test_a_long_gap_in_every_stream_is_warned_once_and_its_stride_moves_0_m_as_track_streaming(root, walk, pushes):
    s = without(walk, 10.2, 11.7)
    tr = Tracker(root / "bundle")
    if pushes == "per sample":
        steps = [st for c in per_timestamp(s) for st in tr.push(c)] + tr.flush()
    else:
        steps = replay(tr, s, 0.37)
    lines = [w for w in tr.warnings if "no samples for" in w]
    assert len(lines) == 1, tr.warnings  # before: no warning at all
    assert re.search(r"fAccelerometer.*: no samples for 1\.55 s \(10\.15-11\.70 s\); a gap longer than 1 s \(B11\): "
                     r"the stride across it moves 0 m", lines[0])
    across = [st for st in steps if st.start_s < 11.7 and st.end_s > 10.15]  # a stance detected at the gap's
    assert 1 <= len(across) <= 2  # start ends a stride inside it: both overlap it, as offline's overlaps_gaps
    assert all(st.gap_s == pytest.approx(1.55) and st.length_m == st.dz_m == 0.0 and st.classes == {}
               for st in across)
    assert all(st.gap_s == 0.0 for st in steps if st not in across)
    # track --streaming (the offline streamed path) moves the same stride 0 m: the same trajectory
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    for st in across:
        i = steps.index(st)
        assert res.steps["length_m"].iloc[i] == 0.0 and pd.isna(res.steps["terrain"].iloc[i])
    assert any("a stride across a foot gap moves 0 m" in w for w in res.info["warnings"])


@pytest.mark.parametrize("incremental", [True, False])
def test_a_short_gap_is_bridged_unclassified_as_track_streaming_and_warned_once(root, walk, incremental):
    """A 0.5 s gap: bridged; the strides overlapping the foot's gap have no classes, as offline's B11 leaves them
    (before: classified from the interpolated window). Positions equal track --streaming's (E30: with the shared
    kernel only, ``incremental=False``; since E36 a stride over a foot gap is levelled by the shared kernel on the
    gap clock in both, and the push-time levelling's 0.11 m on the stride that starts inside the gap is gone)."""
    s = without(walk, 10.2, 10.7)
    tr = Tracker(root / "bundle", incremental=incremental)
    steps = replay(tr, s, 0.37)
    lines = [w for w in tr.warnings if "no samples for" in w]
    assert len(lines) == 1 and "0.55 s (10.15-10.70 s); bridged (interpolated)" in lines[0], tr.warnings
    assert all(st.gap_s == 0.0 for st in steps)
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    assert len(steps) == len(res.steps)
    unclassified = [i for i, st in enumerate(steps) if not st.classes]
    assert unclassified == list(np.flatnonzero(res.steps["terrain"].isna())) and len(unclassified) == 2
    assert all(steps[i].start_s < 10.7 and steps[i].end_s > 10.15 for i in unclassified)
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_a_waist_gap_is_warned_and_does_not_zero_the_stride(root, walk):
    s = without(walk, 10.2, 11.7, names=("wAccelerometer", "wGyroscope", "wBarometer"))
    tr = Tracker(root / "bundle")
    steps = replay(tr, s, 0.37)
    lines = [w for w in tr.warnings if "no samples for" in w]
    assert len(lines) == 1 and lines[0].startswith("wAccelerometer") and "interpolated" in lines[0], tr.warnings
    assert "up to 1 s" not in lines[0]  # a 1.5 s gap (decision E64)
    assert all(st.gap_s == 0.0 and st.classes for st in steps)


def test_a_slow_barometer_has_no_gaps(root, walk):
    """A 1 Hz barometer: its 1 s intervals are its rate, not gaps (the gap is 1.5 of its intervals, as B11)."""
    s = walk.copy()
    b = s.streams["wBarometer"]
    s.streams["wBarometer"] = Stream("wBarometer", b.t[::20], b.values[::20])
    tr = Tracker(root / "bundle")
    assert len(replay(tr, s, 0.37)) >= 20 and not [w for w in tr.warnings if "no samples for" in w], tr.warnings
    tr = Tracker(root / "bundle")
    assert [st for c in per_timestamp(s) for st in tr.push(c)] and not [w for w in tr.warnings
                                                                       if "no samples for" in w], tr.warnings


def test_held_values_of_a_stopped_stream_are_warned_once(root, walk):
    s = without(walk, 12.0, 1e9, names=("wAccelerometer", "wGyroscope", "wBarometer"))
    tr = Tracker(root / "bundle", max_lag_s=float("inf"))
    steps = replay(tr, s, 0.37)
    assert len(steps) >= 20
    held = [w for w in tr.warnings if "last values held" in w]
    assert len(held) == 1 and re.match(r"wAccelerometer, wGyroscope, wBarometer: no samples since 11\.95 s; the step "
                                       r"ending at \d+\.\d\d s and those after it", held[0]), tr.warnings
    assert not [w for w in Tracker(root / "bundle", max_lag_s=float("inf")).warnings]


def test_a_foot_only_stream_names_the_option_and_sensors_without_the_waist_mean_foot_only(root, walk):
    foot = walk.copy()
    for n in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del foot.streams[n]
    with pytest.raises(DataError, match=r"^w(Accelerometer|Gyroscope): no samples at all .*: for a foot-only "
                                        r"stream pass units=\('foot',\) to Tracker"):
        replay(Tracker(root / "bundle"), foot, 0.37)
    a = Tracker(root / "bundle", sensors=list(foot.streams))
    assert a.units == ("foot",)
    b = Tracker(root / "bundle", units=("foot",), sensors=list(foot.streams))
    sa, sb = replay(a, foot, 0.37), replay(b, foot, 0.37)
    assert [(st.x, st.y, st.classes) for st in sa] == [(st.x, st.y, st.classes) for st in sb] and len(sa) >= 20
    assert Tracker(root / "bundle", sensors=list(walk.streams)).units == ("foot", "waist")


def test_a_tracker_is_not_picklable_and_a_bundle_is_shared_by_trackers_in_threads(root, walk):
    """What docs/deploying.md "Runtime API" says: no snapshot (the ONNX sessions), one Tracker per thread with
    one shared Bundle (onnxruntime's run is thread-safe) gives each thread the steps of a lone tracker."""
    bundle = load_bundle(root / "bundle")
    tr = Tracker(bundle)
    with pytest.raises(TypeError):
        pickle.dumps(tr)
    sessions = [synthetic_session(24, seed=k, name=f"w{k}", turn_rad_per_step=0.1 * k) for k in range(4)]
    want = [[(st.end_s, st.x, st.y, st.classes) for st in replay(Tracker(bundle), s, 0.25)] for s in sessions]
    got: dict[int, list] = {}

    def work(k):
        got[k] = [(st.end_s, st.x, st.y, st.classes) for st in replay(Tracker(bundle), sessions[k], 0.25)]

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert [got[k] for k in range(4)] == want


def _doc_example() -> str:
    text = DOCS.read_text()
    m = re.search(r"<!-- example: tests/test_runtime_input_e29.py -->\n```python\n(.*?)```", text, re.S)
    assert m, "the embedding example of docs/deploying.md is gone"
    return m.group(1)


def test_the_embedding_example_of_the_docs_runs(root, walk, tmp_path):
    code = _doc_example()
    assert len(code.strip().splitlines()) <= 22
    assert 'BUNDLE = "out/bundle/u1"' in code and 'SESSION = "out/sim/D_u1"' in code
    write_session(walk, tmp_path / "walk")
    code = code.replace('"out/bundle/u1"', repr(str(root / "bundle"))).replace('"out/sim/D_u1"',
                                                                                repr(str(tmp_path / "walk")))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.strip().splitlines()
    assert len(lines) >= 21 and re.match(r"\s*\d+\.\d\d s .* m at \(", lines[0]), out.stdout
    ref = replay(Tracker(root / "bundle"), walk, 0.37)
    assert lines[-1] == f"{len(ref)} steps, final position ({ref[-1].x:.2f}, {ref[-1].y:.2f}, {ref[-1].z:.2f}) m"


def test_a_push_refused_for_its_rate_changes_nothing(root, walk):
    """E29's all-or-nothing also for a stream whose learned rate ``resample=False`` refuses: the probe of its earlier
    pushes stays (before: the refusal came after the input stage had taken the probe, so the state changed)."""
    g = walk.streams["fGyroscope"]
    t = g.t[0] + np.arange(40) / 50.0  # 50 Hz for a 20 Hz bundle
    v = np.repeat(g.values[:1], 40, axis=0)
    tr = Tracker(root / "bundle", resample=False)
    tr.push({"fGyroscope": (t[:3], v[:3])})  # too few to learn the rate: held by the probe
    before = _state(tr)
    assert before[1] == {"fGyroscope": 1}
    with pytest.raises(DataError, match=r"fGyroscope is sampled at 50 Hz but bundle .* was trained at 20 Hz"):
        tr.push({"fGyroscope": (t[3:], v[3:])})
    assert _state(tr) == before


def test_one_sample_pushes_take_the_general_checks_when_not_plainly_finite(root, walk):
    """E17's one-sample path tests finiteness on the sum of the values: a NaN or inf anywhere is the one-line error,
    and finite values whose sum overflows take the general path (refused there by B435's range check since session
    43: they are beyond any sensor's range)."""
    chunks = per_timestamp(walk)
    tr = Tracker(root / "bundle")
    for c in chunks[:100]:
        tr.push(c)
    t, v = chunks[100]["fAccelerometer"]
    for bad_t, bad_v in ((np.array([np.nan]), v), (t, np.array([[1.0, 2.0, np.inf]])),
                         (t, np.array([[np.inf, -np.inf, 1.0]]))):
        before = _state(tr)
        with pytest.raises(DataError, match=r"^fAccelerometer: pushed samples contain NaN/inf"):
            tr.push({"fAccelerometer": (bad_t, bad_v)})
        assert _state(tr) == before
    before = _state(tr)  # finite values whose sum overflows take the general path, which refuses them since B435
    with pytest.raises(DataError, match=r"^fAccelerometer \(pushed to the Tracker\): 1 sample\(s\) with a value "
                                        r"beyond any accelerometer's range"):
        tr.push({"fAccelerometer": (t, np.array([[1e308, 1e308, 0.0]]))})
    assert _state(tr) == before
