"""Decision W242: ``fast_fill`` -- after the offline sequence rules, one contact where the gap between two kept contacts
is consistent with ONE missing step (a same-side pair; or a pair not on decided opposite sides about two local periods
apart) and the vertical acceleration low-passed at twice the cut-off (5 Hz) has a maximum of its own there (over 0.1 s
from every 2.5 Hz candidate, at least half the median kept height, W237's cue). The kernel by hand, the option's reach
(offline only; the live trackers and W193 name it) and a simulated walk whose contacts it does not change."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import simulate
from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.events import InitialContactDetector
from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS

FS = 100.0
# kept contacts every 0.5 s (50 samples), one step missing at 300 (a gap of two periods between 250 and 350)
PEAKS = np.array([100, 150, 200, 250, 350, 400, 450, 500])


def _fill(side, bump_at=300, bump=1.0, cand=PEAKS, peaks=PEAKS, ref=1.0, max_step_s=1.5):
    x = np.zeros(700)
    x[bump_at] = bump  # the 5 Hz signal's own maximum
    return K.fast_band_fill(x, cand, peaks, np.asarray(side), ref, FS, min_gap=30, max_step_s=max_step_s)


def test_a_same_side_pair_gets_the_own_5hz_maximum():
    # W20: 250 and 350 on one decided side, the alternation asks for the opposite step between them
    np.testing.assert_array_equal(_fill([1, -1, 1, -1, -1, 1, -1, 1]), [300])
    # branch (i) reaches an off-rhythm place too (the gap less the 0.3 s shortest step from each end: 280-320) ...
    np.testing.assert_array_equal(_fill([1, -1, 1, -1, -1, 1, -1, 1], bump_at=318), [318])
    # ... but not one within the shortest step of a kept contact
    assert _fill([1, -1, 1, -1, -1, 1, -1, 1], bump_at=325).size == 0


def test_an_undecided_pair_about_two_periods_apart_gets_it_in_w148s_window():
    side = [1, -1, 1, 0, -1, 1, -1, 1]  # 250 undecided: branch (ii), one period +-35 % from each end
    np.testing.assert_array_equal(_fill(side), [300])
    np.testing.assert_array_equal(_fill(side, bump_at=317), [317])  # within 0.35 x 50 samples of both predictions
    assert _fill(side, bump_at=320).size == 0  # 0.4 periods off the prediction


def test_no_contact_without_the_cue_or_the_gap():
    same = [1, -1, 1, -1, -1, 1, -1, 1]
    assert _fill([1, -1, 1, -1, 1, -1, 1, -1]).size == 0  # decided opposite sides: no single step missing
    assert _fill(same, bump=0.49).size == 0  # under half the median kept 2.5 Hz height (W237, W23's 1/2)
    assert _fill(same, cand=np.sort(np.r_[PEAKS, 292])).size == 0  # a 2.5 Hz candidate 0.08 s away: not its own
    np.testing.assert_array_equal(_fill(same, cand=np.sort(np.r_[PEAKS, 289])), [300])  # 0.11 s away: its own
    assert _fill(same, max_step_s=0.9).size == 0  # 250 -> 350 over the longest step: two sequences (W16)
    assert _fill(same, ref=0.0).size == 0  # no kept height to scale the cue
    # an evenly spaced sequence has no gap for one step, whatever the 5 Hz signal does
    even = np.arange(100, 600, 50)
    assert _fill([1, -1] * 5, bump_at=325, cand=even, peaks=even).size == 0


def test_the_option_is_offline_only_and_named_where_it_does_nothing():
    assert OPTION_DEFAULTS["fast_fill"] is False and InitialContactDetector().fast_fill is False
    assert InitialContactDetector(fast_fill=True).rule_settings()["fast_fill"] is True
    assert InitialContactDetector(fast_fill=True, realtime=True).rule_settings()["fast_fill"] is False
    assert InitialContactDetector(fast_fill=True, learned=True).rule_settings()["fast_fill"] is False
    assert "fast_fill" in LIVE_UNAPPLIED_OPTIONS  # E107: the live trackers say they do not apply it
    o = dict(OPTION_DEFAULTS, fast_fill=True)
    line = ignored_options_line(o, "waist-pendulum", True, "gyro", False, True)
    assert line is not None and "fast_fill=true" in line and "W242" in line
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None


@pytest.fixture(scope="module")
def walk():
    return simulate("A", 1907, rate_hz=100.0)


def test_a_clean_simulated_walk_keeps_its_contacts(walk):
    """A regular walk has no one-step gap: the same contacts either way."""
    off = track_waist(walk, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
    on = track_waist(walk, pipeline="waist-pendulum", fast_fill=True).steps["event_s"].to_numpy(float)
    assert off.size > 10
    np.testing.assert_array_equal(on, off)


def test_the_measured_real_row_ms001_test11_w243():
    """W243 (W242's rule, not met on the freeze route): on MS001 Test11 the 5 Hz maximum recovers the merged step at
    123.88 s (in-bout step_f1 0.8913 82/93 -> 0.8973 83/94 of 91); the default is unchanged."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import step_metrics
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_MS001_Test11_Trial1"))
    r = {v: track_waist(s, pipeline="waist-pendulum", turn_bridge=False,  # W243 was measured before W385's "side"
                        **({"fast_fill": True} if v else {})) for v in (False, True)}
    m = {v: step_metrics(r[v].steps, s) for v in r}
    assert (m[False]["n_detected"], m[False]["n_reference"], round(m[False]["step_f1"], 4)) == (93, 91, 0.8913)
    assert (m[True]["n_detected"], round(m[True]["step_f1"], 4)) == (94, 0.8973)
    added = np.setdiff1d(r[True].steps["event_s"].to_numpy(float), r[False].steps["event_s"].to_numpy(float))
    assert added.size == 1 and abs(added[0] - 123.88) < 0.25
