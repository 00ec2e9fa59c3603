"""Decision C120: ``pdrlearn.classify.training_data`` gives the windows, labels, sessions and users ``train``
cross-validates, so a scikit-learn CV on them scores what ``train --cv-groups user`` scores (the session-37 trial
T4 found the documented ``step_windows`` route cut other windows at the bouts' edges, decision C55)."""

from __future__ import annotations

import numpy as np
import pytest
from sklearn.model_selection import GroupKFold, cross_val_predict

from pdrlearn.classify import make_estimator, train_user, training_data
from pdrlearn.errors import DataError
from pdrlearn.features import step_windows
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def three_users():
    return [simulate("terrain", user_seed=u) for u in (9200, 9201, 9202)]


def test_groupkfold_cv_on_training_data_equals_train_cv_groups_user(three_users):
    model = train_user(three_users, tasks=["terrain"], methods=["heuristic", "fusion"],
                       units=["foot", "waist", "fused"], cv=3, cv_groups="user", distance_calibration=False)
    cv = model.tasks["terrain"].cv
    for method, unit in (("heuristic", "foot"), ("fusion", "fused")):
        d = training_data(three_users, "terrain", unit=unit)
        assert sorted(set(d.user)) == ["user.seed:9200", "user.seed:9201", "user.seed:9202"]
        pred = cross_val_predict(make_estimator("terrain", method, unit), d.X, d.y, groups=d.user, cv=GroupKFold(3))
        assert np.mean(pred == d.y) == pytest.approx(cv[method][unit]["accuracy"], abs=1e-12)
        assert len(d.y) == model.tasks["terrain"].n_steps


def test_training_data_windows_are_trains_not_step_windows_as_given(three_users):
    d = training_data(three_users[:1], "terrain")
    plain = step_windows(three_users[0]).X
    assert d.X.shape == plain.shape and list(d.session) == [three_users[0].name] * len(d.y)
    assert not np.allclose(d.X, plain, equal_nan=True)  # bout edges re-cut as the runtime cuts them (C55)


def test_training_data_refuses_a_bad_task_or_unit(three_users):
    with pytest.raises(DataError, match="training_data: task 'terain'; choose one of terrain, direction, length"):
        training_data(three_users, "terain")
    with pytest.raises(DataError, match="training_data: unit 'both'; choose one of foot, waist, fused, combined"):
        training_data(three_users, "terrain", unit="both")


def test_one_session_is_accepted_and_mixed_rates_name_resample_hz():
    """Review R4 finding 8: training_data(session) raised a TypeError; the API's mixed-rate line named only the
    CLI's --resample."""
    one = simulate("terrain", user_seed=9361)
    assert len(training_data(one, "terrain").y) == len(training_data([one], "terrain").y) > 0
    mixed = [one, simulate("terrain", user_seed=9361, seed=3, rate_hz=100.0)]  # one: 20 Hz
    with pytest.raises(DataError, match=r"^training_data: the sessions were recorded at different rates.*"
                                        r"resample_hz=\d"):
        training_data(mixed, "terrain")
