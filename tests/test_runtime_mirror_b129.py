"""Decision B129: a foot gyroscope whose sign is reversed against its accelerometer (or data mirrored in one axis)
is found live as ``pdrlearn info`` finds it offline (D11): one numpy kernel (``kernels.handedness``), the live
tracker warning once after :data:`~pdrlearn.runtime.guard.LIVE_STRIDES` strides (before: 31.38 m for 89.75 m and a
height error, without a word)."""

from __future__ import annotations

import logging
import re

import numpy as np
import pytest

from pdrlearn.io import Stream, read_session
from pdrlearn.io.handedness import check_handedness, foot_handedness, unit_imu_arrays
from pdrlearn.kernels.handedness import mirror_log_ratios
from pdrlearn.runtime.guard import LIVE_STRIDES
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import replay, trained_dirs

LINE = (r"^the foot unit's fAccelerometer and fGyroscope turn like a left-handed \(mirrored\) pair: the end-of-stride "
        r"velocity error of the ZUPT integration is \d+\.\d times smaller with the gyroscope reversed \(median of "
        rf"{LIVE_STRIDES} strides pushed to the Tracker; decisions D11, B129\); the gyroscope's sign looks reversed "
        r".*negate the gyroscope's three values before pushing")


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk():
    """A simulated walk (the hand-made sessions of tests/runtime_helpers.py are not physically consistent, B119:
    their strides do not integrate to rest, either sign)."""
    from pdrlearn.sim import simulate

    return simulate("walk", 3, length_m=40)


def _negated(s, name: str = "fGyroscope", axes=slice(None)):
    c = s.copy()
    v = s.streams[name].values.copy()
    v[:, axes] *= -1.0
    c.streams[name] = Stream(name, s.streams[name].t, v)
    return c


@pytest.mark.parametrize("chunk_s", [0.5, 3.0])
def test_a_reversed_foot_gyroscope_is_warned_once_live_and_offline(root, walk, chunk_s, caplog):
    tr = Tracker(root / "bundle")
    replay(tr, walk, chunk_s)
    assert not [w for w in tr.warnings if "B129" in w], tr.warnings  # as recorded: no word
    for s in (_negated(walk), _negated(_negated(walk, "fAccelerometer", 1), axes=1)):  # reversed; mirrored in y
        tr = Tracker(root / "bundle")
        steps = replay(tr, s, chunk_s)
        lines = [w for w in tr.warnings if "B129" in w]
        assert len(lines) == 1 and re.match(LINE, lines[0]), tr.warnings
        assert len(steps) > LIVE_STRIDES  # the tracking goes on (a warning, as offline's info / track)
        h, msg = check_handedness(s, "foot")  # offline: the same verdict
        assert h.mirrored and msg.startswith("the foot unit's fAccelerometer and fGyroscope turn like a left-handed")


def test_check_input_false_skips_the_live_test(root, walk):
    tr = Tracker(root / "bundle", check_input=False)
    replay(tr, _negated(walk), 0.5)
    assert not [w for w in tr.warnings if "B129" in w]


def test_offline_result_unchanged_and_from_the_shared_kernel(caplog):
    """``pdrlearn info``'s numbers on a real foot recording are those before B129 (log ratio 3.146 over 33
    strides: scipy's start attitude replaced by the kernel's numpy one changes the 16th digit), and they are the
    median of the kernel's per-stride ratios."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.track.frame_inference import rest_to_rest

    with caplog.at_level(logging.ERROR):
        s = read_session("datasets/real/gaitmap_level_left")
    acc, gyr, fs = unit_imu_arrays(s, "foot")
    h = foot_handedness(acc, gyr, fs)
    assert h.segments == 33 and abs(h.log_ratio - 3.145964237893644) < 1e-9 and h.verdict == "right-handed"
    i0, i1 = rest_to_rest(inertial_stance(acc, gyr, fs), fs)
    r = mirror_log_ratios(acc, gyr, 1.0 / fs, i0, i1)
    assert float(np.median(r)) == h.log_ratio
    assert np.allclose(mirror_log_ratios(acc, -gyr, 1.0 / fs, i0, i1), -r)
