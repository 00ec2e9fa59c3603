"""Decision L427 (session 35): L416's labelled step-time asymmetry runs the waist-ic detector once per session's
lower-back data, not once per summary."""

from __future__ import annotations

import pytest

import pdrlearn
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.steps.waist_ic import WaistICStepDetector

KEYS = ("step_time_asymmetry_pct", "n_step_time_asymmetry_steps", "step_time_asymmetry_reason")


@pytest.fixture(scope="module")
def two_units(tmp_path_factory):
    """A 100 Hz foot + lower-back walk with a step-time asymmetry (simulated user 8362)."""
    root = tmp_path_factory.mktemp("l427") / "s"
    write_session(simulate_path([Stand(3), Straight(45), Stand(3)], UserProfile.from_seed(8362), speed="normal",
                                rate_hz=100, seed=8362, bounce="pendulum", step_time_asymmetry=0.15), root)
    return root


def _counting(monkeypatch) -> list:
    calls = []
    real = WaistICStepDetector.detect

    def detect(self, session):
        calls.append(session.name)
        return real(self, session)

    monkeypatch.setattr(WaistICStepDetector, "detect", detect)
    return calls


def test_summaries_and_write_track_run_the_detector_once(two_units, tmp_path, monkeypatch):
    """result.summary twice and pdrlearn.write_track: one detection (three before), the same numbers as a fresh
    session's."""
    fresh = read_session(two_units)
    want = pdrlearn.get_pipeline("plasys")(fresh).summary(fresh)
    assert want["step_time_asymmetry_pct"] is not None  # the index is given: the detector's contacts are used
    session = read_session(two_units)
    result = pdrlearn.get_pipeline("plasys")(session)
    calls = _counting(monkeypatch)
    first, second = result.summary(session), result.summary(session)
    pdrlearn.write_track(result, session, tmp_path / "t", plot=False)
    import json

    written = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert len(calls) == 1
    for k in KEYS:
        assert first[k] == second[k] == written[k] == want[k], k


def test_changed_lower_back_data_run_it_again(two_units, monkeypatch):
    """A session copy whose lower-back clock moved (apply_alignment) is detected again, with its own numbers."""
    from pdrlearn.steps import apply_alignment
    from pdrlearn.track.labelled_asymmetry import waist_ic_contacts

    reference = WaistICStepDetector().detect(read_session(two_units))["event_s"].to_numpy()
    session = read_session(two_units)
    calls = _counting(monkeypatch)
    a = waist_ic_contacts(session)
    moved = apply_alignment(session, 0.05)  # a deep copy: it carries the original's kept contacts and digest
    b = waist_ic_contacts(moved)
    assert len(calls) == 2
    assert (a == reference).all()
    assert b == pytest.approx(reference - 0.05, abs=0.011)  # its own contacts, not the original's
    assert (waist_ic_contacts(session) == a).all() and len(calls) == 2  # the original's kept ones
