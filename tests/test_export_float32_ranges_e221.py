"""Decision E221: ``export --float32`` refuses a bundle whose float32 graphs leave the float64 ones on the training
range (review R3 finding 3: a network with a near-constant input moved a probability by 0.2 on a walk)."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.classify.nn as nn
from pdrlearn.classify import train_user
from pdrlearn.cli import main
from pdrlearn.export.precision import range_rows
from tests.runtime_helpers import _with_bounds, synthetic_session


def _old_scale(X, mean):  # the rule before decision E220: any std > 0 standardizes, even 4e-16
    std = X.std(axis=0)
    return np.where(std > 0, std, 1.0)


@pytest.fixture(scope="module")
def old_model(tmp_path_factory):
    """R3's case: a waist network trained by the pre-E220 rule on a feature constant up to rounding."""
    mp = pytest.MonkeyPatch()
    mp.setattr(nn, "input_scale", _old_scale)
    try:
        m = _with_bounds(train_user([synthetic_session(90, seed=0)], cv=2, seed=0, units=["waist"],
                                    methods=["nn"]))
    finally:
        mp.undo()
    assert m.tasks["length"].models["nn"]["waist"][-1].scale_.min() < 1e-12  # the hazard is there
    path = tmp_path_factory.mktemp("e221") / "model"
    m.save(path)
    return path


def test_range_rows_cover_each_feature_edge():
    R = range_rows([0.0, 10.0], [1.0, 20.0])
    assert R.shape == (7, 2)
    assert {tuple(r) for r in R} >= {(0, 10), (1, 20), (0.5, 15), (0, 15), (1, 15), (0.5, 10), (0.5, 20)}


def test_float32_export_of_a_rounding_sensitive_network_is_refused(old_model, tmp_path, capsys):
    out = tmp_path / "b32"
    rc = main(["export", str(old_model), "--out", str(out), "--methods", "nn", "--float32"])
    err = capsys.readouterr().err
    assert rc == 2
    assert not out.exists()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "E221" in lines[0] and "nn/waist" in lines[0] and "Traceback" not in err
    assert main(["export", str(old_model), "--out", str(tmp_path / "b64"), "--methods", "nn"]) == 0
