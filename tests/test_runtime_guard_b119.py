"""The streaming tracker's robustness, from the trial of an embedded engineer (session 20):

- B119: ``Tracker.push`` checks the values' units as ``pdrlearn run`` does on files (before: a foot accelerometer in
  g gave 9.15 m for 89.75 m, a waist gyroscope in deg/s a 36 m error, swapped units 6.65 m, all without a word);
- B120: a frozen sensor (bit-identical samples for seconds) is warned about, live and offline;
- B121: an optional stream that stops does not stop the tracking (before: every push raised "step features are
  NaN" when the chosen model read the force sensor);
- B122: a push after which a required stream is found stopped is refused before any sample is taken;
- B123: an accelerometer reading zeros is named with its time (before: "gravity_rotation: gravity vector ...");
- E63: ``Tracker.window`` refuses a step whose samples were trimmed (before: garbage);
- E64: a gap over 1 s in a waist stream is not called "bridged up to 1 s";
- E65: the held-values warning says why they are held (before: "max_lag_s = inf" when nobody set it).
"""

from __future__ import annotations

import logging
import math
import re

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import Stream, read_session, write_session
from pdrlearn.kernels.units import FROZEN_S, frozen_spans
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import per_timestamp, replay, synthetic_session, trained_dirs, without

DEG = 180.0 / math.pi


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=21, name="walk", turn_rad_per_step=0.3)


def _scaled(s, name: str, k: float):
    c = s.copy()
    c.streams[name] = Stream(name, s.streams[name].t, s.streams[name].values * k)
    return c


def _state(tr: Tracker) -> tuple:
    return ({n: (len(r), r.last) for n, r in tr._buf.items()}, tr._latest, tr.n_steps, len(tr._pending))


@pytest.mark.parametrize(("name", "k", "match"), [
    ("fAccelerometer", 1 / 9.80665, r"^fAccelerometer \(its first 5\.0 s pushed to the Tracker, decision B119\): "
                                    r"median \|acc\| is 1\.0\d, which looks like units of g; multiply by 9\.80665"),
    ("fAccelerometer", 1000 / 9.80665, r"^fAccelerometer .*looks like raw counts or mm/s\^2"),
    ("fGyroscope", DEG, r"^fGyroscope .*beyond a 2000 deg/s gyroscope in rad/s; the values look like deg/s"),
    ("wGyroscope", DEG, r"^wGyroscope .*beyond a 2000 deg/s gyroscope in rad/s; the values look like deg/s"),
])
def test_a_stream_in_the_wrong_unit_is_refused_naming_the_sensor_and_nothing_is_taken(root, walk, name, k, match):
    tr = Tracker(root / "bundle")
    chunks = per_timestamp(_scaled(walk, name, k))
    n = 0
    with pytest.raises(DataError, match=match):
        for n, c in enumerate(chunks):  # noqa: B007 - n: the push that raised
            before = _state(tr)
            tr.push(c)
    assert n < 20 * 12  # within its first windows (20 Hz)
    assert _state(tr) == before  # the refused push took nothing (E29)
    # the right units: not refused (the same session, every sample)
    ok = Tracker(root / "bundle")
    assert [st for c in per_timestamp(walk) for st in ok.push(c)] + ok.flush()


def test_swapped_foot_and_waist_streams_are_refused(root, walk):
    s = walk.copy()
    for a, b in (("fAccelerometer", "wAccelerometer"), ("fGyroscope", "wGyroscope")):
        s.streams[a] = Stream(a, walk.streams[b].t, walk.streams[b].values)
        s.streams[b] = Stream(b, walk.streams[a].t, walk.streams[a].values)
    with pytest.raises(DataError, match=r"^fGyroscope, wGyroscope: the foot and waist streams look swapped: the foot "
                                        r"unit turns at \d+ deg/s .*\(decisions B91, B119\)"):
        replay(Tracker(root / "bundle"), s, 1.0)
    assert replay(Tracker(root / "bundle", check_input=False), s, 1.0) is not None  # the option skips the checks


