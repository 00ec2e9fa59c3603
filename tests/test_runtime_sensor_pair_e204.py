"""Decision E204 (session 37, trial T1 finding 7): ``runtime.SensorPair`` pairs an accelerometer and a gyroscope
delivered as two streams with their own stamps (Android) on the accelerometer's stamps for ``WaistTracker.push``,
as the offline pipelines interpolate the gyroscope; the chunking of either stream does not matter."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime import SensorPair, WaistTracker
from tests.test_runtime_waist_repeats_e203 import walk  # noqa: F401  (the module's fixture: user 9216, a bundle)

SHIFT_S = 1.3e-3  # the gyroscope's clock after the accelerometer's (trial T1's phone)


def _offline(w):
    tg = w["t"] + SHIFT_S
    keep = (w["t"] >= tg[0]) & (w["t"] <= tg[-1])
    t = w["t"][keep]
    return t, w["acc"][keep], np.column_stack([np.interp(t, tg, w["gyr"][:, j]) for j in range(3)])


def _paired(w, n_acc: int, n_gyr: int):
    pair, out = SensorPair(), []
    tg = w["t"] + SHIFT_S
    ia = ig = 0
    while ia < len(w["t"]) or ig < len(tg):
        if ig < len(tg):
            pair.push_gyr(tg[ig:ig + n_gyr], w["gyr"][ig:ig + n_gyr])
            ig += n_gyr
        if ia < len(w["t"]):
            pair.push_acc(w["t"][ia:ia + n_acc], w["acc"][ia:ia + n_acc])
            ia += n_acc
        out.append(pair.take())
    return pair, out


@pytest.mark.parametrize(("n_acc", "n_gyr"), [(37, 53), (100, 7), (1, 1)])
def test_paired_streams_equal_the_offline_interpolation(walk, n_acc, n_gyr):  # noqa: F811
    pair, out = _paired(walk, n_acc, n_gyr)
    t, a, g = (np.concatenate([o[k] for o in out]) for k in range(3))
    t0, a0, g0 = _offline(walk)
    assert np.array_equal(t, t0) and np.array_equal(a, a0) and np.allclose(g, g0, atol=1e-12)
    assert pair.n_dropped == 1  # the accelerometer's first sample, 1.3 ms before the gyroscope's first


def test_a_tracker_fed_by_the_pair_tracks_as_the_interpolated_arrays(walk):  # noqa: F811
    one = WaistTracker(walk["bundle"])
    ref = one.push(*_offline(walk)) + one.flush()
    tr = WaistTracker(walk["bundle"])
    got = []
    for o in _paired(walk, 37, 53)[1]:
        got += tr.push(*o)
    got += tr.flush()
    assert [s.t for s in got] == [s.t for s in ref] and len(ref) > 10


def test_a_wrong_shape_is_one_line():
    with pytest.raises(DataError, match=r"SensorPair.push_gyr: expected values of shape \(2, 3\)"):
        SensorPair().push_gyr([0.0, 0.01], np.zeros((2, 2)))


def test_a_stamp_that_goes_back_or_a_non_number_is_one_line_and_keeps_nothing():
    """E204 amended (review R3 finding 4): a gyroscope batch pushed out of order made take() drop 11 accelerometer
    samples the gyroscope covered (``n 0 dropped 11``); now the step back is refused with one DataError line and
    nothing is kept, so the batches pushed in order pair every sample. A late accelerometer sample is refused the
    same way (it was dropped and counted), and a string is a DataError (it was a bare ValueError)."""
    tg, ta = np.arange(0.003, 0.3, 0.01), np.arange(0.0, 0.3, 0.01)
    three = np.ones((10, 3))
    p = SensorPair()
    p.push_gyr(tg[10:20], three)
    with pytest.raises(DataError, match=r"push_gyr: timestamps must not go back .* sample 0 of this push "
                                        r"\(t=0\.003000 s\) is before the previous push's last") as e:
        p.push_gyr(tg[0:10], three)
    assert "\n" not in str(e.value)
    p.push_acc(ta[11:20], three[:9])  # 0.11-0.19 s, all inside the gyroscope's 0.103-0.193 s
    t, _, _ = p.take()
    assert len(t) == 9 and p.n_dropped == 0
    with pytest.raises(DataError, match=r"push_acc: .* sample 2 of this push \(t=0\.050000 s\) is before sample 1"):
        p.push_acc(np.r_[ta[20], ta[21], ta[5]], np.ones((3, 3)))
    with pytest.raises(DataError, match=r"push_acc: .*must be numbers"):
        p.push_acc("a", [1, 2, 3])
    assert p.n_dropped == 0
