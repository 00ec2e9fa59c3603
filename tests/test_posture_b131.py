"""Decision B131 (session 21's responder trial, finding 6): a foot pitched (nearly) vertical at rest MID-session
(kneeling, crawling) is a posture, not a wrong foot frame: ``Tracker.push`` (``pdrlearn run``) and
``track --streaming`` skip those strides with one warning and keep tracking; a session that STARTS so is still
refused (the frame cannot be judged)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, synthetic_session, trained_dirs

PITCH = np.radians(88.0)  # toes down: the declared forward axis x within 2 deg of the vertical


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def _pitched(a: float, b: float):
    """The 24-step synthetic walk with the foot unit's readings pitched by PITCH about its lateral axis (z; thesis
    foot frame: x forward, y up) in ``a``-``b`` s: the same motion, the foot toes-down."""
    s = synthetic_session(24, seed=11, name="kneel")
    c, n = np.cos(PITCH), np.sin(PITCH)
    rot = np.array([[c, -n, 0.0], [n, c, 0.0], [0.0, 0.0, 1.0]])
    for name in ("fAccelerometer", "fGyroscope"):
        st = s.streams[name]
        m = (st.t >= a) & (st.t < b)
        st.values[m] = st.values[m] @ rot.T
    return s


def test_a_mid_session_posture_is_skipped_with_one_warning(root):
    s = _pitched(10.0, 14.0)
    tr = Tracker(root / "bundle")
    steps = replay(tr, s, 1.0)  # refused with "the declared forward axis points (nearly) vertically" before B131
    b131 = [w for w in tr.warnings if "decision B131" in w]
    assert len(b131) == 1 and "skipped" in b131[0], tr.warnings
    assert 20 - 5 <= len(steps) < 24 and any(st.start_s > 14.0 for st in steps)  # tracking goes on after it
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    # one mechanism: the same strides skipped (E154 also keeps the classifier's own B131 line about those steps'
    # missing foot channels, which it logged before and now lands in info too)
    assert [w for w in res.info["warnings"] if "decision B131" in w and "skipped" in w] == b131
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)


def test_a_session_that_starts_pitched_is_still_refused(root):
    s = _pitched(0.0, 30.0)
    with pytest.raises(DataError, match="vertically"):
        replay(Tracker(root / "bundle"), s, 1.0)
    with pytest.raises(DataError, match="vertically"):
        get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
