"""Decision E195 (session 36, trial T2 finding 5): the per-sample kernels do not build whole-session lists of Python
floats, and a sensor stream does not keep its file's timestamp column alive; the track's numbers are unchanged."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main


def test_values_and_rows_give_the_same_floats_as_lists_e195():
    from pdrlearn.kernels.samples import Rows, values

    rng = np.random.default_rng(8903)
    x = np.concatenate([rng.normal(size=1000) * 10.0 ** rng.integers(-300, 300, 1000), [0.0, -0.0, np.inf]])
    got = list(values(x))
    assert [v.hex() for v in got] == [v.hex() for v in x.tolist()] and all(type(v) is float for v in got)
    assert list(values(x[::3])) == x[::3].tolist()  # a strided view
    b = rng.random(50) > 0.5
    assert list(values(b)) == b.tolist() and all(type(v) is bool for v in values(b))
    assert list(values(np.arange(5))) == [0, 1, 2, 3, 4]  # another dtype: tolist()
    r = Rows(4)
    for row in x[:1000].reshape(-1, 4).tolist():
        r.append(tuple(row))
    np.testing.assert_array_equal(r.to_array(), np.array(x[:1000].reshape(-1, 4).tolist()))


def test_madgwick_memory_is_bounded_per_sample_e195():
    """The Madgwick filter on 100 000 samples: its peak allocation was about 350 bytes a sample (six lists of
    Python floats and a list of 4-tuples, 126 MB per recorded hour at 100 Hz); now the columns and the output as
    doubles."""
    from pdrlearn.kernels.ahrs import madgwick_imu

    n = 100_000
    rng = np.random.default_rng(8904)
    gyr, acc = rng.normal(size=(n, 3)) * 0.1, rng.normal(size=(n, 3)) + [0.0, 0.0, 9.81]
    tracemalloc.start()
    try:
        q = madgwick_imu(np.array([1.0, 0.0, 0.0, 0.0]), gyr, acc, 0.01, gain=0.033)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert q.shape == (n, 4) and q.dtype == np.float64 and q.flags.c_contiguous
    assert peak / n < 160, f"{peak / n:.0f} bytes a sample"


def test_stream_values_do_not_hold_the_file_array_e195(tmp_path):
    from pdrlearn.io import read_session

    sim = tmp_path / "s"
    assert main(["simulate", "--route", "straight:8", "-u", "8905", "-o", str(sim)]) == 0
    s = read_session(sim)
    for st in s.streams.values():
        base = st.values if st.values.base is None else st.values.base
        assert base.size == st.values.size, f"{st.name}: its values keep an array of {base.shape}"


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    sim = tmp_path_factory.mktemp("e195") / "s"
    assert main(["simulate", "--route", "stand:3, straight:20, turn:180, straight:20, stand:3", "-u", "8906",
                 "-o", str(sim)]) == 0
    return sim


def _in_memory(sim) -> dict[str, pd.DataFrame]:
    """The foot track's steps and trajectory and the waist detectors' events, in memory (not CSVs written at 10
    digits and read back, review R4): every kernel that takes ``values`` runs (burst, contact, Madgwick, PLL,
    pelvic gyro)."""
    from pdrlearn.io import read_session
    from pdrlearn.steps import get_detector
    from pdrlearn.track.plasys import track_plasys

    session = read_session(sim)
    res = track_plasys(session)
    out = {"steps": res.steps, "trajectory": res.trajectory}
    for name in ("accel", "pll", "pelvic-gyro"):
        out[name] = get_detector(name).detect(session)
    return out


def test_track_outputs_equal_with_and_without_lists_e195(small, monkeypatch):
    """Bit-identical: the track and the detectors with the kernels fed lists (as before E195) and with the arrays'
    own buffers, compared exactly in memory (review R4)."""
    after = _in_memory(small)
    import pdrlearn.kernels.ahrs as ahrs
    import pdrlearn.kernels.contact as contact
    import pdrlearn.kernels.step_events as step_events

    class ListRows(list):
        def __init__(self, width):
            super().__init__()
            self.width = width

        def to_array(self):
            return np.array(self, dtype=float).reshape(-1, self.width)

    fed = []

    def as_list(x):
        fed.append(1)
        return np.asarray(x).tolist()

    for mod in (ahrs, contact, step_events):
        monkeypatch.setattr(mod, "values", as_list)
    monkeypatch.setattr(ahrs, "Rows", ListRows)
    before = _in_memory(small)
    assert fed, "the monkeypatched kernels did not run"
    for name in after:
        assert len(after[name]) > 0, name
        pd.testing.assert_frame_equal(before[name], after[name], check_exact=True)
