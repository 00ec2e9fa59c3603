"""Decisions C51-C53, B177, B178 (notebook-API trial, session 24): ``predict_steps`` on a detector's table
classifies as ``track`` does (C51) and says a rate mismatch as ``track`` does (C52); ``train_user`` says what it
skipped (C53); the API's errors name the parameter beside the CLI flag (B177); classes are plain str (B178).
Simulated users 1750-1755."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.errors import DataError, ModelError
from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.steps import AccelForceStepDetector, AccelStepDetector
from pdrlearn.track.evaluate import match_by_overlap
from pdrlearn.track.gait import STRAIGHT_MAX_RAD
from pdrlearn.track.plasys import model_windows, track_plasys

RATE = "step classifiers were trained at"


@pytest.fixture(scope="module")
def model():
    return train_user([simulate(x, user_seed=1750) for x in ("terrain", "direction", "length")], cv=3)


@pytest.fixture(scope="module")
def scen_d():
    return simulate("D", user_seed=1750, seed=1751)


def _terrain_accuracy(session, table, pred) -> float:
    lab = session.steps.reset_index(drop=True)
    pairs = match_by_overlap(table.reset_index(drop=True), lab, min_iou=0.3)
    return float(np.mean([pred["terrain"].iloc[a] == lab["terrain"].iloc[b] for a, b in pairs]))


@pytest.mark.parametrize("detector", [AccelStepDetector, AccelForceStepDetector])
def test_predict_steps_on_a_detected_table_equals_track(model, scen_d, detector):
    """C51: the trial's "detect, then classify" gave 63 of 68 strides of D 'up' (terrain accuracy 0.250) on the
    detector's own bounds; the table is now classified on track's windows, with track's classes."""
    table = detector().detect(scen_d)
    pred = model.predict_steps(scen_d, table)
    res = track_plasys(scen_d, method="M3", model=model, steps=table)
    assert len(pred) == len(table) == len(res.steps)
    # decision C88 (C91: the default): track's strides turning 15 deg or more take the length class of their
    # measured length, so the length columns are the classifier's (predict_steps') on the straight strides
    straight = np.abs(np.nan_to_num(res.steps["turn_angle_rad"].to_numpy(float))) < STRAIGHT_MAX_RAD
    assert straight.sum() >= len(table) // 2
    for c in [c for c in res.steps.columns if c.startswith("p_")] + ["terrain", "direction", "length_class"]:
        rows = straight if c == "length_class" or c.startswith("p_length_") else slice(None)
        np.testing.assert_array_equal(pred[c].to_numpy()[rows], res.steps[c].to_numpy()[rows], err_msg=c)
    np.testing.assert_allclose(pred["window_start_s"], res.steps["window_start_s"])
    assert _terrain_accuracy(scen_d, table, pred) >= 0.9
    assert all(type(v) is str for c in ("terrain", "direction", "length_class") for v in pred[c])  # B178: not np.str_


def test_track_default_strides_are_predict_steps_classes(model, scen_d):
    """C51: track's own strides (M3's force detector) and predict_steps on that detector's table agree."""
    res = track_plasys(scen_d, method="M3", model=model)
    pred = model.predict_steps(scen_d, AccelForceStepDetector().detect(scen_d))
    np.testing.assert_array_equal(pred["p_terrain_up"].to_numpy(), res.steps["p_terrain_up"].to_numpy())


def test_given_windows_classify_on_the_steps_own_bounds(model, scen_d):
    """C51: windows='given' is the explicit way to classify on the caller's own windows (and the labelled steps'
    default); on a detector's swing windows that is not the model's window and the classes differ."""
    table = AccelStepDetector().detect(scen_d)
    given = model.predict_steps(scen_d, table, windows="given")
    assert "window_start_s" not in given
    assert not np.array_equal(given["p_terrain_up"].to_numpy(), model.predict_steps(scen_d, table)["p_terrain_up"])
    labelled = model.predict_steps(scen_d)  # the session's labelled steps: the windows the model was trained on
    np.testing.assert_array_equal(labelled["p_terrain_up"],
                                  model.predict_steps(scen_d, scen_d.steps, windows="given")["p_terrain_up"])
    win = model_windows(scen_d, table)
    assert len(win) == len(table) and win.attrs["own_bounds"] == 0
    with pytest.raises(DataError, match="windows='stride'; choose one of track, given"):
        model.predict_steps(scen_d, table, windows="stride")


def test_predict_steps_says_a_rate_mismatch_once(model, caplog):
    """C52: a 20 Hz model on a 100 Hz session: predict_steps logged nothing where track warns; now it logs C18's
    line, and track (which calls predict_steps) still gives it once."""
    d100 = simulate("D", user_seed=1752, rate_hz=100, seed=1753)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        model.predict_steps(d100, d100.steps)
    lines = [r.getMessage() for r in caplog.records if RATE in r.getMessage()]
    assert len(lines) == 1 and "trained at 20 / 20 Hz" in lines[0], lines
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        track_plasys(d100, method="M3", model=model)
    assert len([r for r in caplog.records if RATE in r.getMessage()]) == 1


def test_train_user_logs_the_skipped_tasks(real_dir, caplog):
    """C53: train_user returned a model without classifiers and said nothing (the CLI printed the skips)."""
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        m = train_user([read_session(real_dir / "gaitmap_level_left")])
    assert m.tasks == {}
    text = [r.getMessage() for r in caplog.records]
    skips = [t.split(":")[1].strip() for t in text if t.startswith("train: skipped task ")]
    assert skips == ["skipped task terrain", "skipped task direction", "skipped task length"] and len(m.skipped) == 3
    assert sum("no classifier trained" in t for t in text) == 1


def test_cli_train_says_each_skip_once(real_dir, tmp_path, capsys):
    """C53: the CLI no longer prints the skipped tasks itself; train_user's warnings say them once."""
    from pdrlearn.cli import main

    assert main(["train", str(real_dir / "gaitmap_level_left"), "--out", str(tmp_path / "m")]) == 0
    cap = capsys.readouterr()
    assert "skipped task" not in cap.out and "no classifier trained" not in cap.out, cap.out  # printed before C53
    assert cap.err.count("skipped task terrain") == 1 and cap.err.count("no classifier trained") == 1, cap.err


def test_api_errors_name_the_parameter_and_the_flag(scen_d):
    """B177: train_user(methods=["svn"]) said "--methods: unknown method svn"; M3 without a model "pass --model DIR"."""
    with pytest.raises(DataError, match=r"^methods \(--methods\): unknown method svn"):
        train_user([scen_d], methods=["svn"])
    with pytest.raises(ModelError, match=r"pass model= a trained UserModel .*\(CLI --model DIR"):
        track_plasys(scen_d, method="M3")
