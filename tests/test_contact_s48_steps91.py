"""Steps decision 91 (docs/decisions/steps.md): at the rhythm's cutoff (steps 88) a short stride's impact is the head
of a split impact (``contact.split_head``), not its last peak; offline and streamed alike."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels import contact as C
from tests.cli_helpers import insole_free_walk

FS = 100.0
#: steps 88's development child u15219's short walk (the rate added by each test module)
CHILD_15219 = ("--route", "stand:2, straight:8, stand:2", "--rocker", "smooth", "--user-seed", "15219", "--height",
               "1.45", "--leg-length", "0.7584", "--step-length", "0.4684", "--step-time", "0.36")


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


def test_split_head_steps_back_over_a_tail_only():
    t = [0.93, 1.00, 1.04]
    assert C.split_head(t, [47.0, 43.5, 23.9], 2, 0.05) == 1  # a tail under 0.75 of its impact: the impact
    assert C.split_head(t, [47.0, 43.5, 33.6], 2, 0.05) == 2  # 0.77 of it: kept
    assert C.split_head(t, [47.0, 43.5, 23.9], 2, 0.0) == 2  # cluster 0: the last peak (steps 88)
    # the deceleration 70 ms before the impact is out of the cluster even when larger; 40 ms before it and the impact
    # 0.8 of it, the impact stays
    assert C.split_head([0.93, 1.00], [60.0, 40.0], 1, 0.05) == 1
    assert C.split_head([0.96, 1.00], [50.0, 40.0], 1, 0.05) == 1
    assert C.split_head([0.96, 1.00], [60.0, 40.0], 1, 0.05) == 0  # the rule's limit: under 0.75 is a tail


def test_impact_peak_at_20_hz_takes_the_head_of_a_split_impact():
    t = np.arange(160) / FS
    m = C.GRAVITY + sum(h * np.exp(-0.5 * ((t - c) / 0.008) ** 2)
                        for c, h in [(0.5, 10.0), (0.93, 50.0), (1.0, 45.0), (1.04, 22.0)])
    last = C.impact_peak(t, m, C.GRAVITY, C.PEAK_FRAC, 20.0, False, 0.0, 0.0)[0]
    head = C.impact_peak(t, m, C.GRAVITY, C.PEAK_FRAC, 20.0, False, 0.0, C.IMPACT_CLUSTER_S)[0]
    assert last == pytest.approx(1.04, abs=0.005) and head == pytest.approx(1.0, abs=0.005)
    # at 8 Hz (decision 3: every stride that is not short) the cluster is not read
    assert C.impact_peak(t, m, C.GRAVITY, C.PEAK_FRAC, 8.0, False)[0] == pytest.approx(1.0, abs=0.005)


@pytest.fixture(scope="module")
def child(tmp_path_factory):
    """Steps 88's development child u15219 (1.45 m, 0.36 s steps, smooth rocker, no insoles) on a short walk."""
    d = tmp_path_factory.mktemp("steps91") / "u15219"
    session = insole_free_walk(d, *CHILD_15219, "--rate", "100")
    ics = pd.read_csv(d / "ics.csv")
    return session, np.sort(ics[ics.foot == "right"]["ic_ms"].to_numpy(float) / 1000.0)


def _errors(session, truth, **kw) -> np.ndarray:
    from pdrlearn.steps.detectors import AccelStepDetector

    ev = np.asarray(AccelStepDetector(**kw).detect(session)["event_s"], float)
    return np.array([ev[np.argmin(np.abs(ev - x))] - x for x in truth])


def test_a_childs_impact_is_neither_the_deceleration_nor_the_tail(child):
    s, truth = child
    before = _errors(s, truth, short_period_s=0.0)  # decision 3: the terminal-swing deceleration, 60-72 ms early
    tail = _errors(s, truth, impact_cluster_s=0.0)  # steps 88: the split impact's tail, ~30 ms late
    head = _errors(s, truth)  # steps 91, the default
    assert (before < -0.05).sum() >= 3 and (tail > 0.025).sum() >= 3
    assert np.abs(head[1:]).max() < 0.025  # the walk's first contact has no rhythm: decision 3's
    assert head[0] == before[0]


def test_the_rhythm_re_take_with_the_split_head_is_the_default():
    from pdrlearn.runtime.clocks import ACCEL
    from pdrlearn.steps.detectors import AccelStepDetector

    det = AccelStepDetector()
    assert (det.short_period_s, det.impact_cluster_s) == (C.SHORT_PERIOD_S, C.IMPACT_CLUSTER_S) == (0.95, 0.05)
    assert C.IMPACT_SPLIT_RATIO == 0.75 and ACCEL["impact_cluster_s"] == C.IMPACT_CLUSTER_S


def test_streamed_contacts_equal_offline_on_a_childs_walk(child):
    from pdrlearn.track import get_pipeline

    s, _ = child
    off = get_pipeline("plasys")(s).steps
    st = get_pipeline("plasys")(s, streaming=True, contacts=True).steps
    ev_off, ev = off["event_s"].to_numpy(float), st["event_s"].to_numpy(float)
    ok = np.isfinite(ev) & (ev >= off["start_s"].min())
    assert ok.sum() >= 8
    j = np.array([np.argmin(np.abs(ev_off - x)) for x in ev[ok]])
    np.testing.assert_allclose(ev[ok], ev_off[j], rtol=0, atol=1e-9)