def test_a_frozen_sensor_is_warned_once_naming_it_and_its_time(root, walk, tmp_path, caplog):
    s = walk.copy()
    st = walk.streams["fGyroscope"]
    v = st.values.copy()
    k = (st.t >= 8.0) & (st.t < 12.0)
    v[k] = v[np.flatnonzero(k)[0] - 1]  # the last value before 8 s, repeated for 4 s
    s.streams["fGyroscope"] = Stream("fGyroscope", st.t, v)
    for chunk_s in (None, 0.5, 3.0):  # sample by sample, and chunks
        tr = Tracker(root / "bundle")
        if chunk_s is None:
            [tr.push(c) for c in per_timestamp(s)]
        else:
            replay(tr, s, chunk_s)
        frozen = [w for w in tr.warnings if "frozen" in w]
        assert len(frozen) == 1, (chunk_s, tr.warnings)
        assert re.match(r"^fGyroscope: \d+ identical consecutive samples \(.*\) since 7\.95 s \([2-4]\.\d s so far\): "
                        r"the sensor looks frozen .*decision B120", frozen[0]), frozen
    tr = Tracker(root / "bundle")
    replay(tr, walk, 0.5)
    assert not [w for w in tr.warnings if "frozen" in w]
    # offline: one warning naming the file and the whole span
    write_session(s, tmp_path / "s")
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        read_session(tmp_path / "s")
    lines = [r.getMessage() for r in caplog.records if "frozen" in r.getMessage()]
    assert len(lines) == 1 and re.match(r".*fGyroscope\.csv: 81 identical consecutive samples \(.*\) for 4\.0 s "
                                        r"\(7\.95-11\.95 s\)", lines[0]), lines


def test_frozen_spans_of_the_longest_run_only_beyond_the_limit():
    t = np.arange(100) * 0.05
    v = np.random.default_rng(1).normal(size=(100, 3))
    v[10:60] = v[10]  # 50 samples: 2.45 s
    v[70:75] = v[70]
    assert frozen_spans(t, v) == [(0.5, 2.95, 50)]
    assert FROZEN_S == 2.0 and frozen_spans(t, v, 3.0) == []


def test_an_optional_stream_that_stops_does_not_stop_the_tracking(root, walk):
    s = without(walk, 10.0, 1e9, names=("fForceA", "fForceB"))
    ref = Tracker(root / "bundle_all")
    assert ref.classifiers["length"].unit == "fused"  # the chosen length model reads the force sensors
    want = replay(ref, walk, 0.5)
    tr = Tracker(root / "bundle_all")
    got = replay(tr, s, 0.5)  # before: every push after ~13 s raised "step features are NaN"
    assert len(got) == len(want) >= 20
    assert (tr.classifiers["length"].method, tr.classifiers["length"].unit) == ("svm", "waist")
    assert [w for w in tr.warnings if re.match(r"fForceA, fForceB|fForce[AB] stopped: classified from now on as a "
                                               r"stream without it would be, with length svm/waist", w)], tr.warnings
    assert all(st.classes.get("length") for st in got)


def test_a_stopped_required_stream_is_refused_before_the_push_is_taken(root, walk):
    # a foot stream: a stopped waist stream pauses since decision E115 (tests/test_live_waist_gap_e115.py)
    s = without(walk, 10.0, 1e9, names=("fGyroscope",))
    tr = Tracker(root / "bundle")
    chunks = per_timestamp(s)
    with pytest.raises(DataError, match=r"^fGyroscope: no samples since 9\.95 s") as first:
        for c in chunks:
            before = _state(tr)
            tr.push(c)
    assert _state(tr) == before
    with pytest.raises(DataError) as again:  # before: "fAccelerometer: pushed timestamps are not increasing"
        tr.push(c)
    assert str(again.value) == str(first.value)


def test_the_held_values_warning_says_why_they_are_held(root, walk):
    s = without(walk, 12.0, 1e9, names=("wAccelerometer", "wGyroscope", "wBarometer"))
    tr = Tracker(root / "bundle", stream_ends_s={n: float(st.t[-1]) for n, st in walk.streams.items()})
    replay(tr, s, 0.37)  # the recording says the waist resumes: the steps wait, then flush() holds its values
    held = [w for w in tr.warnings if "last values held" in w]
    assert held and "(flush() at the end of the stream)" in held[0] and "inf" not in held[0], held
    tr = Tracker(root / "bundle", max_lag_s=math.inf)
    replay(tr, s, 0.37)
    assert "(max_lag_s = inf, decision E9)" in [w for w in tr.warnings if "last values held" in w][0]


