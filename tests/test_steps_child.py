"""Steps decisions 37 / 38 (session 23 paediatric trial, finding 1): `pdrlearn steps` on a child's foot. The foot
accelerometer detector's shortest stride is 0.4 s (0.6 s merged the strides of a 3-year-old at 230 steps/min: 1 of
26, exit 0, no line), and `steps` says so when the detected strides cover many more rest-to-rest strides."""

from __future__ import annotations

import dataclasses
import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate
from pdrlearn.steps import AccelStepDetector


@pytest.fixture(scope="module")
def age3_fast(tmp_path_factory):
    """A 3-year-old (0.95 m, 0.45 m legs, 0.36 m steps) walking scenario A fast: 0.26 s steps, 230 steps/min."""
    kid = dataclasses.replace(UserProfile.from_seed(1160).scaled(0.95, 0.45), step_length_m=0.36, step_time_s=0.303)
    out = tmp_path_factory.mktemp("kid") / "age3_A_fast"
    write_session(simulate("A", kid, "fast", rate_hz=100.0), out)
    return out


def _steps(folder, capsys, caplog):
    with caplog.at_level(logging.WARNING):
        assert main(["steps", str(folder), "--json"]) == 0
    return json.loads(capsys.readouterr().out), [r.getMessage() for r in caplog.records if "steps 38" in r.getMessage()]


def test_a_fast_three_year_olds_strides_are_counted(age3_fast, capsys, caplog):
    d, lines = _steps(age3_fast, capsys, caplog)
    assert d["recall"] >= 0.95 and d["precision"] == 1.0, d  # 0.6 s: recall 0.04
    assert abs(d["count"] - d["reference_count"]) <= 1 and not lines
    assert AccelStepDetector().min_stride_s == 0.4


def test_merged_strides_are_warned(age3_fast, capsys, caplog, monkeypatch):
    """Steps 38: with decision 3's 0.6 s the strides merge, and `steps` says how many strides `track` counts."""
    monkeypatch.setitem(AccelStepDetector.__init__.__kwdefaults__, "min_stride_s", 0.6)
    d, lines = _steps(age3_fast, capsys, caplog)
    assert d["count"] <= d["reference_count"] // 2 and d["rest_strides"] >= d["reference_count"] - 1
    assert len(lines) == 1 and "0.6 s shortest stride" in lines[0] and "pdrlearn track" in lines[0]
    assert f"cover {d['rest_strides']} rest-to-rest strides" in lines[0] and "\n" not in lines[0]
