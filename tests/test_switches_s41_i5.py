"""Session 41 (implementer I5), W413's rule on 20 of the module-level booleans of ``PENDING``
(tests/test_switches_s40_i4.py): an adopted rule is the code, an alternative not adopted is a keyword or removed.

- W467 (waist): W259, W308, W310, W332 are the code; W284's warning branch is gone; W369's pre-session-35 value is
  inlined (a fact, not a switch).
- L584 (kernels / displace): foot's three options are ``FootDisplacement`` keywords (False); force_clock's L390 is
  the code (L389 removed), its warning the keyword ``warn=True``; W229 is ``ascent_descent(by_rate=False)``.
- C162 (classify): C55 is the code; C71's joint score is ``UserModel.predict_steps(joint_domain=True)`` only.
- E251 (export / io): E19 is ``build_step_graph(one_softmax=True)``; B33 / B64 are ``read_session`` keywords.
- S96 (sim): S23, S24, S25 are the code.
"""

from __future__ import annotations

import importlib
import inspect

import pytest

from tests.test_module_switches_w413 import switch_setters

#: module -> the switches session 41's I5 removed (decisions W467, L584, C162, E251, S96)
REMOVED = {
    "pdrlearn.classify.detected": ("RUNTIME_BOUT_EDGES",),  # C162
    "pdrlearn.classify.domain": ("JOINT_DEFAULT",),  # C162
    "pdrlearn.displace.foot": ("REST_BIAS", "TIMESTAMPS", "UPSAMPLE_RUNS"),  # L584
    "pdrlearn.displace.force_clock": ("FORCE_OFFSET_WARN", "OFFSET_FROM_TOE_OFF", "L389_OFFSET_MAX_S"),  # L584
    "pdrlearn.export.step_graph": ("ONE_SOFTMAX",),  # E251
    "pdrlearn.io.plasys": ("BRIDGE_DROPS", "RESAMPLE_JITTER"),  # E251
    "pdrlearn.kernels.altitude_check": ("DRIFT_BY_RATE",),  # L584
    "pdrlearn.sim.body": ("ASCENT_TOE_LED", "LEVEL_SWING_TOE_LED", "SHOD"),  # S96
    "pdrlearn.waist.lying": ("SIDE_AFTER_CHAIR",),  # W467
    "pdrlearn.waist.pll_calibration": ("UNRECORDED",),  # W467
    "pdrlearn.waist.tug_phases": ("TUG_YAW_TURN_TO_SIT",),  # W467
    "pdrlearn.waist.turn_steps": ("STEPLESS_WARN", "TURN_STEPS_WARN"),  # W467
    "pdrlearn.waist.upright": ("FLEXION_FREE_WALKING",),  # W467
}


@pytest.mark.parametrize("module", sorted(REMOVED))
def test_the_switches_are_gone_w467_l584_c162_e251_s96(module):
    mod = importlib.import_module(module)
    assert [n for n in REMOVED[module] if hasattr(mod, n)] == []


def test_no_experiment_or_test_sets_them_w467_l584_c162_e251_s96():
    assert switch_setters([n for ns in REMOVED.values() for n in ns]) == []


def _defaults(fn, *names):
    params = inspect.signature(fn).parameters
    return tuple(params[n].default for n in names)


def test_the_options_are_keywords_with_the_old_defaults_l584_e251_w467():
    from pdrlearn.classify.training import UserModel
    from pdrlearn.displace.foot import FootDisplacement
    from pdrlearn.displace.force_clock import offset_check
    from pdrlearn.export.step_graph import build_step_graph
    from pdrlearn.io.plasys import read_session
    from pdrlearn.kernels.altitude_check import ascent_descent
    from pdrlearn.waist.tug_phases import segment_phases, tug_phases, tug_trial_table

    assert _defaults(FootDisplacement.__init__, "timestamps", "upsample_runs", "rest_bias") == (False, False, False)
    assert _defaults(offset_check, "warn") == (True,)  # L390's warning, on since L390
    assert _defaults(ascent_descent, "by_rate") == (False,)  # W229 not adopted
    assert _defaults(build_step_graph, "one_softmax") == (True,)  # E19 adopted
    assert _defaults(read_session, "uniform_clock", "bridge_drops") == (False, None)  # B33, B64 not adopted
    assert _defaults(UserModel.predict_steps, "joint_domain") == (False,)  # C71 not adopted
    for fn in (tug_phases, segment_phases, tug_trial_table):
        assert _defaults(fn, "yaw_to_sit") == (True,), fn  # W308 adopted


def test_the_track_asks_for_no_joint_score_c162():
    """C71's score is not computed by ``track --model`` (its rows carry no ``ood_joint_<task>``): the track calls
    ``predict_steps`` without ``joint_domain``."""
    from pdrlearn.track import plasys

    src = inspect.getsource(plasys)
    assert "joint_domain" not in src and "JOINT_DEFAULT" not in src


def test_the_bout_edges_are_always_recut_for_training_c162(monkeypatch):
    """C55 without its switch: training windows on given boundaries always go through ``runtime_bout_edges``."""
    from pdrlearn.classify import detected
    from pdrlearn.classify.training import session_windows
    from pdrlearn.sim.simulate import simulate

    calls = []
    real = detected.runtime_bout_edges

    def spy(session, steps):
        calls.append(len(steps))
        return real(session, steps)

    monkeypatch.setattr(detected, "runtime_bout_edges", spy)
    session_windows([simulate("terrain", 2500, seed=7)], n_samples=40)
    assert len(calls) == 1
