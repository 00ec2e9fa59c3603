"""Decision C17: `pdrlearn train` on sessions labelled only level/forward (real foot walks) writes a model with
the user's distance calibration and no classifier; `track --model` applies the gain and falls back to the
no-model rules for the classes it lacks; evaluate/export say what such a model is for."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdrlearn.cli import main

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
TRAIN, HELD_OUT = REAL / "gaitmap_level_left", REAL / "gaitmap_level_right"


@pytest.fixture(scope="module")
def level_model(tmp_path_factory):
    if not (TRAIN.is_dir() and HELD_OUT.is_dir()):
        pytest.skip("datasets/real/gaitmap_level_* not present")
    root = tmp_path_factory.mktemp("level")
    out = root / "model"
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["train", str(TRAIN), "--out", str(out), "--json"])
    assert rc == 0
    return out, json.loads(buf.getvalue())


def test_level_only_labels_train_the_distance_calibration(level_model):
    out, summary = level_model
    assert summary["tasks"] == {}
    skipped = summary["skipped"]
    assert [s.split(":")[0] for s in skipped] == ["task terrain", "task direction", "task length"]
    assert all("\n" not in s for s in skipped)
    cal = summary["distance_calibration"]
    assert cal["reason"] is None and cal["n_strides"] >= 10 and cal["gain"] != 1.0
    assert (out / "manifest.json").is_file()


def test_level_only_model_tracks_a_held_out_walk(level_model, tmp_path, capsys):
    model, summary = level_model
    gain = summary["distance_calibration"]["gain"]
    assert main(["track", "--no-plot", str(HELD_OUT), "--out", str(tmp_path / "none"), "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["track", "--no-plot", str(HELD_OUT), "--model", str(model), "--out", str(tmp_path / "m"),
                 "--json"]) == 0
    cap = capsys.readouterr()
    res = json.loads(cap.out)
    info = res["info"]
    assert info["distance_gain_source"] == "model" and info["distance_gain"] == pytest.approx(gain)
    # one line for the three missing tasks, with what M3 does instead
    lines = [w for w in cap.err.splitlines() if "classifies no" in w]
    assert len(lines) == 1 and "classifies no terrain, direction, length" in lines[0] and "L39" in lines[0]
    assert "length-class bounds" not in cap.err  # no length class: nothing to clamp, nothing to warn about
    # terrain falls back to L39 as without a model: the same altitude (before C17: 0.78 m vs 0.22 m)
    assert res["altitude_change_m"] == pytest.approx(plain["altitude_change_m"], abs=1e-9)
    # the gain lengthens the level strides only
    assert 1.0 < res["distance_m"] / plain["distance_m"] <= gain + 1e-9
    assert res["n_steps"] == plain["n_steps"]
    assert info["out_of_domain"] is None  # no classifier, nothing out of its domain (no "retrain" note)


def test_level_only_model_evaluate_and_export_say_what_it_is(level_model, tmp_path, capsys):
    model, _ = level_model
    assert main(["evaluate", str(model), str(HELD_OUT)]) != 0
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "no trained classifier" in err and "pdrlearn track" in err
    assert main(["export", str(model), "--out", str(tmp_path / "b")]) != 0
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "no trained classifier" in err and "distance calibration" in err
    assert not (tmp_path / "b").exists()


def test_nothing_to_train_without_stride_lengths_either(tmp_path, capsys):
    """Level labels without stride lengths: no classifier and no calibration -> the one-line error says both."""
    if not TRAIN.is_dir():
        pytest.skip("datasets/real/gaitmap_level_left not present")
    import shutil

    import pandas as pd

    s = tmp_path / "s"
    shutil.copytree(TRAIN, s)
    steps = pd.read_csv(s / "steps.csv")
    steps.drop(columns=["length_m"]).to_csv(s / "steps.csv", index=False)
    assert main(["train", str(s), "--out", str(tmp_path / "m")]) != 0
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: train: nothing to train; task terrain") and err.count("\n") == 0
    assert "no distance calibration either: 0 usable strides" in err
    assert not (tmp_path / "m").exists()
    assert main(["train", str(TRAIN), "--out", str(tmp_path / "m"), "--no-distance-calibration"]) != 0
    assert capsys.readouterr().err.strip().endswith("| distance calibration off")


def test_level_only_model_streamed_says_what_it_lacks(level_model, tmp_path, capsys):
    """Review s11: `track --streaming` with a model without a classifier ran silently (no line that the model
    classifies nothing, and the streamed path keeps each stride's raw height change, unlike offline's L39)."""
    model, _ = level_model
    assert main(["track", "--no-plot", str(HELD_OUT), "--model", str(model), "--streaming", "--out",
                 str(tmp_path / "s")]) == 0
    lines = [w for w in capsys.readouterr().err.splitlines() if "classifies no" in w]
    assert len(lines) == 1 and "classifies no terrain, direction, length" in lines[0], lines
    assert "raw height change" in lines[0] and "is level (L39)" not in lines[0]
