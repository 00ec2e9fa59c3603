"""Decisions E326 / E327 (session 51, I3): stance / swing per streamed stride on the lean runtime by L73's toe-off
kernel (moved to ``pdrlearn.kernels.toeoff``, numpy only), and the two feet's double support and stance / swing
symmetry indices by ``gait``'s per-cycle kernel (``pdrlearn.kernels.gait_values.cycle_support``)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.gait_values import cycle_support, stance_swing, symmetry_index_pct
from pdrlearn.kernels.toeoff import LiveToeOff, toe_off_times
from pdrlearn.runtime.gait import StrideGait, bout_end_rows, gait_summary, support_measures
from pdrlearn.runtime.tracker import Step
from pdrlearn.track.bilateral import cycle_table, merged_contacts
from pdrlearn.track.gait import streamed_gait_columns
from tests.lean_helpers import ROOT
from tests.runtime_helpers import gait_replay

BUNDLE = ROOT / "models" / "plasys-sim-default"


def _strides(n: int, fs: float, *, axis, t_first: float = 1.0, period: float = 1.1, seed: int = 0):
    """A foot gyroscope of ``n`` strides about ``axis`` (toe-up positive): rest, a push-off dip (toe-down) at 0.25 s
    into each stride, a swing peak at 0.5 s, rest; ``(t, gyr, start, end, ic, true toe-off)``."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, t_first + n * period + 1.0, 1.0 / fs)
    r = np.zeros(len(t))
    st = t_first + period * np.arange(n)
    tc = st + 0.25 + rng.uniform(-0.02, 0.02, n)
    for a, c in zip(st, tc, strict=True):
        r += -6.0 * np.exp(-0.5 * ((t - c) / 0.06) ** 2) + 5.0 * np.exp(-0.5 * ((t - (a + 0.5)) / 0.08) ** 2)
    u = np.asarray(axis, float) / np.linalg.norm(axis)
    gyr = np.outer(r, u) + 0.05 * rng.standard_normal((len(t), 3))
    return t, gyr, st, st + 0.75, st + 0.7, tc


def test_live_toe_off_is_the_offline_kernel_stride_by_stride_e326():
    """Each stride's toe-off from its own samples (0.5 s before its start to its end) equals the whole recording's
    (offline ``--toe-off`` / ``run --gait``) to well under a sample; the sign comes out toe-up whichever way the
    sensor holds the axis. (The numpy 15 Hz filter is scipy's to 1e-12: ``tests/test_kernels_dsp.py``.)"""
    for axis in ((0.0, 0.0, 1.0), (0.3, -0.9, 0.2)):
        t, gyr, st, en, ic, true = _strides(12, 100.0, axis=axis)
        off = toe_off_times(t, gyr, st, en, ic)
        live = LiveToeOff()
        got = []
        for a, b, c in zip(st, en, ic, strict=True):
            k = (t >= a - live.pad_s) & (t <= b)
            got.append(live.stride(t[k], gyr[k], a, b, c))
        np.testing.assert_allclose(got, off, atol=2e-4)
        np.testing.assert_allclose(got, true, atol=0.01)  # the push-off's dip, not the swing
        assert abs(live.votes) == 12  # every stride voted the same way (relative to the kept axis)
    bad = gyr[:40].copy()
    bad[5] = np.nan
    assert np.isnan(LiveToeOff().stride(t[:40], bad, 0.0, 0.3, 0.25))  # a stride's NaN sample: no toe-off, no raise


def _step(t0, t1, ic, length=1.4):
    return Step(t0, t1, length_m=length, event_s=ic)


def _foot(ics, tcs):
    g = StrideGait()
    g.add([_step(c - 0.7, c + 0.05, c) for c in ics], tc_s=tcs)
    return g


def test_stride_gait_stance_swing_and_the_summary_e326():
    ics = 1.0 + np.arange(6)
    g = _foot(ics, ics - 0.4)
    s = g.strides()
    assert np.isnan(s["stance_s"][0])  # no stride time: no previous contact
    np.testing.assert_allclose(s["swing_s"], 0.4)
    np.testing.assert_allclose(s["stance_s"][1:], 0.6)
    np.testing.assert_allclose(s["stance_pct"][1:], 60.0)
    ref = stance_swing(s["start_s"], s["end_s"], s["event_s"], ics - 0.4, s["stride_time_s"])
    np.testing.assert_allclose(s["stance_s"], ref[1])
    summ = g.summary()
    assert summ["n_stance_times"] == 5 and summ["median_stance_s"] == pytest.approx(0.6)
    assert summ["median_swing_s"] == pytest.approx(0.4) and summ["median_stance_pct"] == pytest.approx(60.0)
    plain = StrideGait()
    plain.add([_step(c - 0.7, c + 0.05, c) for c in ics])  # no toe-off given (E320's add): no stance
    assert plain.summary()["median_stance_s"] is None and np.isnan(plain.strides()["swing_s"]).all()


