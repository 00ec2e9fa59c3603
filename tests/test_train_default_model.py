"""experiments/train_default_model.py refuses held-out users that it trains on (decision C31)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "experiments" / "train_default_model.py"


def _script():
    spec = importlib.util.spec_from_file_location("train_default_model", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("argv", [
    ["--train-seeds", "101", "102", "--held-out-seeds", "102", "121"],   # explicit overlap
    ["--users", "3", "--held-out-seeds", "103"],                          # default training users 101-103
    ["--train-seeds", "101", "101"],                                      # a user twice
])
def test_train_default_model_refuses_bad_user_lists(argv, tmp_path):
    with pytest.raises(SystemExit) as e:
        _script().main([*argv, "--out", str(tmp_path / "bundle")])
    assert str(e.value).startswith("error: --train-seeds")
    assert not (tmp_path / "bundle").exists()  # refused before simulating or writing anything
