"""Decision steps 49 (session 32 review 2, finding 7): `pll`'s streaming detector refuses ``relative_gate=true``
given explicitly; the default (None) streams with ``gate_var`` and detects offline with steps 48's gate."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.steps.detectors import PLLStepDetector, get_detector


def test_explicit_relative_gate_is_refused_online():
    with pytest.raises(DataError, match="relative_gate=true acts on the offline detect only"):
        get_detector("pll:relative_gate=true").online(100.0)
    with pytest.raises(DataError, match="gate_var=0.25"):
        PLLStepDetector(relative_gate=True).online(50.0)


def test_default_and_false_stream():
    assert get_detector("pll").relative_gate is None
    get_detector("pll").online(100.0)
    get_detector("pll:relative_gate=false").online(100.0)


def test_offline_detect_is_not_refused_and_the_default_is_steps_48s(tmp_path):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route("straight:4"), UserProfile.from_seed(6848), seed=6848, speed="slow")
    on = get_detector("pll:relative_gate=true").detect(s)
    default = get_detector("pll").detect(s)
    assert len(on) == len(default) > 0
