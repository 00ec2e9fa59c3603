"""Per-user stride-length class bounds recorded at training time (thesis ch.6.3) and used by M3."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify.training import length_class_bounds
from pdrlearn.io import Session


def _session(meta=None, lengths=None, classes=None):
    steps = None
    if lengths is not None:
        steps = pd.DataFrame({"start_s": np.arange(len(lengths)), "end_s": np.arange(len(lengths)) + 1.0,
                              "length_m": lengths, "length_class": classes})
    return Session("s", {}, steps=steps, meta=meta or {})


def test_bounds_from_meta_median():
    s = [_session({"length_class_bounds_m": [0.8, 1.2]}), _session({"length_class_bounds_m": [1.0, 1.4]}),
         _session({})]
    assert length_class_bounds(s) == pytest.approx([0.9, 1.3])


def test_bounds_from_labelled_lengths():
    s = [_session(lengths=[0.5, 0.6, 1.0, 1.1, 1.5, 1.6], classes=["short"] * 2 + ["normal"] * 2 + ["long"] * 2)]
    assert length_class_bounds(s) == pytest.approx([(0.55 + 1.05) / 2, (1.05 + 1.55) / 2])


def test_no_bounds_without_information():
    assert length_class_bounds([_session(lengths=[1.0, 1.1], classes=["normal", "normal"])]) is None
    assert length_class_bounds([_session()]) is None


def test_trained_model_carries_bounds_from_simulated_exercise():
    from pdrlearn.classify import train_user
    from pdrlearn.sim import simulate

    s = simulate("length", user_seed=2)
    model = train_user([s], tasks=["length"], methods=["svm"], units=["foot"], cv=3)
    assert model.data_summary["length_bounds_m"] == pytest.approx(list(s.meta["length_class_bounds_m"]))
