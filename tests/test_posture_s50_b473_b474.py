"""Decisions B473 / B474 (session 50, FD, trial s50t1 F2): a foot resting pitched more than 45 deg from its first
stride's rest is B131's posture (kneeling, crawling) for as long as it lasts: skipped live and by ``track
--streaming``, one line (B473's absolute 60 deg was not adopted: a real instep mount rests at 72 deg on stairs)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from pdrlearn.kernels.window import level_reference, pitched_from, rest_pitch_deg, stride_rest_pitch

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
FWD = np.array([1.0, 0.0, 0.0])  # the simulator's foot frame: x forward, y up, z right


def _rest(pitch_deg: float, n: int = 40):
    th = math.radians(pitch_deg)
    t = np.arange(n) / 20.0
    acc = np.tile([-9.81 * math.sin(th), 9.81 * math.cos(th), 0.0], (n, 1))
    return t, acc, np.zeros((n, 3))


@pytest.mark.parametrize("pitch", [0.0, 30.0, 59.0, 80.0, -80.0])
def test_the_kernel_reads_the_first_rest_s_pitch(pitch):
    t, acc, gyr = _rest(pitch)
    assert rest_pitch_deg(t, acc, gyr, FWD, rest_search_s=0.25) == pytest.approx(abs(pitch), abs=1e-6)


def test_a_posture_is_a_pitch_far_from_the_most_level_rest_so_far():
    assert not pitched_from(80.0, None)  # the first stride: its frame is B131's question
    assert pitched_from(80.0, 5.0) and pitched_from(65.0, 5.0)  # a boot crawling from a level walk
    assert not pitched_from(72.3, 49.4)  # gaitmap_stairs_down_left: an instep mount on a stair going down (B473's miss)
    assert not pitched_from(30.0, 0.0) and not pitched_from(float("nan"), 0.0)
    assert not pitched_from(5.0, 70.0)  # one-sided: a walk after a session's kneeling start is tracked
    ref = None
    for p in (70.0, 5.0, float("nan"), 20.0):
        ref = level_reference(ref, p)
    assert ref == 5.0 and pitched_from(80.0, ref)  # then the crawl after that walk is the posture


def _crawl(session, t0: float, t1: float, pitch_deg: float = 80.0):
    """The trial s50t1 way: the foot's IMU over [t0, t1] replaced by a crawl: pitched toes-down after a 1 s tilt,
    dragged 0.3 m every 1.2 s, level again in the last second (the waist and the truth unchanged)."""
    acc_s, gyr_s = session.streams["fAccelerometer"], session.streams["fGyroscope"]
    t = acc_s.t
    m = (t >= t0) & (t <= t1)
    tt, d = t[m] - t0, t1 - t0
    theta = math.radians(pitch_deg) * np.where(tt < 1, tt, np.where(tt > d - 1, d - tt, 1.0))
    ph = np.mod(tt - 1.0, 1.2)
    drag = (tt > 1.3) & (tt < d - 1.3) & (ph < 0.6)
    theta = theta + np.where(drag, math.radians(10) * np.sin(np.pi * ph / 0.6) ** 2, 0.0)
    af = np.where(drag, 0.3 * 2 * np.pi / 0.36 * np.sin(2 * np.pi * ph / 0.6), 0.0)
    acc_s.values[m] = np.column_stack([af * np.cos(theta) - 9.81 * np.sin(theta),
                                       af * np.sin(theta) + 9.81 * np.cos(theta), np.zeros_like(tt)])
    gyr_s.values[m] = np.column_stack([np.zeros_like(tt), np.zeros_like(tt), -np.gradient(theta, tt)])


@pytest.fixture(scope="module")
def crawled():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route("stand:3, straight:6, stand:30, straight:6, stand:3"), UserProfile.from_seed(5032),
                      seed=5032, scenario="route")
    st = s.steps
    e, b = st["end_s"].to_numpy(), st["start_s"].to_numpy()
    k = int(np.argmax(b[1:] - e[:-1]))
    span = (float(e[k]) + 3.0, float(b[k + 1]) - 3.0)
    _crawl(s, *span)
    return s, span


def test_the_live_tracker_skips_the_whole_crawl_as_track_streaming_does(crawled, caplog):
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.track.plasys import track_plasys
    from tests.runtime_helpers import time_chunks

    s, (a, b) = crawled
    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(s.streams))
    with caplog.at_level("WARNING", logger="pdrlearn"):
        steps = [st for _, c in time_chunks(s, 1.0) for st in tr.push(c)] + list(tr.flush())
    inside = [st for st in steps if st.end_s > a and st.start_s < b]
    assert len(inside) <= 1  # before B473: the crawl's cycles were strides (only the tilt's was skipped)
    lines = [w for w in tr.warnings if "(decision B131)" in w]
    assert len(lines) == 1
    n = int(re.match(r"(\d+) stride\(s\)", lines[0]).group(1))
    assert n >= 15  # the drags of a 24 s crawl, one 1.2 s apart
    logged = [r.getMessage() for r in caplog.records if "(decision B131)" in r.getMessage()]
    assert logged[-1].endswith(lines[0])  # the whole span logged at the flush, not only the first stride's
    off = track_plasys(s, streaming=True)
    assert len(off.steps) == len(steps)
    assert [w for w in off.info["warnings"] if "(decision B131)" in w] == lines  # the same line


def test_stride_rest_pitch_reads_the_buffered_streams(crawled):
    s, (a, b) = crawled
    stream = {n: (st.t, st.values) for n, st in s.streams.items()}.__getitem__
    assert stride_rest_pitch(stream, FWD, a + 5.4, a + 6.6, rest_search_s=0.25) > 70.0  # at a rest (B474 amended)
    assert np.isnan(stride_rest_pitch(stream, FWD, a + 5.0, a + 6.2, rest_search_s=0.25))  # starts mid-drag: no rest
    assert stride_rest_pitch(stream, FWD, 3.0, 4.2, rest_search_s=0.25) < 20.0
