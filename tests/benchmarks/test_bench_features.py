"""Speed of step windows, feature extraction and heuristic classification (run with `make bench`)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.classify.heuristic import HeuristicFusionClassifier, HeuristicTerrainClassifier
from pdrlearn.features import CHANNEL_INDEX, TerrainSVMFeatures, make_features, step_windows
from pdrlearn.io import read_session

pytestmark = pytest.mark.bench


@pytest.fixture(scope="module")
def level(real_dir):
    return read_session(real_dir / "gaitmap_level_left")


@pytest.fixture(scope="module")
def windows(level):
    return step_windows(level)


def test_bench_step_windows_one_step(benchmark, level):
    """Levelling + resampling of one 204.8 Hz step."""
    one = level.steps.iloc[:1]
    benchmark(step_windows, level, one)


def test_bench_terrain_svm_features_one_step(benchmark, windows):
    tf = TerrainSVMFeatures(unit="foot").fit(windows.X[:1])
    benchmark(tf.transform, windows.X[:1])


def test_bench_segment_features_one_step(benchmark, windows):
    tf = make_features("terrain", "foot", "nn").fit(windows.X[:1])
    benchmark(tf.transform, windows.X[:1])


def test_bench_heuristic_terrain_one_step(benchmark, windows):
    y = np.array(["flat"] * len(windows), dtype=object)
    clf = HeuristicTerrainClassifier(unit="foot").fit(windows.X, y)
    benchmark(clf.predict, windows.X[:1])


def test_bench_heuristic_fusion_direction_one_step(benchmark, windows):
    X = windows.X.copy()
    w, f = CHANNEL_INDEX["waist_acc_x"], CHANNEL_INDEX["foot_acc_x"]
    X[:, w:w + 3] = X[:, f:f + 3]  # stand-in waist accelerometer
    y = np.array(["forward"] * len(X), dtype=object)
    clf = HeuristicFusionClassifier(task="direction").fit(X, y)
    benchmark(clf.predict, X[:1])
