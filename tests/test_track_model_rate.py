"""Decision C18: a model's step classifiers used on a session at another rate get one warning line."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.classify import load_model
from pdrlearn.io import read_session
from pdrlearn.track.plasys import track_plasys
from tests.cli_helpers import simulated_session_and_model


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    return simulated_session_and_model(tmp_path_factory.mktemp("rate"))


def _rate_lines(result):
    return [w for w in result.info["warnings"] if "step classifiers were trained at" in w]


@pytest.mark.parametrize("streaming", [False, True])
def test_classifiers_trained_at_another_rate_warn_once(sim, streaming):
    folder, model_dir = sim
    session = read_session(folder)
    model = load_model(model_dir)
    fs = session.streams["fAccelerometer"].rate_hz
    res = track_plasys(session, model=model, streaming=streaming)
    assert _rate_lines(res) == [] and res.info["classifier_rate_mismatch"] is None
    model.sampling_rate_hz = {k: 5 * v for k, v in model.sampling_rate_hz.items()}  # trained at 100 Hz
    res = track_plasys(session, model=model, streaming=streaming)
    lines = _rate_lines(res)
    assert len(lines) == 1
    assert f"trained at {5 * fs:g} Hz" in lines[0] and f"runs at {fs:.4g} Hz" in lines[0]
    assert "train on the user's own data at this rate" in lines[0]
    assert set(res.info["classifier_rate_mismatch"]) <= {"foot", "waist"}


def test_within_the_calibration_tolerance_no_warning(sim):
    """The tolerance is the distance calibration's (1 %, decision E14): 0.5 % off is the same rate."""
    folder, model_dir = sim
    session = read_session(folder)
    model = load_model(model_dir)
    model.sampling_rate_hz = {k: 1.005 * v for k, v in model.sampling_rate_hz.items()}
    assert _rate_lines(track_plasys(session, model=model)) == []


def test_track_cli_prints_the_line(sim, tmp_path, caplog):
    from pdrlearn.cli import main

    folder, model_dir = sim
    manifest = json.loads((model_dir / "manifest.json").read_text())
    assert set(manifest["sampling_rate_hz"].values()) == {20.0}
    off = tmp_path / "at100"  # the same model as if trained at 100 Hz
    import shutil

    shutil.copytree(model_dir, off)
    manifest["sampling_rate_hz"] = {k: 100.0 for k in manifest["sampling_rate_hz"]}
    (off / "manifest.json").write_text(json.dumps(manifest))
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--model", str(off), "--out", str(tmp_path / "o"),
                     "--json"]) == 0
    lines = [r.getMessage() for r in caplog.records if "step classifiers were trained at" in r.getMessage()]
    assert len(lines) == 1 and "trained at 100 Hz" in lines[0] and "runs at 20 Hz" in lines[0]
