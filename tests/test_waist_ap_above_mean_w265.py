"""Decision W265: W29's IC (the last local AP maximum in W3's 0.25 s window above the AP acceleration's 2 s mean, else
W3's choice; the kernel is pinned by tests/test_waist_ic_rules.py::test_ic_is_last_ap_maximum_above_the_mean) as a
track option of the offline waist-pendulum, `ap_above_mean`: its default, its reach (offline with the pipeline's own
detector only; W193's line and E107's list name it elsewhere) and what it changes on a clean simulated walk."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import simulate
from pdrlearn.track.waist import OPTION_DEFAULTS, _contact_detector, ignored_options_line, track_waist
from pdrlearn.waist.events import InitialContactDetector
from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS


def test_the_option_is_offline_only_and_named_where_it_does_nothing():
    assert OPTION_DEFAULTS["ap_above_mean"] is False and InitialContactDetector().ap_above_mean is False
    o = dict(OPTION_DEFAULTS, ap_above_mean=True)
    assert _contact_detector(o, 0.5, False).ap_above_mean is True  # the offline detector reads W29's IC
    assert _contact_detector(o, 0.5, True).ap_above_mean is False  # realtime: not (W265's scope)
    assert _contact_detector(OPTION_DEFAULTS, 0.5, False).ap_above_mean is False
    assert "ap_above_mean" in LIVE_UNAPPLIED_OPTIONS  # E107: the live trackers say they do not apply it
    line = ignored_options_line(o, "waist-pendulum", True, "gyro", False, True)
    assert line is not None and "ap_above_mean=true" in line and "W265" in line
    assert ignored_options_line(o, "waist-pendulum", False, "gyro", False, True) is None
    assert "ap_above_mean" in (ignored_options_line(o, "waist-pll", False, "gyro", False, True) or "")


@pytest.fixture(scope="module")
def walk():
    return simulate("A", 1907, rate_hz=100.0)


def test_a_simulated_walk_keeps_its_steps_and_its_contacts_move_at_most_earlier(walk):
    """W29: the IC is still an AP maximum of W3's window before the same vertical maximum -- the same steps, each
    contact at or before today's and at most W3's 0.25 s from it."""
    off = track_waist(walk, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
    on = track_waist(walk, pipeline="waist-pendulum", ap_above_mean=True).steps["event_s"].to_numpy(float)
    assert off.size > 10 and on.size == off.size
    assert np.all(on <= off + 1e-9) and np.all(off - on <= 0.25 + 1e-9)


def test_the_measured_real_row_ha002_test11_w266():
    """W266 (W265's rule, not met): on HA002 Test11 W29's IC moves the 8.91 s maximum's contact onto INDIP's 8.62 s
    (in-bout step_f1 0.8182 36/42 -> 0.8409 37/42 of 46); the default is unchanged."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import step_metrics
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    r = {v: track_waist(s, pipeline="waist-pendulum", **({"ap_above_mean": True} if v else {})) for v in (False, True)}
    m = {v: step_metrics(r[v].steps, s) for v in r}
    assert (m[False]["n_detected"], m[False]["n_reference"], round(m[False]["step_f1"], 4)) == (42, 46, 0.8182)
    assert (m[True]["n_detected"], round(m[True]["step_f1"], 4)) == (42, 0.8409)
    on = r[True].steps["event_s"].to_numpy(float)
    assert np.min(np.abs(on - 8.62)) < 0.25 and np.min(np.abs(r[False].steps["event_s"].to_numpy(float) - 8.62)) > 0.25
