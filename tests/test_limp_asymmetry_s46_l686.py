"""Decision L686: L416's foot + lower-back step-time asymmetry of a slow asymmetric walk carries a bias allowance in
its standard error. The lower back dates the contact ending the shorter step earlier than the one ending the longer
step (simulated limping walkers at 0.6-0.8 s steps), so the index reads high by a share of itself that one foot unit
cannot measure: trial T1's knee patient read 34.3 % (standard error 2.7 points, no note) for a true 22.1 %."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.track import labelled_asymmetry as la
from tests.fakes import FakeWaistSession


def _limp(step_s: float, lead: float, seed: int = 686):
    """A limping walker's contacts: strides of 2 ``step_s``, the other foot's contact at ``lead`` of the stride; the
    lower back's own contacts 0.03 s early and the other foot's 0.07 s early (the shorter step's end dated earlier,
    as on the simulated limping walkers); 60 strides."""
    rng = np.random.default_rng(seed)
    stride = 2.0 * step_s
    foot = np.arange(61) * stride
    own = foot - 0.03 + rng.normal(0.0, 0.01, 61)
    other = foot[:-1] + lead * stride - 0.07 + rng.normal(0.0, 0.01, 60)
    return foot, np.sort(np.concatenate([own, other]))


def test_slow_asymmetric_index_gets_the_allowance_l686():
    """At 0.7 s steps the standard error adds 0.45 x the index in quadrature, so the high index is noted uncertain;
    the index itself is L416's."""
    foot, waist = _limp(0.7, 0.445)
    res = la.labelled_step_asymmetry(foot, waist)
    idx = res["step_time_asymmetry_pct"]
    assert idx is not None and idx > 25.0  # the true 22 %, read high as the simulated walkers'
    assert res["bias_allowance_points"] == pytest.approx(la.ASYMMETRY_BIAS_FRACTION * idx, rel=1e-12)
    phases, lags = la._phases_and_lags(foot, waist, tolerance_steps=la.LABEL_TOLERANCE_STEPS)
    l677 = la.index_standard_error_pct(phases, lags, float(np.median(np.diff(foot))))
    assert l677 <= la.UNCERTAIN_SE_POINTS < res["standard_error_points"]  # bare before, noted now
    assert res["standard_error_points"] == pytest.approx(np.hypot(l677, res["bias_allowance_points"]), rel=1e-12)


def test_normal_pace_keeps_l677s_standard_error_l686():
    """Under 0.6 s steps (L416's validated pace) nothing is added: the standard error is L677's."""
    foot, waist = _limp(0.55, 0.445)
    res = la.labelled_step_asymmetry(foot, waist)
    phases, lags = la._phases_and_lags(foot, waist, tolerance_steps=la.LABEL_TOLERANCE_STEPS)
    assert res["bias_allowance_points"] == 0.0
    assert res["standard_error_points"] == pytest.approx(
        la.index_standard_error_pct(phases, lags, float(np.median(np.diff(foot)))), rel=1e-12)


def test_symmetric_slow_walk_adds_nothing_l686():
    """The allowance is a share of the index: a symmetric slow walker's (index ~0) adds ~nothing."""
    assert la.bias_allowance_points(0.0, 1.6) == 0.0
    assert la.bias_allowance_points(20.0, 1.19) == 0.0
    assert la.bias_allowance_points(20.0, 1.2) == pytest.approx(9.0)


def test_track_reason_names_it_l686(monkeypatch):
    """The plasys track's reason says a slow asymmetric walk's index may read high (decision L686)."""
    import pandas as pd

    foot, waist = _limp(0.7, 0.445)

    monkeypatch.setattr(la, "waist_ic_contacts", lambda session: waist)
    steps = pd.DataFrame({"event_s": foot, "unit": "foot"})
    out = la.track_asymmetry(FakeWaistSession(), steps)
    assert "decision L686" in out["step_time_asymmetry_reason"]
    assert "uncertain" in out["step_time_asymmetry_reason"]
    assert out["step_time_asymmetry_se_points"] > la.UNCERTAIN_SE_POINTS