def test_double_support_and_the_stance_swing_indices_e327():
    """Left stance 0.6 s, right 0.7 s of a 1 s cycle: double support (0.2 + 0.1) / 1 = 30 %, the stance SI
    100 x 0.1 / 0.65, the swing SI 100 x 0.1 / 0.35; the same cycles as ``gait``'s cycle_table."""
    left_ic, right_ic = 1.0 + np.arange(14), 1.5 + np.arange(14)
    left, right = _foot(left_ic, left_ic - 0.4), _foot(right_ic, right_ic - 0.3)
    got = gait_summary(left, right)
    assert got["double_support_pct"] == pytest.approx(30.0)
    assert got["stance_time_s_left"] == pytest.approx(0.6) and got["stance_time_s_right"] == pytest.approx(0.7)
    assert got["stance_time_s_si_pct"] == pytest.approx(symmetry_index_pct(0.6, 0.7))
    assert got["swing_time_s_si_pct"] == pytest.approx(symmetry_index_pct(0.4, 0.3))
    assert got["si_withheld"] is None
    assert got["n_support_cycles"] == 2 * 13 - 1  # L317: the cycle into the bout's last contact left out
    # gait's own cycle table (pandas) on the same contacts: the same per-cycle double support (one kernel)
    ev = [pd.DataFrame({"ic_s": ic, "tc_s": ic - d, "length_m": 1.4}) for ic, d in ((left_ic, 0.4), (right_ic, 0.3))]
    cyc = cycle_table(merged_contacts(*ev))
    np.testing.assert_allclose(cyc["double_support_pct"], 30.0)
    assert cycle_support(1.0, 1.2, 1.5, 1.6, 2.0)[:3] == pytest.approx((0.6, 30.0, 30.0))
    flight = support_measures(left.strides(), _foot(right_ic, right_ic - 0.55).strides())  # toe-off before contact
    assert flight["double_support_pct"] is None and flight["n_support_cycles"] == 0
    few = gait_summary(_foot(left_ic[:5], left_ic[:5] - 0.4), _foot(right_ic[:5], right_ic[:5] - 0.3))
    assert few["stance_time_s_si_pct"] is None and few["swing_time_s_si_pct"] is None  # L461


@pytest.fixture(scope="module")
def streamed():
    imu = ("fAccelerometer", "fGyroscope")  # no insoles: the contact is the accelerometer's impact
    return gait_replay(BUNDLE, 5126, "stand:2, straight:10, stand:2", keep=imu.__contains__)


def test_the_tracker_gives_runs_stance_and_swing_e326(streamed):
    """``Tracker(gait=True)``'s stance / swing / stance % per stride are ``run --gait``'s (the whole recording's
    toe-offs through ``streamed_gait_columns``) within 2 ms / 0.3 points."""
    s, tr, steps = streamed
    mine = tr.gait_strides()
    table = streamed_gait_columns(pd.DataFrame([st.to_dict() for st in steps]).assign(unit="foot"))
    g = s.streams["fGyroscope"]
    tc = toe_off_times(g.t, g.values, *(table[c].to_numpy(float) for c in ("start_s", "end_s", "event_s")))
    ref = streamed_gait_columns(table, tc_s=tc)
    assert np.isfinite(mine["stance_s"]).sum() >= len(steps) - 2 >= 4
    for c, col, tol in (("tc_s", "tc_s", 0.002), ("stance_s", "stance_time_s", 0.002),
                        ("swing_s", "swing_time_s", 0.002), ("stance_pct", "stance_pct", 0.3)):
        np.testing.assert_allclose(mine[c], ref[col].to_numpy(float), atol=tol, err_msg=c)
    assert 50.0 < tr.gait_summary()["median_stance_pct"] < 70.0
    assert not tr._toe_offs  # every measured stride's toe-off was handed to the log
    assert math.isfinite(tr.gait_summary(tr)["double_support_pct"] or math.nan) is False  # one foot twice: no cycle


def test_the_bout_ends_are_the_first_and_last_contact_in_time_e327():
    """Two feet's rows concatenated (left, then right): the bout's ends are its earliest and latest contacts, not its
    first and last rows (the right foot's 1.0 s and the left foot's 3.5 s here)."""
    ends = bout_end_rows([1.5, 2.5, 3.5, 1.0, 2.0, 3.0], np.ones(6, bool))
    assert np.flatnonzero(ends).tolist() == [2, 3]