def test_a_long_waist_gap_is_not_called_bridged_up_to_1_s(root, walk):
    tr = Tracker(root / "bundle", max_lag_s=math.inf)
    replay(tr, without(walk, 10.0, 11.5, names=("wGyroscope",)), 0.5)
    gap = [w for w in tr.warnings if "no samples for" in w]
    assert len(gap) == 1 and "up to 1 s" not in gap[0], gap
    assert re.match(r"wGyroscope: no samples for 1\.55 s \(9\.95-11\.50 s\); longer than 1 s in a stream whose gaps "
                    r"do not stop the strides \(B11 zeroes only a foot stream's; E64\): .*interpolated across the gap",
                    gap[0]), gap


def test_an_accelerometer_reading_zeros_is_named_with_its_time(root, walk):
    s = walk.copy()
    st = walk.streams["fAccelerometer"]
    s.streams["fAccelerometer"] = Stream("fAccelerometer", st.t, np.where(((st.t >= 10) & (st.t < 14))[:, None],
                                                                           0.0, st.values))
    with pytest.raises(DataError, match=r"^fAccelerometer reads 0 in \d+ of its \d+ samples of 1\d\.\d\d-1\d\.\d\d s: "
                                        r"the step \d+\.\d\d-\d+\.\d\d s has no gravity .*decision B123"):
        replay(Tracker(root / "bundle"), s, 0.5)


def test_the_window_of_a_trimmed_step_is_refused(root, walk):
    tr = Tracker(root / "bundle", buffer_s=2.0)
    steps, at_emission = [], {}
    for c in per_timestamp(walk):
        for st in tr.push(c):
            steps.append(st)
            at_emission[st.start_s] = tr.window(st.start_s, st.end_s)  # the documented use: in the same push
    assert len(steps) >= 15 and all(np.isfinite(W[1:]).any() for W in at_emission.values())
    first = steps[0]
    with pytest.raises(DataError, match=rf"^window\({first.start_s:.3f}, {first.end_s:.3f}\): the tracker holds "
                                        r"\w+ from \d+\.\d{3} to \d+\.\d{3} s only .*decision E63"):
        tr.window(first.start_s, first.end_s)


def test_a_refusal_at_flush_is_given_once_and_the_next_flush_ends_the_stream(root, walk):
    """Review 2: ``flush`` checked a stream shorter than GUARD_S and raised; every later ``flush`` raised again (the
    guard was kept), so D21's unused-fix line was never given."""
    short = without(_scaled(walk, "fAccelerometer", 1 / 9.80665), 3.0, 1e9)  # 3 s in g: the window never completes
    tr = Tracker(root / "bundle")
    tr.add_fix(100.0, 1.0, 1.0, accuracy_m=2.0)  # after the stream: unused
    for c in per_timestamp(short):  # the first 3 s: not judged while pushed (the window never completes)
        tr.push(c)
    with pytest.raises(DataError, match=r"^fAccelerometer \(its first 3\.0 s pushed to the Tracker.*units of g"):
        tr.flush()
    tr.flush()  # the stream ends: the refusal is not repeated
    # D21, once (E350's slow-walking line, also given at the end of the stream, may follow it)
    assert [w for w in tr.warnings if w.startswith("1 of 1 fixes not used")] != []
    assert sum(w.startswith("1 of 1 fixes not used") for w in tr.warnings) == 1


