"""Per-step latency of the learned classifiers (terrain, length) and a user's full training (run with
`make bench`).

Targets (issue 5): SVM / NN <= 0.2 ms per step (features + classification), DTW with 108 references
<= 0.3 ms; a user's full training (3 tasks x 5 methods, 10-fold CV) < 60 s.
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.classify.dtw import DTWClassifier
from pdrlearn.classify.training import make_estimator

pytestmark = pytest.mark.bench


@pytest.fixture(scope="module")
def terrain_sessions():
    from pdrlearn.sim.simulate import simulate

    return [simulate("terrain", user_seed=1, seed=k) for k in range(2)]


@pytest.fixture(scope="module")
def terrain_windows(terrain_sessions):
    from pdrlearn.classify.training import session_windows, task_data

    return task_data(session_windows(terrain_sessions, n_samples=40), "terrain")


@pytest.mark.parametrize("prune", [False, True])
def test_bench_dtw_108_references_one_step(benchmark, prune):
    rng = np.random.default_rng(0)
    X = rng.normal(size=(300, 3, 40))
    y = np.repeat(["flat", "up", "down"], 100)
    clf = DTWClassifier(n_references=36, prune=prune).fit(X, y)  # 108 references, thesis ch. 6.1.2.2
    assert len(clf.references_) == 108
    one = X[:1]
    benchmark(clf.predict, one)


@pytest.mark.parametrize("method", ["svm", "nn", "dtw"])
@pytest.mark.parametrize("unit", ["foot", "fused"])
def test_bench_one_step_features_and_classification(benchmark, terrain_windows, method, unit):
    est = make_estimator("terrain", method, "foot" if unit == "foot" else "fused", seed=0)
    est.fit(terrain_windows.X, terrain_windows.y)
    one = terrain_windows.X[:1]
    benchmark(est.predict, one)


@pytest.fixture(scope="module")
def length_windows():
    from pdrlearn.classify.training import session_windows, task_data
    from pdrlearn.sim.simulate import simulate

    sessions = [simulate("length", user_seed=1, seed=k) for k in range(2)]
    return task_data(session_windows(sessions, n_samples=40), "length")


@pytest.mark.parametrize("method", ["svm", "nn"])
@pytest.mark.parametrize("unit", ["foot", "fused"])
def test_bench_length_one_step_features_and_classification(benchmark, length_windows, method, unit):
    """Length: 27 foot features (24 segment + 3 force) and 2 pelvic-rotation features per step (thesis
    ch. 6.3.1), per-class SVM kernels rbf/poly2/linear (thesis ch. 6.3.1.1), fused = both units + vote."""
    est = make_estimator("length", method, unit, seed=0)
    est.fit(length_windows.X, length_windows.y)
    one = length_windows.X[:1]
    benchmark(est.predict, one)


def test_bench_full_user_training(benchmark):
    """3 tasks x 5 methods x (foot, waist, fused), 10-fold CV, on one calibration exercise per task."""
    from pdrlearn.sim.simulate import simulate

    sessions = [simulate(task, user_seed=2, seed=0) for task in ("terrain", "direction", "length")]

    def run():
        return {
            t: train_user([s], tasks=[t], cv=10, seed=0)
            for t, s in zip(("terrain", "direction", "length"), sessions, strict=True)
        }

    models = benchmark.pedantic(run, rounds=1, iterations=1)
    assert set(models) == {"terrain", "direction", "length"}
