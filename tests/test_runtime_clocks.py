"""Decision L177: the live two-unit ``Tracker`` checks the foot and waist clocks as ``pdrlearn track`` / ``run`` do
(L161, L170): the same detectors (their online processors, now numpy-only in ``pdrlearn.kernels.step_events``) and
the same estimate, on the pushed samples; one warning; ``waist_clock_offset_s`` moves a known offset off."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.session import Stream
from pdrlearn.kernels.step_events import NumpyLowpass, numpy_delay_s
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.clocks import ACCEL, FORCE, PLL
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.signal.filters import CausalLowpass, lowpass_delay_s
from pdrlearn.sim import simulate
from pdrlearn.steps.align import align_units
from pdrlearn.steps.detectors import AccelForceStepDetector, AccelStepDetector, PLLStepDetector

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # foot + waist units


def _shifted(session, dt: float):
    """The waist clock read ``dt`` s later (as tests/test_unit_clocks.py)."""
    s = session.copy()
    for n, st in list(s.streams.items()):
        if st.placement == "waist":
            s.streams[n] = Stream(n, st.t + dt, st.values)
    return s


@pytest.fixture(scope="module")
def walk():
    logging.disable(logging.WARNING)
    try:
        return simulate("walk", 1796, length_m=40, rate_hz=50.0)  # L161 / L170's test walk
    finally:
        logging.disable(logging.NOTSET)


def _run(session, chunk_s: float, **kw):
    tr = Tracker(load_bundle(BUNDLE), **kw)
    streams = {n: (st.t, st.values) for n, st in session.streams.items() if len(st)}
    for push in replay_chunks(streams, chunk_s):
        tr.push(push)
    tr.flush()
    return tr, [w for w in tr.warnings if "decision L161" in w]


def test_the_runtime_detector_settings_are_the_detectors_defaults():
    assert AccelStepDetector().get_params() == ACCEL
    assert AccelForceStepDetector().get_params() == FORCE
    assert PLLStepDetector().get_params() == PLL


@pytest.mark.parametrize("order", [2, 3])
def test_the_numpy_lowpass_is_the_causal_lowpass(order):
    x = np.random.default_rng(order).normal(size=(500, 3)).cumsum(axis=0)
    a, b = CausalLowpass(3.0, 50.0, order=order), NumpyLowpass(3.0, 50.0, order=order)
    got = np.concatenate([b.push(x[i:i + k]) for i, k in ((0, 1), (1, 37), (38, 462))])
    np.testing.assert_allclose(got, a.push(x), rtol=0, atol=1e-9)
    assert numpy_delay_s(5.0, 100.0, order=order) == pytest.approx(lowpass_delay_s(5.0, 100.0, order=order),
                                                                    abs=1e-12)


@pytest.mark.parametrize("chunk_s", [0.02, 0.7, 2.0])  # 2 s: the first push holds 100 foot samples
def test_the_live_tracker_checks_the_clocks_as_run_does(walk, chunk_s):
    """Clean: quiet, and at flush the estimate is the offline one on the same samples (align_units, L161/L170);
    waist clock +0.3 s: one L161 line naming waist_clock_offset_s, the final estimate again the offline one;
    with that offset given the waist samples are moved onto the foot clock: quiet, and the track comes back."""
    shifted = _shifted(walk, 0.3)
    clean, w_clean = _run(walk, chunk_s)
    off, w_off = _run(shifted, chunk_s)
    assert not w_clean
    assert clean.clock_offset["offset_s"] == pytest.approx(align_units(walk)[0], abs=1e-9)
    (line,) = w_off
    assert "+0.2" in line and "waist_clock_offset_s=0.2" in line and "decision L161" in line
    offline = align_units(shifted)[0]
    assert off.clock_offset["offset_s"] == pytest.approx(offline, abs=1e-9)
    assert offline == pytest.approx(0.25, abs=0.05)  # L170's reading of this walk
    fixed, w_fixed = _run(shifted, chunk_s, waist_clock_offset_s=offline)
    assert not w_fixed and abs(fixed.clock_offset["offset_s"]) < 0.2
    assert math.dist(fixed.position[:2], clean.position[:2]) < 0.5 * math.dist(off.position[:2], clean.position[:2])
    quiet, w_quiet = _run(shifted, chunk_s, clock_check=False)
    assert not w_quiet and quiet.clock_offset is None
    assert tuple(quiet.position) == tuple(off.position)  # the check changes no step


def test_the_line_names_the_whole_offset_when_one_was_given(walk):
    """A waist clock 0.6 s late and 0.3 s of it given: the check sees the 0.3 s left (about 0.25, as above) and
    names the offset that fixes it, the given one plus the one seen (not the rest alone)."""
    tr, (line,) = _run(_shifted(walk, 0.6), 0.7, waist_clock_offset_s=0.3)
    named = float(line.split("waist_clock_offset_s=")[1].split(")")[0])
    assert named == pytest.approx(0.3 + tr.clock_offset["offset_s"], abs=0.02)
    assert named == pytest.approx(0.55, abs=0.05)


def test_the_check_holds_one_block_after_its_line(walk):
    """After the line the foot samples still go through the detector (not held to the flush: bounded state)."""
    from pdrlearn.runtime.clocks import BLOCK_SAMPLES

    tr = Tracker(load_bundle(BUNDLE))
    s = _shifted(walk, 0.3)
    held, warned_at = [], None
    for i, push in enumerate(replay_chunks({n: (st.t, st.values) for n, st in s.streams.items() if len(st)}, 0.5)):
        tr.push(push)
        if tr._clock.warned:
            warned_at = i if warned_at is None else warned_at
            held.append(tr._clock._held["fAccelerometer"].n)
    assert warned_at is not None and len(held) >= 10  # the line came while walking, pushes followed
    assert max(held) < BLOCK_SAMPLES + 0.5 * 50 + 1  # a block and one push at 50 Hz at the most
    tr.flush()
    assert tr.clock_offset["offset_s"] == pytest.approx(align_units(s)[0], abs=1e-9)  # the end as before


def test_a_foot_only_tracker_has_no_clock_check(walk):
    tr, lines = _run(walk, 0.5, units=("foot",))
    assert not lines and tr.clock_offset is None


@pytest.mark.parametrize(("kw", "match"), [
    ({"clock_check": "yes"}, r"^clock_check='yes' must be True or False$"),
    ({"waist_clock_offset_s": "0.3"}, r"^waist_clock_offset_s='0.3' must be the waist clock's offset in seconds"),
    ({"waist_clock_offset_s": float("nan")}, r"^waist_clock_offset_s=nan must be"),
    ({"waist_clock_offset_s": 0.3, "units": ("foot",)}, r"^waist_clock_offset_s=0.3: the tracker follows foot only"),
])
def test_bad_clock_arguments_are_one_line(kw, match):
    with pytest.raises(DataError, match=match):
        Tracker(load_bundle(BUNDLE), **kw)