def test_a_foot_accelerometer_arriving_after_its_gyroscope_is_not_taken_as_movement():
    """Review 2: a gyroscope window whose accelerometer had not arrived was judged "in motion", so a still foot's
    ~0 rad/s was taken as its swing and the waist's first fast turn refused as swapped units (B91)."""
    from pdrlearn.kernels.units import WAIST_SWINGS
    from pdrlearn.runtime.guard import UnitGuard

    rng = np.random.default_rng(3)
    t = np.arange(0, 5.5, 0.01)
    still_g = rng.normal(0, 0.01, (len(t), 3))  # the foot stands
    still_a = np.array([0.0, 9.81, 0.0]) + rng.normal(0, 0.02, (len(t), 3))
    turn = np.column_stack([np.zeros(len(t)), np.zeros(len(t)), (WAIST_SWINGS + 1.0) * np.sin(2 * np.pi * t)])
    walk_a = np.array([0.0, 9.81, 0.0]) + rng.normal(0, 2.0, (len(t), 3))  # the waist walks and pivots
    g = UnitGuard(["fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"])
    first = {"fGyroscope": (t, still_g), "wAccelerometer": (t, walk_a), "wGyroscope": (t, turn)}
    g.take(first, g.check(first))  # the foot accelerometer's samples come later (another link)
    late = {"fAccelerometer": (t, still_a)}
    g.take(late, g.check(late))
    assert "fGyroscope" not in g.rates  # not judged in motion on a window without its accelerometer
    later = {"fGyroscope": (t + 5.5, still_g), "fAccelerometer": (t + 5.5, still_a),
             "wAccelerometer": (t + 5.5, walk_a), "wGyroscope": (t + 5.5, turn)}
    g.take(later, g.check(later))  # the foot still stands: still no B91 judgement, no refusal
    assert "fGyroscope" not in g.rates and g.rates["wGyroscope"] > WAIST_SWINGS


def _coarse_rest(seed: int = 0):
    """30 s of a unit lying still at 100 Hz: a 10-bit +-16 g accelerometer (31 mg/LSB, 1.5 mg noise: its reading
    repeats for seconds) and a gyroscope with 0.005 rad/s noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(0, 30, 0.01)
    lsb = 1 / 32
    acc = np.round((np.array([0.03, -0.02, 1.0]) + rng.normal(0, 0.0015, (len(t), 3))) / lsb) * lsb * 9.80665
    gyr = rng.normal(0, 0.005, (len(t), 3))
    return t, acc, gyr


def test_a_coarse_accelerometer_at_rest_is_not_called_frozen_live_or_offline(caplog):
    """Review 2 (B120 amended): the rule fired on a coarsely quantised accelerometer lying still (runs of one
    reading up to 8.1 s); a run is frozen only while the unit's other sensor shows it moving."""
    from pdrlearn.io.plasys import warn_frozen
    from pdrlearn.io.session import Session
    from pdrlearn.runtime.guard import FrozenWatch

    t, acc, gyr = _coarse_rest()
    assert max(b - a for a, b, _ in frozen_spans(t, acc)) > FROZEN_S  # the runs are there
    w = FrozenWatch()
    msgs = []
    for i in range(0, len(t), 25):
        for name, v in (("fAccelerometer", acc), ("fGyroscope", gyr)):
            w.note(name, t[i:i + 25], v[i:i + 25])
        msgs += [w.feed(n, t[i:i + 25], v[i:i + 25]) for n, v in (("fAccelerometer", acc), ("fGyroscope", gyr))]
    assert not any(msgs)
    s = Session(name="rest", streams={"fAccelerometer": Stream("fAccelerometer", t, acc),
                                      "fGyroscope": Stream("fGyroscope", t, gyr)})
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        warn_frozen(s)
    assert not [r for r in caplog.records if "frozen" in r.getMessage()]
    # the same accelerometer reading while the gyroscope turns (the unit moves): frozen, live and offline
    gyr_turn = gyr + np.array([0.0, 0.0, 1.5])
    w = FrozenWatch()
    w.note("fGyroscope", t, gyr_turn)
    frozen = np.tile(acc[0], (len(t), 1))
    assert w.feed("fAccelerometer", t, frozen).startswith("fAccelerometer: 3000 identical consecutive samples")
    s.streams["fGyroscope"] = Stream("fGyroscope", t, gyr_turn)
    s.streams["fAccelerometer"] = Stream("fAccelerometer", t, frozen)
    with caplog.at_level(logging.WARNING):
        warn_frozen(s)
    assert len([r for r in caplog.records if "frozen" in r.getMessage()]) == 1
